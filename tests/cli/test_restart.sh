#!/bin/sh
# Checkpoints and restart: a run stopped (by step count or by SIGTERM) and continued with
# --restart ends bitwise identical to an uninterrupted run (VTK files, .pvd, series.csv,
# profiles), for each scheme (MPS included, and Oldroyd-B fluids in MPS and WCSPH), with
# inflow and outflow (an inlet ramped up too), on another thread count too; a damaged newest checkpoint is skipped for
# the one before it; a truncated or corrupted checkpoint is rejected by name; a restart with
# other output and checkpoint intervals follows them from the checkpoint on.
# usage: test_restart.sh RYUSHI SOURCE_DIR
set -u
RY=$1
SRC=$2
. "$SRC/tests/cli/lib.sh"

# same A B: every result file of run A is byte for byte in run B
same() {
    n=0
    for f in "$1"/*.vtp "$1"/*.pvd "$1"/*.csv; do
        [ -f "$f" ] || continue
        n=$((n + 1))
        if ! cmp -s "$f" "$2/$(basename "$f")"; then bad "$3: $(basename "$f") differs"; return; fi
    done
    if [ "$n" -lt 3 ]; then bad "$3: only $n result files"; return; fi
    ok
}

# run NAME CASE ARGS...: a run with its output in $T/NAME; the exit code in $rc
run() {
    name=$1; case_file=$2; shift 2
    "$RY" run "$case_file" -o "$T/$name" "$@" > "$T/$name.log" 2>&1
    rc=$?
}

DAM="$SRC/cases/dam_break_seed.yaml"
DAMSET="--set spacing=0.0125 --set time.end=0.2 --set time.output_interval=0.02"

# 1. WCSPH dam break: stopped at step 700 (not an output time), continued on 1 thread.
# shellcheck disable=SC2086
run full "$DAM" $DAMSET --threads 2
[ "$rc" -eq 0 ] || bad "uninterrupted dam break exited $rc: $(cat "$T/full.log")"
# shellcheck disable=SC2086
run part "$DAM" $DAMSET --threads 2 --set time.max_steps=700
[ -f "$T/part/checkpoints/checkpoint_0000000700.ryc" ] || bad "no checkpoint at step 700"
# shellcheck disable=SC2086
"$RY" run "$DAM" $DAMSET --threads 1 --restart "$T/part" > "$T/part2.log" 2>&1 ||
    bad "restart failed: $(cat "$T/part2.log")"
grep -q "restarting from .*checkpoint_0000000700.ryc (step 700" "$T/part2.log" ||
    bad "restart did not name its checkpoint: $(cat "$T/part2.log")"
same "$T/full" "$T/part" "dam break restarted at step 700"
# a restart with another spacing is refused, naming the checkpoint's
"$RY" run "$DAM" --set spacing=0.00625 --set time.end=0.2 --restart "$T/part" -o "$T/respaced" \
    > "$T/respaced.log" 2>&1
rc=$?
[ "$rc" -eq 2 ] && grep -q "written with spacing = 0.0125, the case has 0.00625" "$T/respaced.log" ||
    bad "restart with another spacing: exit $rc: $(cat "$T/respaced.log")"

# restarted NAME CASE STEPS LABEL: CASE (Oldroyd-B start-up, to 4 ms, one thread) run whole and
# stopped at STEPS then continued with --restart ends bitwise the same
OBSET="--set time.end=0.004 --set time.output_interval=0.001 --set output.vtk=true --threads 1"
restarted() {
    # shellcheck disable=SC2086
    run "$1full" "$2" $OBSET
    [ "$rc" -eq 0 ] || bad "uninterrupted $4 run exited $rc: $(cat "$T/$1full.log")"
    # shellcheck disable=SC2086
    run "$1part" "$2" $OBSET --set time.max_steps="$3"
    # shellcheck disable=SC2086
    "$RY" run "$2" $OBSET --restart "$T/$1part" > "$T/$1part2.log" 2>&1 ||
        bad "$4 restart failed: $(cat "$T/$1part2.log")"
    same "$T/$1full" "$T/$1part" "$4 restarted at step $3"
}

# 1b. MPS with an Oldroyd-B fluid: the polymer stress is part of the state.
restarted ob "$SRC/cases/mps_oldroyd_b_startup.yaml" 250 "Oldroyd-B start-up"
# 1c. The same with WCSPH: the polymer stress and the particle viscosity are part of its state.
restarted obs "$SRC/cases/sph_oldroyd_b_startup.yaml" 350 "WCSPH Oldroyd-B start-up"

# 2. Periodic checkpoints (every 250 steps, keep 2): restart from the older of the two, after
# the newest was damaged (truncated).
# shellcheck disable=SC2086
run per "$DAM" $DAMSET --set time.max_steps=1000 --set checkpoint.every_steps=250 \
    --set checkpoint.keep=2 --set checkpoint.at_end=false
n=$(ls "$T/per/checkpoints" | wc -l)
[ "$n" -eq 2 ] || bad "checkpoint.keep=2 left $n checkpoints"
newest="$T/per/checkpoints/checkpoint_0000001000.ryc"
head -c 5000 "$newest" > "$T/trunc.ryc"
cp "$T/trunc.ryc" "$newest"
out=$("$RY" checkpoint "$newest" 2>&1)
[ $? -eq 2 ] && printf '%s' "$out" | grep -q "checkpoint_0000001000.ryc: truncated" && ok ||
    bad "truncated checkpoint not rejected by name: $out"
# shellcheck disable=SC2086
"$RY" run "$DAM" $DAMSET --restart "$T/per" > "$T/per2.log" 2>&1 || bad "restart past a damaged checkpoint failed: $(cat "$T/per2.log")"
grep -q "skipped damaged checkpoint" "$T/per2.log" && grep -q "step 750" "$T/per2.log" && ok ||
    bad "damaged checkpoint not reported/skipped: $(cat "$T/per2.log")"
same "$T/full" "$T/per" "dam break restarted from the older checkpoint"

# 3. A flipped byte anywhere fails the checksum.
cp "$T/part/checkpoints/checkpoint_0000000700.ryc" "$T/flip.ryc"
printf '\377' | dd of="$T/flip.ryc" bs=1 seek=4000 conv=notrunc 2>/dev/null
out=$("$RY" checkpoint "$T/flip.ryc" 2>&1)
[ $? -eq 2 ] && printf '%s' "$out" | grep -q "checksum mismatch" && ok ||
    bad "corrupted checkpoint not rejected: $out"
out=$("$RY" checkpoint "$T/part/checkpoints/checkpoint_0000000700.ryc" 2>&1)
printf '%s' "$out" | grep -q "checksum good" && printf '%s' "$out" | grep -q "field/x" && ok ||
    bad "checkpoint listing: $out"

# 4. SIGTERM mid-run: exit 130 with a checkpoint, continued to the same end.
# shellcheck disable=SC2086
"$RY" run "$DAM" $DAMSET --set time.dt_max=1e-5 -o "$T/sig" > "$T/sig.log" 2>&1 &
pid=$!
sleep 1
kill -TERM "$pid"
wait "$pid"
rc=$?
[ "$rc" -eq 130 ] || bad "SIGTERM: exit $rc, expected 130: $(cat "$T/sig.log")"
grep -q "continue with --restart" "$T/sig.log" && ok || bad "no checkpoint named: $(cat "$T/sig.log")"
# shellcheck disable=SC2086
run sigfull "$DAM" $DAMSET --set time.dt_max=1e-5
# shellcheck disable=SC2086
"$RY" run "$DAM" $DAMSET --set time.dt_max=1e-5 --restart "$T/sig" > "$T/sig2.log" 2>&1 ||
    bad "restart after SIGTERM failed: $(cat "$T/sig2.log")"
same "$T/sigfull" "$T/sig" "dam break restarted after SIGTERM"

# 5. Lid-driven cavity with time-averaged profiles (transport-velocity WCSPH).
CAV="$SRC/cases/cavity_re100.yaml"
CAVSET="--set spacing=0.05 --set time.end=0.6 --set time.output_interval=0.1"
CAVSET="$CAVSET --set profiles[0].average_from=0.2 --set profiles[1].average_from=0.2"
# shellcheck disable=SC2086
run cav "$CAV" $CAVSET
# shellcheck disable=SC2086
run cavp "$CAV" $CAVSET --set time.max_steps=333
# shellcheck disable=SC2086
"$RY" run "$CAV" $CAVSET --restart "$T/cavp" > "$T/cavp2.log" 2>&1 || bad "cavity restart failed: $(cat "$T/cavp2.log")"
same "$T/cav" "$T/cavp" "cavity restarted at step 333"

# 6. Channel with an inlet and an outlet: particles created and removed during the run.
CH="$SRC/cases/channel_inflow.yaml"
CHSET="--set spacing=0.01 --set time.end=0.8 --set time.output_interval=0.1"
CHSET="$CHSET --set open_boundaries[0].lo=[-0.04,0] --set open_boundaries[1].hi=[0.44,0.1]"
CHSET="$CHSET --set bodies[1].lo=[-0.06,-0.03] --set bodies[2].hi=[0.46,0.13]"
CHSET="$CHSET --set profiles[0].average_from=0.4"
# shellcheck disable=SC2086
run ch "$CH" $CHSET
[ "$rc" -eq 0 ] || bad "channel exited $rc: $(cat "$T/ch.log")"
# shellcheck disable=SC2086
run chp "$CH" $CHSET --set time.max_steps=555
# shellcheck disable=SC2086
"$RY" run "$CH" $CHSET --restart "$T/chp" > "$T/chp2.log" 2>&1 || bad "channel restart failed: $(cat "$T/chp2.log")"
same "$T/ch" "$T/chp" "channel with inflow and outflow restarted at step 555"

# 6b. The same channel with its inlet ramped up over 0.6 s (open_boundaries[0].ramp), stopped
# during the ramp at step 300.
# shellcheck disable=SC2086
run chr "$CH" $CHSET --set "open_boundaries[0].ramp=0.6"
[ "$rc" -eq 0 ] || bad "ramped channel exited $rc: $(cat "$T/chr.log")"
# shellcheck disable=SC2086
run chrp "$CH" $CHSET --set "open_boundaries[0].ramp=0.6" --set time.max_steps=300
# shellcheck disable=SC2086
"$RY" run "$CH" $CHSET --set "open_boundaries[0].ramp=0.6" --restart "$T/chrp" > "$T/chrp2.log" 2>&1 ||
    bad "ramped channel restart failed: $(cat "$T/chrp2.log")"
same "$T/chr" "$T/chrp" "channel with its inflow ramped up, restarted at step 300"

# 7. Elastic solid (total-Lagrangian, kinetic damping) stopped at step 150.
BEAM="$SRC/cases/cantilever.yaml"
BEAMSET="--set time.max_steps=400 --set time.output_interval=0.5 --set output.vtk=true"
# shellcheck disable=SC2086
run beam "$BEAM" $BEAMSET
# shellcheck disable=SC2086
run beamp "$BEAM" $BEAMSET --set time.max_steps=150
# shellcheck disable=SC2086
"$RY" run "$BEAM" $BEAMSET --restart "$T/beamp" > "$T/beamp2.log" 2>&1 || bad "solid restart failed: $(cat "$T/beamp2.log")"
same "$T/beam" "$T/beamp" "cantilever restarted at step 150"

# 8. Updated-Lagrangian solid (Jaumann-rate stress as particle fields): the oscillating plate.
PLATE="$SRC/cases/oscillating_plate.yaml"
PSET="--set time.end=0.02 --set time.output_interval=0.005 --set output.vtk=true"
# shellcheck disable=SC2086
run plate "$PLATE" $PSET
# shellcheck disable=SC2086
run platep "$PLATE" $PSET --set time.max_steps=77
# shellcheck disable=SC2086
"$RY" run "$PLATE" $PSET --restart "$T/platep" > "$T/platep2.log" 2>&1 || bad "plate restart failed: $(cat "$T/platep2.log")"
same "$T/plate" "$T/platep" "updated-Lagrangian plate restarted at step 77"

# 9. A checkpoint does not fit another case.
out=$("$RY" run "$BEAM" --restart "$T/part" -o "$T/wrong" 2>&1)
[ $? -eq 2 ] && printf '%s' "$out" | grep -q "written for scheme 'wcsph', the case has 'solid'" &&
    ok || bad "checkpoint of another case accepted: $out"
out=$("$RY" run "$DAM" --restart "$T/nothing" 2>&1)
[ $? -eq 2 ] && printf '%s' "$out" | grep -q "no checkpoint" && ok || bad "missing checkpoint: $out"

# 10. MPS square drop (potential-model surface tension, conjugate-gradient pressure whose initial
# guess is the pressure field): stopped at step 37 on 2 threads, continued on 1.
DROP="$SRC/cases/mps_droplet_square.yaml"
DSET="--set time.end=0.002 --set time.output_interval=0.0005"
# shellcheck disable=SC2086
run drop "$DROP" $DSET --threads 2
# shellcheck disable=SC2086
run dropp "$DROP" $DSET --threads 2 --set time.max_steps=37
# shellcheck disable=SC2086
"$RY" run "$DROP" $DSET --threads 1 --restart "$T/dropp" > "$T/dropp2.log" 2>&1 || bad "MPS restart failed: $(cat "$T/dropp2.log")"
same "$T/drop" "$T/dropp" "MPS drop restarted at step 37"

# 11. A restart with another measurement list: the series keeps one header, this run's; the
# earlier rows are carried over column by name, empty where that run did not measure.
# shellcheck disable=SC2086
run meas "$DAM" $DAMSET --threads 1 --set time.max_steps=700
# shellcheck disable=SC2086
"$RY" run "$DAM" $DAMSET --threads 1 --restart "$T/meas" --set "measure=[max_speed, mass, fluid_particles]" \
    > "$T/meas2.log" 2>&1 || bad "restart with other measurements failed: $(cat "$T/meas2.log")"
hdr=$(head -1 "$T/meas/series.csv")
[ "$hdr" = "t,step,dt,particles,max_speed,mass,fluid_particles" ] || bad "series header after the restart: $hdr"
# every row has 7 fields; the first rows carry the uninterrupted run's max_speed and mass, and
# no fluid_particles; the last rows have all three
awk -F, 'NF != 7 { exit 1 }' "$T/meas/series.csv" || bad "series rows of another width after the restart"
want=$(awk -F, 'NR == 3 { print $1 "," $8 "," $6 "," }' "$T/full/series.csv")
got=$(awk -F, 'NR == 3 { print $1 "," $5 "," $6 "," $7 }' "$T/meas/series.csv")
[ "$got" = "$want" ] || bad "first row after the restart: $got, want $want (max_speed, mass, none)"
last=$(tail -1 "$T/meas/series.csv" | awk -F, '{ print ($7 > 0) }')
[ "$last" = 1 ] || bad "last row without fluid_particles: $(tail -1 "$T/meas/series.csv")"
ok

# 12. A restart with a shorter output interval and a checkpoint interval asked for anew: the
# outputs go on every 0.005 s from the first such time after the checkpoint (0.1044 s), not
# from the stored schedule's next time (0.12 s), and a checkpoint comes at 0.15 s.
# shellcheck disable=SC2086
run sched "$DAM" $DAMSET --threads 1 --set time.max_steps=620
# shellcheck disable=SC2086
"$RY" run "$DAM" $DAMSET --threads 1 --restart "$T/sched" --set time.output_interval=0.005 \
    --set checkpoint.interval=0.05 --set checkpoint.keep=10 > "$T/sched2.log" 2>&1 ||
    bad "restart with other intervals failed: $(cat "$T/sched2.log")"
got=$(awk -F, 'NR > 1 && $1 > 0.1 && $1 < 0.13 { printf "%s ", $1 }' "$T/sched/series.csv")
[ "$got" = "0.105 0.11 0.115 0.12 0.125 " ] && ok || bad "output times after the restart: $got"
ncheck=$(find "$T/sched/checkpoints" -name 'checkpoint_*.ryc' | wc -l)
# (and the first run's first one, for guard.last_good; the restart's first one is the stop's)
[ "$ncheck" -eq 4 ] && ok || bad "$ncheck checkpoints after the restart, want 4 (at the start, the stop, 0.15 s, the end)"

printf "restart tests: "
finish
