/* The light phase of IISPH as a moving boundary (scheme.light_phase: boundary;
 * docs/reference/iisph.md, "A light phase"): which materials are light (lighter than RY_IISPH_LIGHT
 * of the heaviest), the light phase's tolerance, the couplings it does not define and the pockets
 * of light fluid that the heavy fluid encloses, refused at set-up. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/cell_key.h"
#include "schemes/iisph/iisph_internal.h"

/* A pocket of the light phase that the heavy fluid encloses (a bubble) is not held: the heavy
 * phase does not feel the light one's pressure and fills it (docs/reference/iisph.md, "A light
 * phase"). The set-up refuses one. The light particles are joined into bodies (neighbours within
 * 1.5 dx); a body is a pocket when none of its particles lacks lattice neighbours within
 * 1.5 dx (a free surface: fewer than 3/4 of the full lattice's 8 in 2D, 18 in 3D) and none has a
 * wall neighbour. *size receives the size of the first pocket found (0: none), *where one of
 * its particles. */
static ry_status light_pocket(const ry_sim *sim, const iisph *s, size_t *size_out, size_t *where,
                              ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const double dx = sim->dx, reach = 1.5 * dx, r2 = reach * reach * (1 + 1e-9);
    const int full = dim == 3 ? 18 : 8;
    ry_cell_key *k = malloc((n ? n : 1) * sizeof *k);
    uint8_t *seen = calloc(n ? n : 1, 1);
    uint32_t *stack = malloc((n ? n : 1) * sizeof *stack);
    if (!k || !seen || !stack) {
        free(k);
        free(seen);
        free(stack);
        RY_CHECK(err, 0, RY_ERR_NOMEM, "out of memory (light-phase pockets)");
    }
    for (size_t i = 0; i < n; ++i) {
        k[i].i = (uint32_t)i;
        for (int d = 0; d < 3; ++d)
            k[i].c[d] = d < dim ? (int64_t)floor(ps->f[RY_F_X + d][i] / reach) : 0;
    }
    qsort(k, n, sizeof *k, ry_cell_key_cmp);
    size_t found = 0;
    for (size_t seed = 0; seed < n && !found; ++seed) {
        if (!MOBILE[ps->kind[seed]] || !s->light_mat[ps->material[seed]] || seen[seed]) continue;
        size_t top = 0, size = 0;
        int open = 0;
        stack[top++] = (uint32_t)seed;
        seen[seed] = 1;
        while (top) {
            const size_t i = stack[--top];
            ++size;
            int count = 0;
            int64_t c[3] = {0, 0, 0};
            for (int d = 0; d < dim; ++d) c[d] = (int64_t)floor(ps->f[RY_F_X + d][i] / reach);
            for (int a = -1; a <= 1; ++a)
                for (int b = -1; b <= 1; ++b)
                    for (int e = dim == 3 ? -1 : 0; e <= (dim == 3 ? 1 : 0); ++e) {
                        const int64_t q[3] = {c[0] + a, c[1] + b, c[2] + e};
                        for (size_t m = ry_cell_key_find(k, n, q); m < n && ry_cell_same(k[m].c, q);
                             ++m) {
                            const size_t j = k[m].i;
                            if (j == i) continue;
                            double d2 = 0;
                            for (int d = 0; d < dim; ++d) {
                                const double u = ps->f[RY_F_X + d][i] - ps->f[RY_F_X + d][j];
                                d2 += u * u;
                            }
                            if (d2 > r2) continue;
                            ++count;
                            const int light = MOBILE[ps->kind[j]] && s->light_mat[ps->material[j]];
                            if (!MOBILE[ps->kind[j]]) open = 1; /* a wall: not enclosed by fluid */
                            if (light && !seen[j]) {
                                seen[j] = 1;
                                stack[top++] = (uint32_t)j;
                            }
                        }
                    }
            if (4 * count < 3 * full) open = 1;
        }
        if (!open) {
            found = size;
            *where = seed;
        }
    }
    free(k);
    free(seen);
    free(stack);
    *size_out = found;
    return RY_OK;
}

/* scheme.light_phase: with boundary (the default) a material lighter than RY_IISPH_LIGHT of the
 * heaviest is light, and the light and heavy phases are solved as two incompressible fluids,
 * each with the other as its boundary: the heavy phase does not see the light one (its
 * interface is a free surface, p >= 0), the light phase sees the heavy particles as moving
 * walls with their velocity and its own pressure extrapolated onto them (docs/reference/iisph.md,
 * "A light phase"). The couplings this does not define are refused. */
ry_status iisph_light_phase_init(ry_sim *sim, iisph *s, ry_case *c, ry_error *err) {
    static const char *const modes[] = {"coupled", "boundary", NULL};
    int boundary;
    RY_TRY(ry_case_choice(c, "scheme.light_phase", "boundary", modes, &boundary, err));
    s->light_mat = calloc((size_t)sim->nmat, 1);
    RY_CHECK(err, s->light_mat != NULL, RY_ERR_NOMEM, "out of memory");
    /* over the materials of the fluid, and of what inlets and outlets carry */
    const ry_particles *ps = &sim->ps;
    double rmax = 0;
    for (size_t i = 0; i < ps->n; ++i)
        if (MOBILE[ps->kind[i]] || ps->kind[i] == RY_KIND_INLET)
            rmax = fmax(rmax, sim->mat[ps->material[i]].density);
    for (int m = 0; m < sim->nmat; ++m)
        s->light_mat[m] = boundary && sim->mat[m].density < RY_IISPH_LIGHT * rmax;
    for (size_t i = 0; i < ps->n; ++i)
        if (MOBILE[ps->kind[i]] || ps->kind[i] == RY_KIND_INLET)
            s->light_on |= s->light_mat[ps->material[i]];
    /* The light phase's error does not reach the heavy phase: a looser tolerance (10 times the
     * heavy one by default) took the dam break under air from 15 to 5 iterations per step with
     * the same front and the same air speeds (docs/reference/iisph.md). */
    double ltol = fmin(10.0 * s->tol, 0.1);
    RY_TRY(ry_case_double(c, "scheme.light_tolerance", &ltol, 1e-7, 0.1, &s->light_tol, err));
    if (!s->light_on) return RY_OK;
    int light = 0;
    while (!s->light_mat[light]) ++light;
    const char *key = s->st.model != RY_ST_NONE ? "surface_tension.model"
                      : s->implicit             ? "scheme.viscosity"
                                                : NULL;
    if (!key && s->rheo.on) key = "scheme.light_phase";
    if (!key) {
        size_t at = 0, pocket = 0;
        RY_TRY(light_pocket(sim, s, &pocket, &at, err));
        char where[256];
        RY_CHECK(err, pocket == 0, RY_ERR_INPUT,
                 "%s: key 'scheme.light_phase': %zu particles of the light material '%s' around "
                 "(%g, %g, %g) lie wholly inside the heavy fluid, a pocket the light phase does "
                 "not hold (the heavy phase fills it; docs/reference/iisph.md, \"A light phase\")",
                 ry_case_where(c, "scheme.light_phase", where, sizeof where), pocket,
                 sim->mat[ps->material[at]].name, ps->f[RY_F_X][at], ps->f[RY_F_Y][at],
                 sim->dim == 3 ? ps->f[RY_F_Z][at] : 0.0);
    }
    char where[256];
    RY_CHECK(err, key == NULL, RY_ERR_INPUT,
             "%s: key '%s': not available with a light phase (material '%s' is lighter than %g "
             "of the heaviest, and scheme.light_phase is boundary%s); set scheme.light_phase: "
             "coupled",
             ry_case_where(c, key ? key : "scheme", where, sizeof where), key ? key : "",
             sim->mat[light].name, RY_IISPH_LIGHT,
             key && strcmp(key, "scheme.light_phase") == 0 ? ", with a non-Newtonian material"
                                                           : "");
    return RY_OK;
}
