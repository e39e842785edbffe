#!/bin/sh
# bench/pysph_compare.sh: throughput of ryushi against PySPH on the same 2D dam break.
#
# PySPH's packaged example pysph.examples.dam_break_2d (Debian package python3-pysph, installed
# here with apt-get when missing; it is not a build dependency of ryushi) is a water column of
# width L = 1 m and height 2L in an open tank 4L wide and 4L high with 4 layers of boundary
# particles. ryushi runs cases/dam_break_seed.yaml (column 0.25 m x 0.5 m, so L = 0.25 m) with
# the tank raised to 4L and given 4 wall layers, so that both codes have the same geometry, and
# with spacing = DX x 0.25 m, the same resolution in units of L: the particle counts, fluid and
# wall, agree to a few per cent.
#
# For each code, serially and on 2 threads, it runs STEPS time steps from rest, REPS times, and
# takes the median of particle-steps/s = (fluid + wall particles) x steps / wall seconds of the
# time loop:
#   - PySPH: "Run took" from its log (the time of solver.solve(): set-up and the C compilation
#     of its generated kernels are not included), particles from "Total:" in its log, steps
#     checked against its "control handler: count=" log lines. Serial: the build without
#     OpenMP (--no-openmp); 2 threads: --openmp with OMP_NUM_THREADS=2. One short warm-up run
#     per build first compiles the kernels into ~/.pysph, so no timed run compiles.
#   - ryushi: particle_steps_per_s= from the summary line of `build/ryushi run` (time loop
#     only), --threads 1 and --threads 2, VTK output off.
# Then it prints one table and the ratios ryushi/PySPH at 1 and 2 threads.
#
# Usage: sh bench/pysph_compare.sh            (from anywhere; as root if PySPH is missing)
# Environment: DX (PySPH spacing in m, default 0.02: 7603 particles), STEPS (default 400),
#              REPS (default 3), PYTHON (default /usr/bin/python3, the interpreter Debian's
#              python3-pysph is installed for).
# Exit status: 0 on success, 1 with a message on stderr when a step fails.
# Other work on the cores makes the numbers noisy, the 2-thread ones most: the table states the
# load average before and after the runs.
set -eu

DX=${DX:-0.02}
STEPS=${STEPS:-400}
REPS=${REPS:-3}
PYTHON=${PYTHON:-/usr/bin/python3}
SCALE=0.25 # ryushi's column width L in m (PySPH's is 1 m)

die() {
    echo "pysph_compare: error: $*" >&2
    exit 1
}
note() { echo "pysph_compare: $*" >&2; }

ROOT=$(cd "$(dirname "$0")/.." && pwd) || die "cannot find the repository root"
cd "$ROOT"

case $STEPS in '' | *[!0-9]*) die "STEPS must be a positive integer, got '$STEPS'" ;; esac
case $REPS in '' | *[!0-9]*) die "REPS must be a positive integer, got '$REPS'" ;; esac
if [ "$STEPS" -lt 1 ] || [ "$REPS" -lt 1 ]; then die "STEPS and REPS must be at least 1"; fi

# --- PySPH -------------------------------------------------------------------------------
if ! dpkg-query -W -f='${Status}' python3-pysph 2>/dev/null | grep -q 'ok installed'; then
    [ "$(id -u)" -eq 0 ] || die "python3-pysph is not installed; run as root or apt-get install python3-pysph"
    note "installing python3-pysph (apt-get)"
    apt-get update >/dev/null || die "apt-get update failed"
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends python3-pysph \
        >/dev/null || die "apt-get install python3-pysph failed"
fi
[ -x "$PYTHON" ] || die "no Python interpreter at $PYTHON (set PYTHON)"
"$PYTHON" -c 'import pysph.examples.dam_break_2d' 2>/dev/null ||
    die "$PYTHON cannot import pysph.examples.dam_break_2d (python3-pysph is for Debian's python3)"

# --- ryushi ------------------------------------------------------------------------------
if [ ! -x build/ryushi ]; then
    note "build/ryushi is missing: make build"
    make build >/dev/null || die "make build failed"
fi
[ -x build/ryushi ] || die "build/ryushi still missing after make build"

WORK=$(mktemp -d "${TMPDIR:-/tmp}/pysph_compare.XXXXXX") || die "mktemp failed"
trap 'rm -rf "$WORK"' EXIT
trap 'exit 130' INT TERM

load=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo 0)
if awk -v l="$load" 'BEGIN { exit !(l > 0.5) }'; then
    note "warning: load average $load before the runs: other work shares the cores, numbers will be noisy"
fi

# median of the numbers on standard input (one per line)
median() { sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) exit 1; print v[int((NR + 1) / 2)] }'; }

# pysph_run MODE THREADS STEPS DIR: one run of the example; prints "particles steps seconds t_end"
pysph_run() {
    p_mode=$1 p_threads=$2 p_steps=$3 p_dir=$4
    rm -rf "$p_dir"
    if [ "$p_mode" = omp ]; then p_flag=--openmp; else p_flag=--no-openmp; fi
    OMP_NUM_THREADS=$p_threads "$PYTHON" -m pysph.examples.dam_break_2d --dx "$DX" \
        --max-steps "$p_steps" --disable-output -q -v debug $p_flag -d "$p_dir" \
        >"$p_dir.out" 2>&1 || {
        tail -n 20 "$p_dir.out" >&2
        die "PySPH run failed ($p_mode, $p_threads thread(s), $p_steps steps)"
    }
    p_log=$p_dir/dam_break_2d.log
    [ -f "$p_log" ] || die "PySPH wrote no log $p_log"
    awk '
        /^ *Total: [0-9]+/ { n = $2 }
        /Run took:/ { for (i = 1; i <= NF; ++i) if ($i == "took:") s = $(i + 1) }
        /control handler: count=/ { sub(/.*count=/, ""); c = $0 + 0 }
        /Iteration=[0-9]+, time=/ {
            line = $0; sub(/.*time=/, "", line); split(line, a, /, timestep=/); t = a[1] + a[2] }
        END { if (n == "" || s == "" || c == "") exit 1; print n, c, s, t }' "$p_log" ||
        die "cannot read particles, steps and run time from $p_log"
}

# ryushi_run THREADS STEPS DIR: one run; prints the summary line
RY_SPACING=$(awk -v d="$DX" -v s="$SCALE" 'BEGIN { printf "%.9g", d * s }')
ryushi_run() {
    r_threads=$1 r_steps=$2 r_dir=$3
    OMP_NUM_THREADS=$r_threads build/ryushi run cases/dam_break_seed.yaml -o "$r_dir" \
        --set spacing="$RY_SPACING" --set 'bodies[1].hi=[1.0,1.0]' --set 'bodies[1].layers=4' \
        --set output.vtk=false --set time.max_steps="$r_steps" --threads "$r_threads" \
        >"$r_dir.out" 2>&1 || {
        tail -n 20 "$r_dir.out" >&2
        die "ryushi run failed ($r_threads thread(s), $r_steps steps)"
    }
    r_line=$(tail -n 1 "$r_dir.out")
    case $r_line in *particle_steps_per_s=*) ;; *) die "no summary line from ryushi: $r_line" ;; esac
    echo "$r_line"
}
field() { # field KEY LINE
    printf '%s\n' "$2" | tr ' ' '\n' | sed -n "s/^$1=//p"
}

# --- warm-up (compiles PySPH's kernels into ~/.pysph on a first run; not timed) -----------
note "warm-up: PySPH serial and OpenMP builds, ryushi (a first PySPH run compiles its kernels, about 20 s per build)"
for mode in serial omp; do
    t0=$(date +%s)
    pysph_run "$mode" 1 5 "$WORK/warm_$mode" >/dev/null
    note "  PySPH $mode warm-up: $(($(date +%s) - t0)) s (start-up, set-up and compilation, not timed)"
done
ryushi_run 1 20 "$WORK/warm_ry" >/dev/null

# --- timed runs ----------------------------------------------------------------------------
RESULTS=$WORK/results # code threads particles steps rate
: >"$RESULTS"
for threads in 1 2; do
    if [ "$threads" = 1 ]; then mode=serial; else mode=omp; fi
    : >"$WORK/py_rates"
    : >"$WORK/ry_rates"
    r=1
    while [ "$r" -le "$REPS" ]; do
        res=$(pysph_run "$mode" "$threads" "$STEPS" "$WORK/py_${threads}_$r") || exit 1
        # shellcheck disable=SC2086 # four numbers, split on purpose
        set -- $res
        py_n=$1 py_steps=$2 py_s=$3 py_t=$4
        [ "$py_steps" -eq "$STEPS" ] || die "PySPH took $py_steps steps, expected $STEPS"
        rate=$(awk -v n="$py_n" -v k="$py_steps" -v s="$py_s" 'BEGIN { printf "%.6g", n * k / s }')
        echo "$rate" >>"$WORK/py_rates"
        note "  PySPH  threads=$threads run $r: $py_n particles, $py_steps steps, ${py_s} s, $rate particle-steps/s, t=$py_t s"

        line=$(ryushi_run "$threads" "$STEPS" "$WORK/ry_${threads}_$r") || exit 1
        ry_n=$(field particles "$line") ry_steps=$(field steps "$line")
        ry_rate=$(field particle_steps_per_s "$line") ry_t=$(field t "$line")
        [ "$ry_steps" -eq "$STEPS" ] || die "ryushi took $ry_steps steps, expected $STEPS"
        echo "$ry_rate" >>"$WORK/ry_rates"
        note "  ryushi threads=$threads run $r: $ry_n particles, $ry_steps steps, $(field wall_s "$line") s, $ry_rate particle-steps/s, t=$ry_t s"
        r=$((r + 1))
    done
    echo "PySPH $threads $py_n $STEPS $(median <"$WORK/py_rates")" >>"$RESULTS"
    echo "ryushi $threads $ry_n $STEPS $(median <"$WORK/ry_rates")" >>"$RESULTS"
done

# --- table -------------------------------------------------------------------------------
echo
echo "2D dam break (column L x 2L in a 4L x 4L open tank), PySPH --dx $DX, ryushi spacing $RY_SPACING m;"
echo "median of $REPS runs of $STEPS steps; particle-steps/s = (fluid + wall particles) x steps / wall s"
echo "$(nproc) processors; load average $load before the runs, $(cut -d' ' -f1 /proc/loadavg) after"
awk '
    { code[NR] = $1; th[NR] = $2; n[NR] = $3; k[NR] = $4; v[NR] = $5; rate[$1, $2] = $5 }
    END {
        printf "%-8s %10s %8s %8s %18s\n", "code", "particles", "threads", "steps", "particle-steps/s"
        for (i = 1; i <= NR; ++i)
            if (code[i] == "PySPH") printf "%-8s %10d %8d %8d %18.4g\n", code[i], n[i], th[i], k[i], v[i]
        for (i = 1; i <= NR; ++i)
            if (code[i] == "ryushi") printf "%-8s %10d %8d %8d %18.4g\n", code[i], n[i], th[i], k[i], v[i]
        for (t = 1; t <= 2; t *= 2)
            printf "ratio ryushi/PySPH at %d thread%s: %.2f\n", t, (t > 1 ? "s" : ""), rate["ryushi", t] / rate["PySPH", t]
        printf "speed-up 2 threads / 1 thread: PySPH %.2f, ryushi %.2f\n",
            rate["PySPH", 2] / rate["PySPH", 1], rate["ryushi", 2] / rate["ryushi", 1]
    }' "$RESULTS" || die "cannot print the table"
