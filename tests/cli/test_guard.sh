#!/bin/sh
# Guarded runs: a run that goes unstable stops with a diagnosis (step, particle, position,
# what is wrong), exit code 4, and its last good state on disk (VTK and a checkpoint one can
# restart from); a write error (here a file-size limit, as a full disk would) stops the run with
# exit code 3 and leaves every earlier output whole.
# usage: test_guard.sh RYUSHI SOURCE_DIR
set -u
RY=$1
SRC=$2
. "$SRC/tests/cli/lib.sh"
DAM="$SRC/cases/dam_break_seed.yaml"
SET="--set spacing=0.0125 --set time.end=0.2"

# 1. Gravity 200 times too strong: particles pass the sound speed within a few dozen steps.
# shellcheck disable=SC2086
out=$("$RY" run "$DAM" $SET --set "gravity=[0,-2000]" -o "$T/g" 2>&1)
rc=$?
[ "$rc" -eq 4 ] || bad "unstable run exited $rc, expected 4: $out"
printf '%s' "$out" | grep -q "unstable at step [0-9]*, t = .*first: particle id [0-9]* (fluid) at (.*): speed .* exceeds guard.max_speed = 30 m/s" &&
    ok || bad "no diagnosis: $out"
printf '%s' "$out" | grep -q "last good state (step [0-9]*" && ok || bad "no last good state: $out"
[ -f "$T/g/dam_break_seed_last_good.vtp" ] && ok || bad "last good VTK missing"
ck=$(ls "$T/g/checkpoints"/*.ryc 2>/dev/null | tail -1)
[ -n "$ck" ] && "$RY" checkpoint "$ck" > /dev/null && ok || bad "last good checkpoint missing or unreadable"
# The last good state is replayed from the run's first checkpoint to the last step that passed
# the check: it is bitwise the state of a run stopped at that step.
good=$(printf '%s' "$out" | sed -n 's/.*last good state (step \([0-9]*\),.*/\1/p')
# shellcheck disable=SC2086
"$RY" run "$DAM" $SET --set "gravity=[0,-2000]" --set time.max_steps="$good" -o "$T/g2" > /dev/null 2>&1
cmp -s "$T/g/dam_break_seed_last_good.vtp" "$T/g2/dam_break_seed_00001.vtp" && ok ||
    bad "the replayed last good state (step $good) differs from a run stopped there"
# The in-memory copy (guard.last_good: memory) is at most guard.snapshot_every steps older.
# shellcheck disable=SC2086
out=$("$RY" run "$DAM" $SET --set "gravity=[0,-2000]" --set guard.last_good=memory -o "$T/gm" 2>&1)
mem=$(printf '%s' "$out" | sed -n 's/.*last good state (step \([0-9]*\),.*/\1/p')
[ -n "$mem" ] && [ "$mem" -le "$good" ] && [ "$mem" -gt $((good - 10)) ] &&
    [ -f "$T/gm/dam_break_seed_last_good.vtp" ] && ok || bad "memory copy: step '$mem': $out"
# A guard set below the dam break's real speeds (about 3 m/s) trips it; the run continues from
# the last good state with the guard back at its default and reaches the end.
# shellcheck disable=SC2086
"$RY" run "$DAM" $SET --set guard.max_speed=2 -o "$T/s" > "$T/s.log" 2>&1
[ $? -eq 4 ] && ok || bad "guard.max_speed=2 did not stop the run: $(cat "$T/s.log")"
# shellcheck disable=SC2086
"$RY" run "$DAM" $SET --restart "$T/s" > "$T/s2.log" 2>&1 &&
    grep -q "summary status=ok .* t=0.2 " "$T/s2.log" && ok ||
    bad "restart from the last good state failed: $(cat "$T/s2.log")"

# 2. The density guard, with the speed guard off.
# shellcheck disable=SC2086
out=$("$RY" run "$DAM" $SET --set "gravity=[0,-2000]" --set guard.max_speed=0 -o "$T/d" 2>&1)
[ $? -eq 4 ] && printf '%s' "$out" | grep -q "times the reference, outside guard.density_min..density_max" &&
    ok || bad "density guard: $out"

# 3. The time-step guard: the dam break's stable step falls by a few per cent as the column
# collapses and its speeds grow; a ratio of 0.99 catches that, as the default (1e-4) catches a
# step that collapses in a flow that has blown up.
# shellcheck disable=SC2086
out=$("$RY" run "$DAM" $SET --set guard.min_dt_ratio=0.99 -o "$T/dt" 2>&1)
[ $? -eq 4 ] && printf '%s' "$out" | grep -q "the time step .* s fell below guard.min_dt_ratio = 0.99 times the largest of this run (.* s); largest speed" &&
    ok || bad "time-step guard: $out"
[ -f "$T/dt/dam_break_seed_last_good.vtp" ] && ok || bad "time-step guard: last good VTK missing"

# 4. A file-size limit below the size of a checkpoint: the run stops at the first checkpoint
# with exit code 3, naming it; the outputs before it are whole and no temporary file is left.
# (Each VTK file of this run is 133 kB, a checkpoint 144 kB: the limit, 270 blocks of 512 B
# (sh's unit), lies between.)
# shellcheck disable=SC2086
# (guard.last_good=memory: the replay's first checkpoint would be the one to fail)
out=$(sh -c "ulimit -f 270; exec \"$RY\" run \"$DAM\" $SET --set checkpoint.every_steps=300 --set guard.last_good=memory -o \"$T/full\"" 2>&1)
rc=$?
[ "$rc" -eq 3 ] || bad "write error exited $rc, expected 3: $out"
printf '%s' "$out" | grep -q "writing checkpoint .*checkpoint_0000000300.ryc failed: File too large" &&
    ok || bad "write error not named: $out"
leftovers=$(find "$T/full" -name '*.tmp*' | wc -l)
[ "$leftovers" -eq 0 ] && ok || bad "$leftovers temporary files left"
nv=$(grep -c "<DataSet" "$T/full/dam_break_seed.pvd")
nc=$(($(wc -l < "$T/full/series.csv") - 1))
[ "$nv" -ge 2 ] && [ "$nv" -eq "$nc" ] && ok || bad "pvd lists $nv files, series.csv has $nc rows"
for f in "$T/full"/*.vtp; do
    tail -c 12 "$f" | grep -q "</VTKFile>" || bad "$(basename "$f") is cut short"
done
ok

printf "guard tests: "
finish
