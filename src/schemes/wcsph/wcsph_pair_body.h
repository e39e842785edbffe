/* The body of wcsph_pair.h in the precision RY_REAL, its names suffixed by RY_PAIR (no include
 * guard: included once per precision). Constants are written as RY_C(...), of type RY_REAL,
 * so that the single-precision pair stays in floats. */

/* Particle i. */
typedef struct RY_PAIR(wc_pair_i) {
    RY_REAL ux, uy, uz;    /* velocity */
    RY_REAL drho;          /* rho_i - rho_ref */
    RY_REAL rho2;          /* 2 rho_ref + drho: rho_i + rho_j = rho2 + drho_j */
    RY_REAL prho2;         /* p_i / rho_i^2 */
    RY_REAL mu;            /* dynamic viscosity */
    RY_REAL inv_rho;       /* 1 / rho_i */
    RY_REAL cs;            /* sound speed */
    RY_REAL fgx, fgy, fgz; /* rho0 g / c0^2 (Fourtakas et al. 2019), 0 otherwise */
} RY_PAIR(wc_pair_i);

/* The run's constants. */
typedef struct RY_PAIR(wc_pair_k) {
    RY_REAL h, eta2, alpha, beta; /* h, eta^2 = 0.01 h^2, the artificial viscosity's */
    RY_REAL rep_d, rep_r02;       /* wall repulsion: strength D, radius r0^2 */
} RY_PAIR(wc_pair_k);

/* Neighbour j. */
typedef struct RY_PAIR(wc_pair_j) {
    RY_REAL ux, uy, uz;    /* velocity */
    RY_REAL ugx, ugy, ugz; /* velocity seen by viscous terms */
    RY_REAL drho;          /* rho_j - rho_ref */
    RY_REAL prho2, vol, mu, cs, mass;
    RY_REAL fluid; /* 1 for fluid and outlet particles, 0 for walls */
    RY_REAL visc;  /* viscous coupling: 1, or the wall's factor */
} RY_PAIR(wc_pair_j);

/* The pair's share of particle i's rates: acceleration, velocity divergence (times rho_i:
 * the continuity term), the density diffusion sum (subtracted, times 2 delta h c0) and the
 * energy rate. */
typedef struct RY_PAIR(wc_pair_out) {
    RY_REAL ax, ay, az, div, diff, de;
} RY_PAIR(wc_pair_out);

/* Monaghan (1994) wall repulsion D ((r0/r)^12 - (r0/r)^4) / r^2 (it multiplies x_ij) for a
 * pair with `on` set (a wall particle within r0), 0 otherwise; (r0/r)^2 is capped at 1e3 so
 * that single precision cannot overflow. Written without branches for SIMD loops. */
RY_HD static inline RY_REAL RY_PAIR(wc_repulsion)(const int on, RY_REAL r2, RY_REAL r02,
                                                  RY_REAL D) {
    const RY_REAL inv_r2 = RY_C(1.0) / (on ? r2 : RY_C(1.0));
    RY_REAL q2 = r02 * inv_r2;
    q2 = q2 < RY_C(1e3) ? q2 : RY_C(1e3);
    const RY_REAL q4 = q2 * q2;
    return on ? D * (q4 * q4 * q4 - q4) * inv_r2 : RY_C(0.0);
}

/* The pair term. dim (2 or 3), energy and repulse (the energy equation, wall repulsion) are
 * literals at each call, so that the unused terms compile away. */
RY_HD static inline RY_PAIR(wc_pair_out)
    RY_PAIR(wc_pair)(const RY_PAIR(wc_pair_k) * K, const RY_PAIR(wc_pair_i) * I,
                     const RY_PAIR(wc_pair_j) * J, RY_REAL dx, RY_REAL dy, RY_REAL dz, RY_REAL r2,
                     RY_REAL fw, const int dim, const int energy, const int repulse) {
    const RY_REAL zero = RY_C(0.0);
    const RY_REAL vx = I->ux - J->ugx, vy = I->uy - J->ugy, vz = dim > 2 ? I->uz - J->ugz : zero;
    RY_REAL vdx = vx * dx + vy * dy;
    if (dim > 2) vdx += vz * dz;
    RY_REAL vdw = (I->ux - J->ux) * dx + (I->uy - J->uy) * dy;
    if (dim > 2) vdw += (I->uz - J->uz) * dz;
    const RY_REAL ieta = RY_C(1.0) / (r2 + K->eta2);
    /* Monaghan's artificial viscosity, active for approaching pairs only. */
    const RY_REAL pi_ij = RY_PAIR_AV(vdx, ieta, K->h, RY_C(0.5) * (I->cs + J->cs),
                                     I->rho2 + J->drho, K->alpha, K->beta);
    const RY_REAL pterm = I->prho2 + J->prho2 + pi_ij;
    RY_REAL fp = -J->mass * pterm;
    /* The Morris weight L_ij, and mu_ij L_ij / rho_i (a wall takes the fluid's viscosity). */
    const RY_REAL lw = fw * r2 * ieta * J->vol;
    const RY_REAL mu_j = J->fluid * J->mu + (RY_C(1.0) - J->fluid) * I->mu;
    const RY_REAL fv = J->visc * (I->mu + mu_j) * I->inv_rho * lw;
    fp *= fw;
    if (repulse)
        fp += RY_PAIR(wc_repulsion)((J->fluid == zero) & (r2 < K->rep_r02) & (r2 > zero), r2,
                                    K->rep_r02, K->rep_d);
    RY_PAIR(wc_pair_out) o;
    o.ax = fp * dx + fv * vx;
    o.ay = fp * dy + fv * vy;
    o.az = dim > 2 ? fp * dz + fv * vz : zero;
    o.div = J->vol * vdw * fw;
    RY_REAL psi = J->drho - I->drho;
    if (dim > 2)
        psi += I->fgx * dx + I->fgy * dy + I->fgz * dz;
    else
        psi += I->fgx * dx + I->fgy * dy;
    o.diff = J->fluid * psi * lw;
    o.de = energy ? RY_C(0.5) * J->mass * pterm * vdx * fw : zero;
    return o;
}
