/* Squared distances to eight particles at a time with AVX-512 (where the compiler targets it:
 * the default build optimises for the building machine, -march=native). The neighbour search
 * and the MPS pair lists keep the pairs within a radius of each particle; these helpers give
 * them the same distances, in the same rounding, as their scalar loops, and store the kept
 * entries contiguously with a compressing store instead of a branch or a counted store per
 * entry. */
#ifndef RYUSHI_NEIGHBOR_R2_SIMD_H
#define RYUSHI_NEIGHBOR_R2_SIMD_H

#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512BW__)
#define RY_R2_SIMD 1
#include <immintrin.h>
#include <stddef.h>
#include <stdint.h>

/* The lanes of the first min(left, 8) entries. */
static inline __mmask8 ry_simd_lanes(size_t left) {
    return left >= 8 ? (__mmask8)0xff : (__mmask8)((1u << left) - 1u);
}

/* |x_j - x_i|^2 of the particles idx (3D, in the lanes of m; the others 0), summed as the
 * scalar loops do, ((dx^2 + dy^2) + dz^2) without fused multiply-adds: the same bits. */
static inline __m512d ry_simd_r2(const double *const x[3], const __m512d xi[3], __m256i idx,
                                 __mmask8 m) {
    const __m512d zero = _mm512_setzero_pd();
    __m512d r2 = zero;
    for (int d = 0; d < 3; ++d) {
        const __m512d e = _mm512_sub_pd(_mm512_mask_i32gather_pd(zero, m, idx, x[d], 8), xi[d]);
        r2 = d == 0 ? _mm512_mul_pd(e, e) : _mm512_add_pd(r2, _mm512_mul_pd(e, e));
    }
    return r2;
}

/* Appends the indices idx and values v of the lanes in m to oj and ov; returns their count. */
static inline size_t ry_simd_append(__mmask8 m, __m256i idx, __m512d v, uint32_t *oj, double *ov) {
    if (ov) _mm512_mask_compressstoreu_pd(ov, m, v);
    _mm256_mask_compressstoreu_epi32(oj, m, idx);
    return (size_t)__builtin_popcount((unsigned)m);
}
#endif

#endif
