/* Internal to src/solid: the state of the scheme `solid`, shared by the total-Lagrangian
 * (solid.c) and updated-Lagrangian (updated.c) formulations. */
#ifndef RYUSHI_SOLID_INTERNAL_H
#define RYUSHI_SOLID_INTERNAL_H

#include "ryushi/beam.h"
#include "schemes/solid/solid.h"

enum { LOAD_NONE, LOAD_END, LOAD_UNIFORM, LOAD_LINEAR, LOAD_COSINE };
enum { RELAX_NONE, RELAX_KINETIC, RELAX_VISCOUS };
enum { PLANE_STRESS, PLANE_STRAIN };
enum { CORR_NONE, CORR_LINEAR, CORR_QUADRATIC };
enum { CLAMP_FACE, CLAMP_BLOCK };
enum { INTEGRATION_NODAL, INTEGRATION_GRADIENT };

/* Loops over fewer particles run on one thread: a step of a small beam takes microseconds, less
 * than a thread barrier on a busy machine. (Every particle sums only into itself, so the
 * results do not depend on this.) */
enum { RY_SOLID_PARALLEL_MIN = 8192 };
#define RY_SOLID_INLINE static inline __attribute__((always_inline))

/* A pass over the particles: the statement row2 or row3 (a row function called with the
 * literal dimension 2 or 3) for every particle i. The OpenMP region holds the calls, not the
 * other way round: a region is outlined before constants reach it, so a region inside a
 * function called with 2 and with 3 would serve both, the dimension read at run time. */
/* clang-format off */
#define RY_SOLID_ROWS(sim, i, row2, row3)                                                          \
    do {                                                                                           \
        const size_t ry_rows_n = (sim)->ps.n;                                                      \
        const int ry_rows_dim = (sim)->dim;                                                        \
        _Pragma("omp parallel for schedule(static) if (ry_rows_n >= RY_SOLID_PARALLEL_MIN)")       \
        for (size_t i = 0; i < ry_rows_n; ++i) {                                                   \
            if (ry_rows_dim == 2)                                                                  \
                row2;                                                                              \
            else                                                                                   \
                row3;                                                                              \
        }                                                                                          \
    } while (0)
/* clang-format on */

typedef struct solid {
    int correction, plane, load, relax, clamp, integration;
    double load_q, load_dir[3], damping, residual_tol;
    double *lam, *mu, *E; /* per material (lambda* in plane stress), Young's modulus */
    double hourglass;     /* hourglass-control coefficient alpha */
    double c_max;    /* fastest wave speed (of the free particles' materials with relaxation) */
    double *modulus; /* per material: P-wave modulus lambda + 2 mu */
    double *mscale;  /* per particle: fictitious-mass factor of dynamic relaxation */
    double *hgc;     /* per pair: hourglass stiffness (E_i + E_j)/2 V_j W_ij / |X_ij|^2 */
    int f_X[3], f_fext[3], f_u[3], f_psi;
    /* reference neighbour list and per-pair kernel gradients */
    ry_cell_list cells;
    ry_nlist nl;
    double *G;   /* dim per pair: gradient weights, grad f_i = sum_j G_ij (f_j - f_i) */
    double *H;   /* dim^2 per pair: second-derivative weights (integration: gradient) */
    double *Q;   /* 27 per particle: Q_k = (cell^2/12) F T_k, the strain-gradient stresses */
    size_t *rev; /* per pair ij: the index of the pair ji */
    double *vol; /* reference volume per particle */
    double *A;   /* 9 per particle: first Piola-Kirchhoff stress P_i */
    double *F;   /* 9 per particle: deformation gradient */
    double *r2;  /* squared net force per particle */
    int built, have_forces;
    double residual, ke_prev;
    long peaks;          /* kinetic-damping resets */
    double probe_dir[3]; /* direction of tip_deflection: the load, else the initial velocity */
    /* updated-Lagrangian formulation */
    int ul;
    double av_alpha, av_beta; /* Monaghan artificial viscosity */
    double as_eps, as_n;      /* artificial stress: epsilon, exponent n of f = (W(r)/W(dx))^n */
    double *K;                /* per material: bulk modulus of the dim-dimensional model */
    int f_S[6];               /* deviatoric stress: xx, yy, zz, xy, xz, yz (2D: xx, yy, xy) */
    double *Lc;  /* 9 per particle: kernel-gradient correction (identity with correction none) */
    double *sig; /* 9 per particle: Cauchy stress sigma = -P I + S */
    double *Ras; /* 9 per particle: artificial stress R_i (divided by rho_i^2) */
    size_t cap_pair; /* capacity of G and rev (quadratic correction; G, rev, vol reused) */
    long rev_search; /* list (sim->nl_generation) that rev was built for */
} solid;

/* Acceleration of free particle i from its internal force f (NULL for a clamped particle,
 * whose acceleration is zero), the load and gravity, with the fictitious-mass factor of
 * dynamic relaxation; keeps the squared net force for the residual. */
void ry_solid_accelerate(ry_sim *sim, solid *s, size_t i, const double *f, int dim);
/* Relative residual of the net forces kept by ry_solid_accelerate (particle order). */
void ry_solid_residual_update(ry_sim *sim, solid *s);

/* Index of the pair (j, i) in a symmetric neighbour list with sorted rows. */
size_t ry_solid_reverse_pair(const ry_nlist *nl, size_t i, size_t j);

/* Total-Lagrangian formulation (total.c): the reference configuration's neighbour list, kernel
 * gradients and corrections (built once), and the stresses, accelerations and residual for the
 * current positions. */
ry_status ry_solid_tl_build(ry_sim *sim, solid *s, ry_error *err);
void ry_solid_tl_forces(ry_sim *sim, solid *s);

/* Updated-Lagrangian formulation (updated.c): reads its keys, registers its fields and
 * allocates its arrays; evaluate brings the neighbour list up to date, advances density and
 * deviatoric stress by dt (0 on the first call) with the velocities and positions now current,
 * and computes the accelerations and the residual. */
ry_status ry_solid_ul_init(ry_sim *sim, ry_case *c, solid *s, ry_error *err);
ry_status ry_solid_ul_evaluate(ry_sim *sim, solid *s, double dt, ry_error *err);
void ry_solid_ul_free(solid *s);

#endif
