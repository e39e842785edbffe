#!/bin/sh
# bench/symmetry.sh: the cost of a step of a case run whole and cut by symmetry planes
# (docs/reference/symmetry.md, "Cost"). Seconds per step are the difference of two run
# lengths (so the set-up does not count), whole and part alternating, medians of REPS.
#
# Usage: sh bench/symmetry.sh RYUSHI [THREADS]
# Environment: CASES (names from the list below, default "dam3d drop3d"), REPS (default 3),
#              OUT (scratch folder, default a temporary one).
# Cases (output off):
#   dam3d    cases/mps_dam_break_3d.yaml at 12.5 mm, halved at y = 0.125 m (MPS), 10 and 60 steps
#   dam3dfine  the same at 6.25 mm, 5 and 25 steps
#   drop3d   cases/iisph_drop_rest_3d.yaml, an eighth (three planes through its centre, IISPH),
#            5 and 25 steps
#   tank     cases/mps_embolization_unified_3d.yaml (0.1 mm, 576,180 particles), a quarter (two
#            planes through the catheter's axis, MPS), 2 and 6 steps
# Each case prints a line per repetition (whole and part: particles simulated, seconds per step,
# peak resident memory in MB of the longer run, set-up and output included) and a line of
# medians with the speed-up.
# Exit status: 0 on success, 1 with a message on stderr when a run fails.
set -eu

[ $# -ge 1 ] || {
    echo "usage: sh bench/symmetry.sh RYUSHI [THREADS]" >&2
    exit 1
}
RY=$1
THREADS=${2:-2}
CASES=${CASES:-dam3d drop3d}
REPS=${REPS:-3}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT=${OUT:-$(mktemp -d)}
mkdir -p "$OUT"

field() { # field NAME LINE: the value of NAME= in a summary line
    printf '%s\n' "$2" | tr ' ' '\n' | sed -n "s/^$1=//p"
}

run() { # run CASE STEPS ARGS...: prints "particles wall_s peak_rss_mb"
    c=$1 steps=$2
    shift 2
    "$RY" run "$ROOT/$c" -o "$OUT/run" --threads "$THREADS" --set time.max_steps="$steps" \
        --set output.vtk=false "$@" >"$OUT/run.log" 2>&1 || {
        echo "bench/symmetry.sh: $c failed (see $OUT/run.log)" >&2
        exit 1
    }
    s=$(grep '^summary' "$OUT/run.log")
    echo "$(field particles "$s") $(field wall_s "$s") $(field peak_rss_mb "$s")"
}

per_step() { # per_step CASE N1 N2 ARGS...: prints "particles seconds_per_step peak_MB"
    c=$1 n1=$2 n2=$3
    shift 3
    a=$(run "$c" "$n1" "$@")
    b=$(run "$c" "$n2" "$@")
    echo "$a $b" | awk -v n1="$n1" -v n2="$n2" '{ printf "%d %.4f %.0f\n", $4, ($5 - $2) / (n2 - n1), $6 }'
}

median() { sort -g | awk '{ v[NR] = $1 } END { print NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

bench() { # bench NAME CASE N1 N2 "CUT ARGS" [ARGS...]
    name=$1 c=$2 n1=$3 n2=$4 cut=$5
    shift 5
    : >"$OUT/$name.whole"
    : >"$OUT/$name.part"
    rep=0
    while [ "$rep" -lt "$REPS" ]; do
        w=$(per_step "$c" "$n1" "$n2" "$@")
        # shellcheck disable=SC2086
        p=$(per_step "$c" "$n1" "$n2" "$@" $cut)
        echo "$name rep $rep: whole $w, part $p"
        echo "$w" | cut -d' ' -f2 >>"$OUT/$name.whole"
        echo "$p" | cut -d' ' -f2 >>"$OUT/$name.part"
        rep=$((rep + 1))
    done
    mw=$(median <"$OUT/$name.whole")
    mp=$(median <"$OUT/$name.part")
    echo "$name median: whole $mw s/step, part $mp s/step, speed-up $(awk "BEGIN { printf \"%.2f\", $mw / $mp }")"
}

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg), threads $THREADS"
for name in $CASES; do
    case $name in
    dam3d)
        bench dam3d cases/mps_dam_break_3d.yaml 10 60 \
            "--set domain.hi=[1.1,0.125,1.5] --set domain.symmetry=[y_hi]" --set spacing=0.0125 ;;
    dam3dfine)
        bench dam3dfine cases/mps_dam_break_3d.yaml 5 25 \
            "--set domain.hi=[1.1,0.125,1.5] --set domain.symmetry=[y_hi]" --set spacing=0.00625 ;;
    drop3d)
        bench drop3d cases/iisph_drop_rest_3d.yaml 5 25 \
            "--set domain.lo=[0,0,0] --set domain.symmetry=[x_lo,y_lo,z_lo]" ;;
    tank)
        bench tank cases/mps_embolization_unified_3d.yaml 2 6 \
            "--set domain.lo=[0,0,-1e-3] --set domain.symmetry=[x_lo,y_lo]" ;;
    *)
        echo "bench/symmetry.sh: unknown case '$name'" >&2
        exit 1 ;;
    esac
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
