/* Measured quantities: the columns of series.csv. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "measure/probes_internal.h"
#include "ryushi/rheology.h"
#include "ryushi/sim.h"
#include "ryushi/open_boundary.h"
#include "ryushi/probes.h"

static ry_status probe_mass(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    const ry_particles *ps = &sim->ps;
    double m = 0;
    for (size_t i = 0; i < ps->n; ++i)
        if (ps->kind[i] == RY_KIND_FLUID) m += ps->f[RY_F_MASS][i];
    *v = m;
    return RY_OK;
}

static ry_status probe_kinetic(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    *v = ry_particles_kinetic_energy(&sim->ps, sim->dim, RY_KIND_FLUID, NULL);
    return RY_OK;
}

static ry_status probe_shape_m4(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    *v = ry_particles_shape_m4(&sim->ps, sim->dim, RY_KIND_FLUID, sim->dx);
    return RY_OK;
}

static ry_status probe_shape_p2(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    *v = ry_particles_shape_p2(&sim->ps, sim->dim, RY_KIND_FLUID, sim->dx);
    return RY_OK;
}

static ry_status probe_max_speed(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    const ry_particles *ps = &sim->ps;
    double m = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        double u2 = 0;
        for (int d = 0; d < sim->dim; ++d) u2 += ps->f[RY_F_VX + d][i] * ps->f[RY_F_VX + d][i];
        m = fmax(m, u2);
    }
    *v = sqrt(m);
    return RY_OK;
}

/* The largest size of the polymer stress, |tau| = sqrt(tau : tau), over the fluid. */
static ry_status probe_max_polymer_stress(const ry_sim *sim, double *v, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const int nt = ry_tau_count(sim->dim);
    int f[6];
    for (int k = 0; k < nt; ++k) {
        f[k] = ry_particles_field(ps, ry_tau_name(sim->dim, k));
        RY_CHECK(err, f[k] >= 0, RY_ERR_INPUT,
                 "measurement 'max_polymer_stress' needs a visco-elastic material (rheology "
                 "model oldroyd_b or giesekus)");
    }
    double m = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        double t[6];
        for (int k = 0; k < nt; ++k) t[k] = ps->f[f[k]][i];
        m = fmax(m, ry_tau_norm2(sim->dim, t));
    }
    *v = sqrt(m);
    return RY_OK;
}

static ry_status probe_outside(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    *v = (double)ry_sim_count_outside(sim);
    return RY_OK;
}

/* The densest material of the fluid particles (of a liquid under air, the liquid); 0 without
 * fluid. */
static int densest_material(const ry_sim *sim) {
    const ry_particles *ps = &sim->ps;
    int dense = -1;
    for (size_t i = 0; i < ps->n; ++i)
        if (ps->kind[i] == RY_KIND_FLUID &&
            (dense < 0 || sim->mat[ps->material[i]].density > sim->mat[dense].density))
            dense = ps->material[i];
    return dense < 0 ? 0 : dense;
}

/* Surge front: the leading edge (largest x) of the fluid body on the floor (of the densest fluid
 * material: the water under air). Fluid particles within 3 spacings of the lowest fluid particle
 * are binned along x in bins one spacing wide; starting from the leftmost occupied bin, the body
 * continues while gaps are at most one empty bin. Spray ahead of the body (separated by two or
 * more empty bins) does not count. The front is the largest x of a particle in the body plus
 * half a spacing (the particle's extent). */
static ry_status probe_front_x(const ry_sim *sim, double *v, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const int up = sim->dim - 1;
    double ymin = INFINITY, xmin = INFINITY, xmax = -INFINITY;
    const int dense = densest_material(sim);
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || ps->material[i] != dense) continue;
        ymin = fmin(ymin, ps->f[RY_F_X + up][i]);
    }
    if (!isfinite(ymin)) {
        *v = NAN;
        return RY_OK;
    }
    double band = ymin + 3 * sim->dx;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || ps->material[i] != dense ||
            ps->f[RY_F_X + up][i] > band)
            continue;
        xmin = fmin(xmin, ps->f[RY_F_X][i]);
        xmax = fmax(xmax, ps->f[RY_F_X][i]);
    }
    size_t nb = (size_t)((xmax - xmin) / sim->dx) + 1;
    double *edge = malloc(nb * sizeof *edge);
    RY_CHECK(err, edge != NULL, RY_ERR_NOMEM, "out of memory (front_x)");
    for (size_t b = 0; b < nb; ++b) edge[b] = -INFINITY;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || ps->material[i] != dense ||
            ps->f[RY_F_X + up][i] > band)
            continue;
        double x = ps->f[RY_F_X][i];
        size_t b = (size_t)((x - xmin) / sim->dx);
        if (b >= nb) b = nb - 1;
        edge[b] = fmax(edge[b], x);
    }
    double front = edge[0];
    int gap = 0;
    for (size_t b = 1; b < nb; ++b) {
        if (edge[b] == -INFINITY) {
            if (++gap >= 2) break;
        } else {
            gap = 0;
            front = edge[b];
        }
    }
    free(edge);
    *v = front + 0.5 * sim->dx;
    return RY_OK;
}

/* Fluid particles inside a wall: inside the lattice cell (a square or cube of side dx centred
 * on the particle) of some wall particle, i.e. within dx/2 of it in every direction. The wall
 * surface lies half a spacing beyond the outer wall layer, so this counts exactly the fluid
 * particles that crossed it. */
static ry_status probe_in_wall(const ry_sim *sim, double *v, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    *v = 0;
    const double lim = 0.5 * sim->dx * (1 - 1e-9);
    /* The run's own cells where they serve (a pair within lim in every direction lies within
     * lim sqrt(dim)); else cells of two spacings: an eighth of the cells of one, whose start
     * offsets would take more memory than the particles on a fine 3D lattice. */
    double drift = 0;
    const ry_cell_list *run = ry_sim_cells_within(sim, lim * sqrt((double)dim), &drift);
    ry_cell_list own;
    const double *x[3];
    int per[3], periodic = 0;
    for (int d = 0; d < 3; ++d) {
        per[d] = d < dim && sim->box.periodic[d];
        periodic |= per[d];
    }
    ry_particles_coords(ps, x);
    if (!run) RY_TRY(ry_probe_current_cells(sim, 2.0 * sim->dx, &own, x, per, err));
    const ry_cell_list *cl = run ? run : &own;
    /* The cells binned from positions within lim + drift of a particle in every direction
     * (the binning is monotone in the position); the 3 x 3 (x 3) block in periodic domains. */
    const double reach = lim + drift;
    size_t count = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : count)
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        size_t cells[27];
        int nc = 0;
        if (periodic) {
            nc = ry_cells_neighbours(cl, per, cl->cell_of[i], cells);
        } else {
            long lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
            for (int d = 0; d < dim; ++d) {
                const double inv = 1.0 / cl->cell[d];
                const double a = floor((x[d][i] - reach - cl->lo[d]) * inv);
                const double b = floor((x[d][i] + reach - cl->lo[d]) * inv);
                const long top = cl->ncell[d] - 1;
                lo[d] = a < 0.0 ? 0 : a > (double)top ? top : (long)a;
                hi[d] = b < 0.0 ? 0 : b > (double)top ? top : (long)b;
            }
            for (long kz = lo[2]; kz <= hi[2]; ++kz)
                for (long ky = lo[1]; ky <= hi[1]; ++ky)
                    for (long kx = lo[0]; kx <= hi[0]; ++kx)
                        if (nc < 27)
                            cells[nc++] = ((size_t)kz * (size_t)cl->ncell[1] + (size_t)ky) *
                                              (size_t)cl->ncell[0] +
                                          (size_t)kx;
        }
        int inside = 0;
        for (int c = 0; c < nc && !inside; ++c)
            for (size_t q = cl->start[cells[c]]; q < cl->start[cells[c] + 1] && !inside; ++q) {
                const uint32_t j = cl->order[q];
                if (ps->kind[j] != RY_KIND_WALL) continue;
                double dx[3] = {0, 0, 0}, dmax = 0;
                for (int d = 0; d < dim; ++d) dx[d] = x[d][i] - x[d][j];
                ry_box_min_image(&sim->box, dx);
                for (int d = 0; d < dim; ++d) dmax = fmax(dmax, fabs(dx[d]));
                inside = dmax < lim;
            }
        count += (size_t)inside;
    }
    if (!run) ry_cells_free(&own);
    *v = (double)count;
    return RY_OK;
}

/* Droplet at a nozzle (case section `droplet`: material and tip height along the last axis,
 * "up"): the particles of that material (fluid) form bodies, two particles being connected
 * when closer than 1.5 spacings (union-find over a cell search of its own). The attached body
 * is the union of the bodies that reach the nozzle (a particle above half a spacing under the
 * tip: a droplet whose top still touches the tip hangs from it, even where a void in a narrow
 * bore parts it from the liquid above, as in the coarse 3D tank's bore of 2 x 2 particles,
 * docs/reference/mps.md). Values:
 * [0] length: the tip less the attached body's lowest point (its lowest particle less half a
 * spacing), 0 when nothing hangs below the tip; [1] width: the largest horizontal extent of the
 * attached body below the tip plus one spacing (0 if none); [2] length / width (NAN if no width);
 * [3] detached: 1 when a body of at least 10 particles lies wholly below the tip, else 0;
 * [4] volume: the attached body's particles below the tip times the particle volume dx^dim
 * (a droplet that leaves the tip sideways or upwards, a remnant still hanging, shows here);
 * [5] offset: the horizontal distance from the nozzle's axis (droplet.axis) to the centroid of
 * those particles (0 if none): a droplet that slides off the tip moves away from the axis, one
 * that necks stays on it. */
static uint32_t uf_find(uint32_t *parent, uint32_t a) {
    while (parent[a] != a) {
        parent[a] = parent[parent[a]];
        a = parent[a];
    }
    return a;
}

static ry_status droplet_measure(const ry_sim *sim, double out[6], ry_error *err) {
    RY_CHECK(err, sim->droplet_material >= 0, RY_ERR_INPUT,
             "the droplet measurements need the case section 'droplet' (material, tip)");
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int up = sim->dim - 1, mat = sim->droplet_material;
    const double tip = sim->droplet_tip, r2max = 2.25 * sim->dx * sim->dx;
    uint32_t *parent = malloc((n + 1) * sizeof *parent);
    uint8_t *flags = calloc(n + 1, 1); /* per root: 1 reaches the nozzle */
    size_t *count = calloc(n + 1, sizeof *count);
    if (!parent || !flags || !count) {
        free(parent);
        free(flags);
        free(count);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory (droplet measurements)");
    }
    ry_cell_list cl;
    const double *x[3];
    int per[3];
    ry_status st = ry_probe_current_cells(sim, 1.5 * sim->dx, &cl, x, per, err);
    if (st != RY_OK) {
        free(parent);
        free(flags);
        free(count);
        return st;
    }
    for (size_t i = 0; i < n; ++i) parent[i] = (uint32_t)i;
#define IN_DROP(i) (ps->kind[i] == RY_KIND_FLUID && ps->material[i] == mat)
    for (size_t i = 0; i < n; ++i) {
        if (!IN_DROP(i)) continue;
        size_t cells[27];
        const int nc = ry_cells_neighbours(&cl, per, cl.cell_of[i], cells);
        for (int c = 0; c < nc; ++c)
            for (size_t q = cl.start[cells[c]]; q < cl.start[cells[c] + 1]; ++q) {
                const uint32_t j = cl.order[q];
                if (j <= i || !IN_DROP(j)) continue;
                double dx[3] = {0, 0, 0}, r2 = 0;
                for (int d = 0; d < sim->dim; ++d) dx[d] = x[d][i] - x[d][j];
                ry_box_min_image(&sim->box, dx);
                for (int d = 0; d < sim->dim; ++d) r2 += dx[d] * dx[d];
                if (r2 < r2max) {
                    const uint32_t a = uf_find(parent, (uint32_t)i), b = uf_find(parent, j);
                    if (a != b) parent[a] = b;
                }
            }
    }
    ry_cells_free(&cl);
    for (size_t i = 0; i < n; ++i)
        if (IN_DROP(i)) {
            const uint32_t r = uf_find(parent, (uint32_t)i);
            count[r]++;
            if (x[up][i] >= tip - 0.5 * sim->dx) flags[r] = 1;
        }
    double low = INFINITY, lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY},
           sum[2] = {0, 0};
    int detached = 0;
    size_t below = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!IN_DROP(i)) continue;
        const uint32_t r = uf_find(parent, (uint32_t)i);
        if (!flags[r]) {
            detached |= count[r] >= 10;
            continue;
        }
        if (x[up][i] >= tip) continue;
        ++below;
        low = fmin(low, x[up][i]);
        for (int d = 0; d < up; ++d) {
            lo[d] = fmin(lo[d], x[d][i]);
            hi[d] = fmax(hi[d], x[d][i]);
            sum[d] += x[d][i];
        }
    }
#undef IN_DROP
    free(parent);
    free(flags);
    free(count);
    double width = 0;
    for (int d = 0; d < up; ++d)
        if (hi[d] >= lo[d]) width = fmax(width, hi[d] - lo[d] + sim->dx);
    out[0] = isfinite(low) ? fmax(tip - (low - 0.5 * sim->dx), 0.0) : 0.0;
    out[1] = width;
    out[2] = width > 0 ? out[0] / width : NAN;
    out[3] = detached;
    out[4] = (double)below * pow(sim->dx, sim->dim);
    double off2 = 0;
    for (int d = 0; d < up && below; ++d) {
        const double e = sum[d] / (double)below - sim->droplet_axis[d];
        off2 += e * e;
    }
    out[5] = sqrt(off2);
    return RY_OK;
}

/* One of droplet_measure's values. */
static ry_status droplet_value(const ry_sim *sim, int k, double *v, ry_error *err) {
    double o[6];
    RY_TRY(droplet_measure(sim, o, err));
    *v = o[k];
    return RY_OK;
}
static ry_status probe_droplet_length(const ry_sim *sim, double *v, ry_error *err) {
    return droplet_value(sim, 0, v, err);
}
static ry_status probe_droplet_width(const ry_sim *sim, double *v, ry_error *err) {
    return droplet_value(sim, 1, v, err);
}
static ry_status probe_droplet_aspect(const ry_sim *sim, double *v, ry_error *err) {
    return droplet_value(sim, 2, v, err);
}
static ry_status probe_droplet_detached(const ry_sim *sim, double *v, ry_error *err) {
    return droplet_value(sim, 3, v, err);
}
static ry_status probe_droplet_volume(const ry_sim *sim, double *v, ry_error *err) {
    return droplet_value(sim, 4, v, err);
}
static ry_status probe_droplet_offset(const ry_sim *sim, double *v, ry_error *err) {
    return droplet_value(sim, 5, v, err);
}

static ry_status probe_inflow(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    *v = ry_open_volume(sim, RY_OPEN_INLET);
    return RY_OK;
}

static ry_status probe_outflow(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    *v = ry_open_volume(sim, RY_OPEN_OUTLET);
    return RY_OK;
}

static ry_status probe_fluid_particles(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    size_t k = 0;
    for (size_t i = 0; i < sim->ps.n; ++i) k += sim->ps.kind[i] == RY_KIND_FLUID;
    *v = (double)k;
    return RY_OK;
}

/* Filling: fluid particles of the injected fluid (the second material; the first is the one in
 * place at the start) over all fluid particles. */
static ry_status probe_filled_fraction(const ry_sim *sim, double *v, ry_error *err) {
    RY_CHECK(err, sim->nmat >= 2, RY_ERR_INPUT,
             "measurement 'filled_fraction' needs two materials (the second is the injected one)");
    const ry_particles *ps = &sim->ps;
    size_t nf = 0, ni = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        ++nf;
        ni += ps->material[i] == 1;
    }
    *v = nf ? (double)ni / (double)nf : 0.0;
    return RY_OK;
}

/* The injected fluid kept: its fluid particles' volume (count x dx^dim) over the volume that came
 * in through the inlets; 1 until it reaches an outlet (the eye: the oil at the drainage). */
static ry_status probe_injected_kept(const ry_sim *sim, double *v, ry_error *err) {
    RY_CHECK(err, sim->nmat >= 2, RY_ERR_INPUT,
             "measurement 'injected_kept' needs two materials (the second is the injected one)");
    const ry_particles *ps = &sim->ps;
    size_t ni = 0;
    for (size_t i = 0; i < ps->n; ++i) ni += ps->kind[i] == RY_KIND_FLUID && ps->material[i] == 1;
    const double in = ry_open_volume(sim, RY_OPEN_INLET);
    *v = in > 0 ? (double)ni * pow(sim->dx, sim->dim) / in : 1.0;
    return RY_OK;
}

ry_status ry_probe_eval(const ry_probe *p, const ry_sim *sim, double *value, ry_error *err) {
    return p->eval ? p->eval(sim, value, err) : p->eval_item(sim, p->item, value, err);
}

/* A standing wave (2D): the top surface of the densest fluid material (with air above water:
 * the water), in columns one spacing wide across its x-range widened by half a spacing each
 * side (width W from x_lo), each column's height h_b its highest particle; the amplitude of the
 * mode a cos(2 pi (x - x_lo) / W), a = (2 / N) sum_b h_b cos(2 pi (b + 1/2) / N) over the N
 * columns. a > 0: the surface is higher at x_lo than at the middle. */
static ry_status probe_wave_amplitude(const ry_sim *sim, double *v, ry_error *err) {
    RY_CHECK(err, sim->dim == 2, RY_ERR_INPUT, "measurement 'wave_amplitude' needs dimension 2");
    const ry_particles *ps = &sim->ps;
    const int dense = densest_material(sim);
    double xlo = INFINITY, xhi = -INFINITY;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || ps->material[i] != dense) continue;
        xlo = fmin(xlo, ps->f[RY_F_X][i]);
        xhi = fmax(xhi, ps->f[RY_F_X][i]);
    }
    *v = 0;
    if (!(xhi >= xlo)) return RY_OK;
    const size_t nb = (size_t)floor((xhi - xlo) / sim->dx + 0.5) + 1;
    double *h = malloc(nb * sizeof *h);
    RY_CHECK(err, h != NULL, RY_ERR_NOMEM, "out of memory (wave_amplitude)");
    for (size_t b = 0; b < nb; ++b) h[b] = -INFINITY;
    xlo -= 0.5 * sim->dx;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || ps->material[i] != dense) continue;
        const size_t b = (size_t)((ps->f[RY_F_X][i] - xlo) / sim->dx);
        const size_t c = b < nb ? b : nb - 1;
        h[c] = fmax(h[c], ps->f[RY_F_Y][i]);
    }
    double sum = 0;
    size_t used = 0;
    for (size_t b = 0; b < nb; ++b) {
        if (!isfinite(h[b])) continue;
        sum += h[b] * cos(2.0 * 3.14159265358979323846 * ((double)b + 0.5) / (double)nb);
        ++used;
    }
    free(h);
    if (used) *v = 2.0 * sum / (double)used;
    return RY_OK;
}

/* Interface of two fluids stacked in a box one wavelength wide (2D; Rayleigh-Taylor): the
 * amplitude a of the mode a cos(2 pi (x - x_lo) / W) of the interface height, W = x_hi - x_lo
 * the width of the fluid (its particles' x-range widened by half a spacing each side). The
 * lower fluid (of materials 0 and 1, the one with the lower mean height) fills y < eta(x), so
 * sum_lower V cos = int eta cos dx = a W / 2; subtracting the lower fluid's share of the same
 * sum over all fluid makes the result insensitive to W and to the flat bottom and top. a > 0:
 * the interface is higher at x_lo than at the middle of the box. */
static ry_status probe_interface_amplitude(const ry_sim *sim, double *v, ry_error *err) {
    RY_CHECK(err, sim->nmat >= 2 && sim->dim == 2, RY_ERR_INPUT,
             "measurement 'interface_amplitude' needs dimension 2 and two materials");
    const ry_particles *ps = &sim->ps;
    double xlo = INFINITY, xhi = -INFINITY, ysum[2] = {0, 0};
    size_t cnt[2] = {0, 0};
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || ps->material[i] > 1) continue;
        const double x = ps->f[RY_F_X][i];
        xlo = fmin(xlo, x);
        xhi = fmax(xhi, x);
        ysum[ps->material[i]] += ps->f[RY_F_Y][i];
        ++cnt[ps->material[i]];
    }
    if (!cnt[0] || !cnt[1]) {
        *v = 0;
        return RY_OK;
    }
    const int lower = ysum[1] / (double)cnt[1] < ysum[0] / (double)cnt[0];
    xlo -= 0.5 * sim->dx;
    const double w = xhi + 0.5 * sim->dx - xlo, k = 2.0 * 3.14159265358979323846 / w;
    double cl = 0, ca = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || ps->material[i] > 1) continue;
        const double c = cos(k * (ps->f[RY_F_X][i] - xlo));
        ca += c;
        if (ps->material[i] == lower) cl += c;
    }
    const double share = (double)cnt[lower] / (double)(cnt[0] + cnt[1]);
    *v = 2.0 * sim->dx * sim->dx / w * (cl - share * ca);
    return RY_OK;
}

/* IISPH pressure-solve iterations: of the last step, and the mean over the run so far. */
static ry_status probe_iisph_iters(const ry_sim *sim, double *v, ry_error *err) {
    RY_CHECK(err, ry_scheme_stat(sim, "pressure_iterations_mean", v), RY_ERR_INPUT,
             "measurement 'iisph_iterations' needs scheme iisph");
    ry_scheme_stat(sim, "pressure_iterations", v);
    return RY_OK;
}
static ry_status probe_iisph_iters_mean(const ry_sim *sim, double *v, ry_error *err) {
    RY_CHECK(err, ry_scheme_stat(sim, "pressure_iterations_mean", v), RY_ERR_INPUT,
             "measurement 'iisph_iterations_mean' needs scheme iisph");
    return RY_OK;
}

static const ry_probe p_mass = {"mass", "total fluid mass [kg]", probe_mass, NULL, 0};
static const ry_probe p_inflow = {"inflow_volume",
                                  "volume that entered through inlets [m^3] (particles x dx^dim)",
                                  probe_inflow, NULL, 0};
static const ry_probe p_outflow = {"outflow_volume",
                                   "volume that left through outlets [m^3] (particles x dx^dim)",
                                   probe_outflow, NULL, 0};
static const ry_probe p_kept = {
    "injected_kept",
    "volume of the injected fluid (the second material) inside over the volume injected: 1 "
    "until it reaches an outlet",
    probe_injected_kept, NULL, 0};
static const ry_probe p_nfluid = {"fluid_particles", "number of fluid particles",
                                  probe_fluid_particles, NULL, 0};
static const ry_probe p_kin = {"kinetic_energy", "fluid kinetic energy [J]", probe_kinetic, NULL,
                               0};
static const ry_probe p_shape_m4 = {
    "shape_m4",
    "fourth-order shape moment of the fluid about its centroid, <x^4+y^4+z^4>/<r^4> - 3/5 (2D: "
    "<x^4+y^4>/<r^4> - 3/4), of the particles within twice the equivalent radius: 0 for a "
    "sphere or circle, -0.126 for a cube, -0.107 for a square",
    probe_shape_m4, NULL, 0};
static const ry_probe p_shape_p2 = {
    "shape_p2",
    "second-order (mode-2) shape moment of the fluid about its centroid, <z^2 - (x^2+y^2)/2>/<r^2> "
    "(2D: <y^2 - x^2>/(2 <r^2>)), of the particles within twice the equivalent radius: 0 for a "
    "sphere or circle, eps for a surface at R (1 + eps P_2(cos theta)) (2D: R (1 + eps cos 2 phi), "
    "phi from the y axis)",
    probe_shape_p2, NULL, 0};
static const ry_probe p_vmax = {"max_speed", "largest fluid speed [m/s]", probe_max_speed, NULL, 0};
static const ry_probe p_tau_max = {
    "max_polymer_stress", "largest size of the polymer stress sqrt(tau : tau) over the fluid [Pa]",
    probe_max_polymer_stress, NULL, 0};
static const ry_probe p_out = {"outside", "particles outside the domain", probe_outside, NULL, 0};
static const ry_probe p_front = {"front_x", "surge front position [m] (leading edge on the floor)",
                                 probe_front_x, NULL, 0};
static const ry_probe p_in_wall = {
    "in_wall", "fluid particles inside a wall (within dx/2 of a wall particle in every direction)",
    probe_in_wall, NULL, 0};
static const ry_probe p_iters = {"iisph_iterations",
                                 "scheme iisph: pressure-solve iterations of the last step",
                                 probe_iisph_iters, NULL, 0};
static const ry_probe p_iters_mean = {
    "iisph_iterations_mean", "scheme iisph: mean pressure-solve iterations per step so far",
    probe_iisph_iters_mean, NULL, 0};
static const ry_probe p_filled = {
    "filled_fraction", "fluid particles of the second (injected) material over all fluid particles",
    probe_filled_fraction, NULL, 0};
static const ry_probe p_interface = {
    "interface_amplitude",
    "2D, two fluids in a box one wavelength wide: amplitude of the interface mode "
    "cos(2 pi x / width) [m]",
    probe_interface_amplitude, NULL, 0};
static const ry_probe p_wave = {
    "wave_amplitude",
    "2D: amplitude of the mode cos(2 pi x / width) of the top surface of the densest fluid [m]",
    probe_wave_amplitude, NULL, 0};
static const ry_probe p_droplet_length = {
    "droplet_length",
    "section droplet: vertical extent of the droplet attached to the nozzle below its tip [m]",
    probe_droplet_length, NULL, 0};
static const ry_probe p_droplet_width = {
    "droplet_width", "section droplet: largest horizontal extent of that droplet [m]",
    probe_droplet_width, NULL, 0};
static const ry_probe p_droplet_aspect = {
    "droplet_aspect", "section droplet: droplet length / width", probe_droplet_aspect, NULL, 0};
static const ry_probe p_droplet_detached = {
    "droplet_detached",
    "section droplet: 1 once a body of the material (10 particles or more) lies wholly below "
    "the tip, disconnected from the nozzle; else 0",
    probe_droplet_detached, NULL, 0};
static const ry_probe p_droplet_volume = {
    "droplet_volume",
    "section droplet: volume of the attached droplet below the tip (its particles times dx^dim) "
    "[m^3, m^2 in 2D]",
    probe_droplet_volume, NULL, 0};
static const ry_probe p_droplet_offset = {
    "droplet_offset",
    "section droplet: horizontal distance from the nozzle's axis (droplet.axis) to the centroid "
    "of the attached droplet below the tip [m]",
    probe_droplet_offset, NULL, 0};

static const ry_probe *const all_probes[] = {&p_mass,
                                             &p_filled,
                                             &ry_probe_oil_wall_contact,
                                             &p_kept,
                                             &p_interface,
                                             &ry_probe_interface_height,
                                             &p_wave,
                                             &p_iters,
                                             &p_iters_mean,
                                             &p_kin,
                                             &p_shape_m4,
                                             &p_shape_p2,
                                             &p_vmax,
                                             &p_tau_max,
                                             &p_out,
                                             &p_front,
                                             &p_in_wall,
                                             &p_inflow,
                                             &p_outflow,
                                             &p_nfluid,
                                             &ry_probe_tip_deflection,
                                             &ry_probe_tip_axial,
                                             &ry_probe_residual,
                                             &ry_probe_solid_kinetic_energy,
                                             &ry_probe_strain_energy,
                                             &ry_probe_min_spacing,
                                             &ry_probe_width_x,
                                             &ry_probe_drop_pressure,
                                             &ry_probe_ppe_iterations,
                                             &ry_probe_contact_angle,
                                             &ry_probe_contact_angle_second,
                                             &ry_probe_width_x_second,
                                             &ry_probe_pressure_jump_second,
                                             &p_droplet_length,
                                             &p_droplet_width,
                                             &p_droplet_aspect,
                                             &p_droplet_detached,
                                             &p_droplet_volume,
                                             &p_droplet_offset,
                                             NULL};

const ry_probe *const *ry_probes(void) {
    return all_probes;
}

double ry_band_max_speed(const ry_sim *sim, int axis, double lo, double hi) {
    const ry_particles *ps = &sim->ps;
    double m = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        const double x = ps->f[RY_F_X + axis][i];
        if (x < lo || x > hi) continue;
        double u2 = 0;
        for (int d = 0; d < sim->dim; ++d) u2 += ps->f[RY_F_VX + d][i] * ps->f[RY_F_VX + d][i];
        m = fmax(m, sqrt(u2));
    }
    return m;
}
