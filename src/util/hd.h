/* RY_HD marks a function that a GPU driver compiles for the device as well as the host: empty
 * in a C or C++ build for the CPU, __host__ __device__ under CUDA. Functions marked with it are
 * written in the common subset of C and C++ (no GCC vector types, no variable-length arrays, no
 * designated initializers, no restrict) and call only other RY_HD functions and <math.h>. */
#ifndef RY_UTIL_HD_H
#define RY_UTIL_HD_H

#if defined(__CUDACC__)
#define RY_HD __host__ __device__
#else
#define RY_HD
#endif

#endif
