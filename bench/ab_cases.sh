#!/bin/sh
# bench/ab_cases.sh: two builds of ryushi on the same cases, runs alternating between them,
# the median particle-steps/s of each and their ratio.
#
# Machines shared with other work are noisy (several-fold on a busy 2-core machine): a ratio
# measured in one run of this script, the two builds alternating, is worth more than numbers
# taken at different times. Build the older version into its own folder first, e.g.
#   git worktree add /tmp/old COMMIT && cmake -S /tmp/old -B /tmp/old/build && make -C /tmp/old/build ryushi
#
# Usage: sh bench/ab_cases.sh OLD_RYUSHI NEW_RYUSHI [THREADS]
# Environment: REPS (runs of each build per case, default 3), CASES (names from the list
#              below, default all).
# Cases (time.end shortened; output off; particle_steps_per_s= from the summary line, the
# time loop only):
#   eye      cases/eye_posterior_drain.yaml to 0.15 s (IISPH, 3D, in- and outflow)
#   iisph    cases/dam_break_mm_iisph.yaml to 0.1 s (IISPH, 2D)
#   channel  cases/channel_inflow.yaml, 4 s (WCSPH, 2D, in- and outflow)
#   mps3d    cases/mps_embolization_3d_coarse.yaml to 0.01 s at dt = 1e-4 s (MPS, 3D, 100 steps)
# Exit status: 0 on success, 1 with a message on stderr when a run fails.
set -eu

[ $# -ge 2 ] || {
    echo "usage: sh bench/ab_cases.sh OLD_RYUSHI NEW_RYUSHI [THREADS]" >&2
    exit 1
}
OLD=$1
NEW=$2
THREADS=${3:-2}
REPS=${REPS:-3}
CASES=${CASES:-eye iisph channel mps3d}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

case_args() {
    case $1 in
    eye) echo "$ROOT/cases/eye_posterior_drain.yaml --set time.end=0.15" ;;
    iisph) echo "$ROOT/cases/dam_break_mm_iisph.yaml --set time.end=0.1" ;;
    channel) echo "$ROOT/cases/channel_inflow.yaml" ;;
    mps3d) echo "$ROOT/cases/mps_embolization_3d_coarse.yaml --set time.end=0.01 --set time.dt_max=1e-4" ;;
    *)
        echo "ab_cases: error: unknown case '$1' (eye, iisph, channel, mps3d)" >&2
        exit 1
        ;;
    esac
}

# one run: prints "particles particle_steps_per_s"
one() {
    bin=$1
    name=$2
    # shellcheck disable=SC2046 # the case and its --set arguments are words
    line=$(OMP_NUM_THREADS=$THREADS "$bin" run $(case_args "$name") --threads "$THREADS" \
        --set output.vtk=false --set time.output_interval=1 -o "$WORK/out" 2>&1 |
        grep '^summary status=ok') || {
        echo "ab_cases: error: $bin on $name failed" >&2
        exit 1
    }
    echo "$line" | sed 's/.* particles=\([0-9]*\) .* particle_steps_per_s=\([0-9.e+]*\).*/\1 \2/'
}

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

echo "# $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, $THREADS threads, $REPS runs each," \
    "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# old: $OLD"
echo "# new: $NEW"
echo "| case | particles | old [particle-steps/s] | new | new / old |"
echo "|---|---|---|---|---|"
for name in $CASES; do
    : >"$WORK/old" && : >"$WORK/new"
    r=0
    while [ "$r" -lt "$REPS" ]; do
        one "$OLD" "$name" >>"$WORK/old"
        one "$NEW" "$name" >>"$WORK/new"
        r=$((r + 1))
    done
    n=$(head -1 "$WORK/new" | cut -d' ' -f1)
    o=$(cut -d' ' -f2 "$WORK/old" | median)
    w=$(cut -d' ' -f2 "$WORK/new" | median)
    echo "| $name | $n | $o | $w | $(awk -v a="$w" -v b="$o" 'BEGIN {printf "%.2f", a / b}') |"
done
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
