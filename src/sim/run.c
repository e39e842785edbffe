/* The time loop. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sim/writer.h"
#include "ryushi/sim.h"
#include "ryushi/probes.h"
#include "core/guard_check.h"
#include "ryushi/clock.h"
#include "ryushi/open_boundary.h"
#include "ryushi/run.h"
#include "sim/symmetry.h"

/* A checkpoint due after this step by the case's policy: 1 on the simulated schedule
 * (interval, every_steps), 2 by the wall clock alone, 0 none. */
static int checkpoint_due(ry_sim *sim, double eps) {
    const ry_ckpt_policy *k = &sim->ckpt;
    if (k->interval > 0 && sim->t >= k->next_t - eps) return 1;
    if (k->every_steps > 0 && sim->step % k->every_steps == 0) return 1;
    return k->wall_interval > 0 && ry_wall_time() - k->last_wall >= k->wall_interval ? 2 : 0;
}

/* The largest fluid speed (over all ranks), for a diagnosis. */
static double largest_speed(ry_sim *sim) {
    const double v = ry_band_max_speed(sim, 0, -INFINITY, INFINITY);
    return sim->par ? sim->par->max(sim, v) : v;
}

static ry_status run_loop(ry_sim *sim, const ry_run_hooks *hooks, ry_run_stats *stats, long max_now,
                          double until_t, long replay_until, ry_error *err);

/* On instability: the last good state goes to disk (VTK and checkpoint), named in the message.
 * By replay, the newest checkpoint of this run is read back and the run taken again from it to
 * the last checked step (the steps are the same bitwise: the state is the one the run had);
 * or from the in-memory copy (guard.last_good: memory). */
static void keep_last_good(ry_sim *sim, const ry_run_hooks *hooks, ry_error *err) {
    const ry_loop_state *lg = &sim->loop;
    const int replay = sim->guard.last_good == RY_LAST_GOOD_REPLAY && lg->ck_step >= 0;
    if (!sim->snapshot && !replay) {
        size_t l = strlen(err->msg);
        snprintf(err->msg + l, sizeof err->msg - l,
                 "; no last good state was kept%s: the newest output and checkpoint in %s remain",
                 sim->par ? " (a distributed run)" : "",
                 sim->out_dir ? sim->out_dir : "the output folder");
        return;
    }
    char path[4300];
    ry_error e = {0};
    ry_status st;
    if (replay) {
        ry_run_hooks stop_only = {0};
        if (hooks) stop_only.stop = hooks->stop;
        st = ry_sim_checkpoint_read(sim, lg->ckpt, &e);
        if (st == RY_OK && sim->step < lg->good_step)
            st = run_loop(sim, &stop_only, NULL, -1, INFINITY, lg->good_step, &e);
        if (st == RY_OK && sim->step != lg->good_step)
            st = ry_error_set(&e, RY_ERR_INTERNAL, "the replay from %s ended at step %ld", lg->ckpt,
                              sim->step);
        if (st == RY_OK) {
            ry_symmetry_hidden h; /* (the simulated particles, without their mirror copies) */
            ry_symmetry_hide(sim, &h);
            st = ry_sim_last_good_write(sim, path, sizeof path, &e);
            ry_symmetry_show(sim, &h);
        }
    } else {
        st = ry_sim_snapshot_write(sim, path, sizeof path, &e);
    }
    if (st == RY_OK) {
        size_t l = strlen(err->msg);
        snprintf(err->msg + l, sizeof err->msg - l,
                 "; the last good state (step %ld, t = %.6g s) is in %s/%s_last_good.vtp and %s",
                 sim->step, sim->t, sim->out_dir, sim->case_name, path);
    } else {
        size_t l = strlen(err->msg);
        snprintf(err->msg + l, sizeof err->msg - l, "; the last good state was not written: %s",
                 e.msg);
    }
}

ry_status ry_sim_output(ry_sim *sim, ry_error *err) {
    return sim->par ? sim->par->output(sim, err) : ry_output_write(sim, err);
}

ry_status ry_run(ry_sim *sim, const ry_run_hooks *hooks, ry_run_stats *stats, ry_error *err) {
    return run_loop(sim, hooks, stats, -1, INFINITY, -1, err);
}

ry_status ry_run_some(ry_sim *sim, const ry_run_hooks *hooks, long max_steps, double until_t,
                      ry_run_stats *stats, ry_error *err) {
    return run_loop(sim, hooks, stats, max_steps, until_t, -1, err);
}

/* Whether the run has nothing left to do. */
static int run_over(const ry_sim *sim, double eps) {
    return !(sim->t < sim->t_end - eps && sim->step < sim->max_steps && !sim->finished);
}

/* The time loop: at most max_now steps (< 0: no limit) and up to time until_t (landed on),
 * within the case's end. The first call of a run writes the first output, checks the state
 * and keeps it as the first last good one; the call that reaches the end writes the final
 * checkpoint and output. replay_until >= 0: a replay (keep_last_good) to that step, which
 * writes the outputs again as they were and no checkpoints. */
static ry_status run_loop(ry_sim *sim, const ry_run_hooks *hooks, ry_run_stats *stats, long max_now,
                          double until_t, long replay_until, ry_error *err) {
    const int replay = replay_until >= 0;
    double t0 = ry_wall_time(), last_report = t0;
    long step0 = sim->step;
    const double t_begin = sim->t; /* a restart or a second call starts part-way */
    double psteps = 0;
    ry_status st = RY_OK;
    ry_error local;
    if (!err) err = &local;
    if (sim->output_index == 0) {
        RY_TRY(ry_sim_output(sim, err));
        sim->next_output = sim->t + sim->output_interval;
    }
    /* The state handed in must be sound before it becomes the first "last good" one. */
    RY_TRY(ry_sim_check(sim, err));
    const int snap_every = replay ? 0 : sim->guard.snapshot_every;
    ry_loop_state *lg = &sim->loop;
    const double eps = 1e-12 * sim->t_end;
    if (!replay && !lg->begun) {
        lg->begun = 1;
        lg->first_step = sim->step;
        lg->dt_peak = 0;
        lg->good_step = sim->step;
        lg->ck_step = -1;
        lg->ckpt[0] = '\0';
        if (snap_every > 0) RY_TRY(ry_sim_snapshot_take(sim, err));
        if ((!sim->par || sim->par->redistribute_at_ref) && /* (a serial run's hooks) */
            sim->guard.last_good == RY_LAST_GOOD_REPLAY) {
            /* the state a replay starts from (not counted in the run's speed) */
            double w = ry_wall_time();
            sim->ckpt.scheduled = 0;
            RY_TRY(ry_sim_checkpoint_now(sim, lg->ckpt, sizeof lg->ckpt, err));
            lg->ck_step = sim->step;
            t0 += ry_wall_time() - w;
        }
    }
    const long last_step = max_now >= 0 ? sim->step + max_now : -1;
    while (!run_over(sim, eps) && !(replay && sim->step >= replay_until) &&
           !(last_step >= 0 && sim->step >= last_step) && sim->t < until_t - eps) {
        int stop = hooks && hooks->stop && *hooks->stop;
        if (sim->par) stop = !sim->par->all(sim, !stop); /* all ranks stop at the same step */
        if (stop) {
            st = RY_ERR_INTERRUPTED;
            break;
        }
        double dt;
        st = sim->scheme->stable_dt(sim, sim->scheme_state, &dt, err);
        if (st != RY_OK) {
            if (st == RY_ERR_UNSTABLE && !replay) keep_last_good(sim, hooks, err);
            goto done;
        }
        if (sim->par) dt = -sim->par->max(sim, -dt);
        if (sim->dt_max > 0 && dt > sim->dt_max) dt = sim->dt_max;
        if (!(dt > 0) || !isfinite(dt)) {
            st = ry_error_set(err, RY_ERR_UNSTABLE,
                              "unstable at step %ld, t = %.6g s: time step %g is not positive",
                              sim->step, sim->t, dt);
            if (!replay) keep_last_good(sim, hooks, err);
            goto done;
        }
        /* A step that collapses (the speeds or forces of a flow that has blown up set it)
         * would let the run crawl on without end. The first steps do not count towards the
         * peak: from rest a scheme may have no limit yet and take its fallback. */
        if (!replay && sim->step - lg->first_step >= 10) lg->dt_peak = fmax(lg->dt_peak, dt);
        if (dt < sim->guard.min_dt_ratio * lg->dt_peak) {
            st = ry_error_set(err, RY_ERR_UNSTABLE,
                              "unstable at step %ld, t = %.6g s: the time step %.4g s fell below "
                              "guard.min_dt_ratio = %g times the largest of this run (%.4g s); "
                              "largest speed %.4g m/s",
                              sim->step, sim->t, dt, sim->guard.min_dt_ratio, lg->dt_peak,
                              largest_speed(sim));
            if (!replay) keep_last_good(sim, hooks, err);
            goto done;
        }
        /* Land on output times and the end time exactly (no sliver steps after them). */
        double target = fmin(fmin(sim->next_output, sim->t_end), until_t);
        if (sim->t + dt > target - 1e-3 * dt)
            dt = target - sim->t;
        else if (sim->t + 2 * dt > target)
            dt = 0.5 * (target - sim->t);
        sim->dt = dt;
        sim->checked = 0;
        st = sim->scheme->step(sim, sim->scheme_state, dt, err);
        if (st != RY_OK) {
            if (st == RY_ERR_UNSTABLE && !replay) keep_last_good(sim, hooks, err);
            goto done;
        }
        sim->t += dt;
        sim->step++;
        if (sim->nopen > 0) sim->checked = 0; /* the particle set changes */
        st =
            sim->par && sim->nopen > 0 ? sim->par->open_update(sim, err) : ry_open_update(sim, err);
        if (st != RY_OK) goto done;
        psteps += (double)sim->ps.n;
        st = sim->checked
                 ? ry_check_verdict(sim, sim->check_bad, sim->check_fluid, sim->check_outside, err)
                 : ry_sim_check(sim, err);
        sim->checked = 0;
        if (st != RY_OK) {
            if (!replay) lg->good_step = sim->step - 1;
            if (!replay) keep_last_good(sim, hooks, err);
            goto done;
        }
        if (!replay) lg->good_step = sim->step;
        if (snap_every > 0 && sim->step % snap_every == 0) {
            st = ry_sim_snapshot_take(sim, err);
            if (st != RY_OK) goto done;
        }
        if (sim->t >= sim->next_output - eps) {
            st = ry_sim_output(sim, err);
            if (st != RY_OK) goto done;
            while (sim->next_output <= sim->t + eps) sim->next_output += sim->output_interval;
        }
        if (replay) continue;
        int due = checkpoint_due(sim, eps);
        /* The wall clock differs between ranks: they agree on the most pressing verdict. */
        if (sim->par) due = (int)sim->par->max(sim, due == 1 ? 3.0 : due);
        if (due == 3) due = 1;
        if (due) {
            sim->ckpt.scheduled = due == 1;
            while (sim->ckpt.next_t <= sim->t + eps) sim->ckpt.next_t += sim->ckpt.interval;
            st = ry_sim_checkpoint_now(sim, lg->ckpt, sizeof lg->ckpt, err);
            if (st != RY_OK) goto done;
            lg->ck_step = sim->step;
        }
        double now = ry_wall_time();
        if (hooks && hooks->progress && now - last_report >= hooks->progress_interval_s) {
            double rate = psteps / fmax(now - t0, 1e-9);
            /* From this run's own pace: a run continued from 15 of 20 s has 5 s to go at the
             * rate of the steps it has taken, not 15/20 of its work done. */
            double done_t = sim->t - t_begin, left_t = sim->t_end - sim->t;
            double eta = done_t > 0 ? (now - t0) * left_t / done_t : 0;
            hooks->progress(hooks->ctx, sim, rate, eta);
            last_report = now;
        }
    }
    /* A checkpoint of the final state (before its output, so that a restart from it writes
     * that output again exactly as an uninterrupted run would), then the final state's output
     * unless it was just written. */
    if (replay || (st == RY_OK && !run_over(sim, eps)) || lg->ended) goto done;
    lg->ended = st == RY_OK;
    char ck_end[sizeof lg->ckpt] = "";
    if (st == RY_ERR_INTERRUPTED || sim->ckpt.at_end) {
        ry_error e = {0};
        sim->ckpt.scheduled = st != RY_ERR_INTERRUPTED; /* the end of the run is scheduled */
        ry_status cs = ry_sim_checkpoint_now(sim, ck_end, sizeof ck_end, &e);
        if (cs == RY_OK) {
            memcpy(lg->ckpt, ck_end, sizeof ck_end);
            lg->ck_step = sim->step;
        }
        if (cs != RY_OK && st == RY_OK) {
            *err = e;
            st = cs;
            goto done;
        }
    }
    if (st == RY_ERR_INTERRUPTED)
        ry_error_set(err, RY_ERR_INTERRUPTED,
                     "interrupted at step %ld, t = %.6g s; state written; checkpoint %s (continue "
                     "with --restart %s)",
                     sim->step, sim->t, ck_end[0] ? ck_end : "not written", sim->out_dir);
    if (st == RY_OK || st == RY_ERR_INTERRUPTED) {
        ry_error tmp;
        ry_error *e = st == RY_OK ? err : &tmp;
        if (sim->output_index == 0 || fabs(sim->t - (sim->next_output - sim->output_interval)) >
                                          1e-9 * sim->output_interval) {
            ry_status ws = ry_sim_output(sim, e);
            if (ws != RY_OK && st == RY_OK) st = ws;
        }
    }
done:
    if (stats) {
        stats->steps = sim->step - step0;
        stats->particles = sim->ps.n;
        stats->wall_s = ry_wall_time() - t0;
        stats->particle_steps_per_s = psteps / fmax(stats->wall_s, 1e-9);
        stats->outputs = sim->output_index;
    }
    return st;
}
