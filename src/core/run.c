/* The time loop. */
#include <math.h>
#include <stdio.h>

#include "core/writer.h"
#include "ryushi/sim.h"

ry_status ry_sim_run(ry_sim *sim, const ry_run_hooks *hooks, ry_run_stats *stats, ry_error *err) {
    double t0 = ry_wall_time(), last_report = t0;
    long step0 = sim->step;
    double psteps = 0;
    ry_status st = RY_OK;
    if (sim->output_index == 0) {
        RY_TRY(ry_sim_write_output(sim, err));
        sim->next_output = sim->t + sim->output_interval;
    }
    const double eps = 1e-12 * sim->t_end;
    while (sim->t < sim->t_end - eps && sim->step < sim->max_steps && !sim->finished) {
        if (hooks && hooks->stop && *hooks->stop) {
            st = ry_error_set(err, RY_ERR_INTERRUPTED,
                              "interrupted at step %ld, t = %.6g s; state written", sim->step,
                              sim->t);
            break;
        }
        double dt;
        RY_TRY(sim->scheme->stable_dt(sim, sim->scheme_state, &dt, err));
        if (sim->dt_max > 0 && dt > sim->dt_max) dt = sim->dt_max;
        if (!(dt > 0) || !isfinite(dt)) {
            return ry_error_set(err, RY_ERR_UNSTABLE,
                                "unstable at step %ld, t = %.6g s: time step %g is not positive",
                                sim->step, sim->t, dt);
        }
        /* Land on output times and the end time exactly (no sliver steps after them). */
        double target = fmin(sim->next_output, sim->t_end);
        if (sim->t + dt > target - 1e-3 * dt)
            dt = target - sim->t;
        else if (sim->t + 2 * dt > target)
            dt = 0.5 * (target - sim->t);
        sim->dt = dt;
        RY_TRY(sim->scheme->step(sim, sim->scheme_state, dt, err));
        sim->t += dt;
        sim->step++;
        psteps += (double)sim->ps.n;
        st = ry_sim_check(sim, err);
        if (st != RY_OK) return st; /* the last good output stays on disk */
        if (sim->t >= sim->next_output - eps) {
            RY_TRY(ry_sim_write_output(sim, err));
            while (sim->next_output <= sim->t + eps) sim->next_output += sim->output_interval;
        }
        double now = ry_wall_time();
        if (hooks && hooks->progress && now - last_report >= hooks->progress_interval_s) {
            double rate = psteps / fmax(now - t0, 1e-9);
            double frac = sim->t / sim->t_end;
            double eta = frac > 0 ? (now - t0) * (1 - frac) / frac : 0;
            hooks->progress(hooks->ctx, sim, rate, eta);
            last_report = now;
        }
    }
    /* The final state, unless it was just written. */
    if (st == RY_OK || st == RY_ERR_INTERRUPTED) {
        ry_error tmp;
        ry_error *e = st == RY_OK ? err : &tmp;
        if (sim->output_index == 0 || fabs(sim->t - (sim->next_output - sim->output_interval)) >
                                          1e-9 * sim->output_interval) {
            ry_status ws = ry_sim_write_output(sim, e);
            if (ws != RY_OK && st == RY_OK) return ws;
        }
    }
    if (stats) {
        stats->steps = sim->step - step0;
        stats->particles = sim->ps.n;
        stats->wall_s = ry_wall_time() - t0;
        stats->particle_steps_per_s = psteps / fmax(stats->wall_s, 1e-9);
        stats->outputs = sim->output_index;
    }
    return st;
}
