#!/bin/sh
# bench/linear_solvers.sh: the implicit solves of MPS with the Jacobi preconditioner (built in)
# and with hypre's BoomerAMG, each case at two spacings (a factor 2): iterations per solve and
# seconds per step in the solver, and seconds per step in all (docs/reference/mps.md, "Linear
# solver").
#
# Usage: sh bench/linear_solvers.sh RYUSHI [THREADS]
# Environment: CASES (names from the list below, default all), OUT (scratch folder, default a
#              temporary one).
# Cases (output off; the runs from the case's start):
#   dam2d    cases/mps_dam_break_mm.yaml at a/40 and a/80 to 0.1 s (MPS, 2D)
#   dam3d    cases/mps_dam_break_3d.yaml at 0.02 and 0.01 m to 0.2 s (MPS, 3D)
#   embol3d  the seed's tank, cases/mps_embolization_3d_coarse.yaml (0.2 mm) and
#            cases/mps_embolization_3d.yaml (0.1 mm), 20 steps at dt = 1e-4 s (MPS, 3D, implicit
#            viscosity of the embolic liquid)
# Each run prints one line: case, spacing, preconditioner, the hierarchy's reuse, particles,
# steps, pressure iterations per solve, pressure-solve seconds per step, viscous iterations per
# step (three components together) and seconds, seconds per step, particle-steps/s, peak memory.
# Exit status: 0 on success, 1 with a message on stderr when a run fails.
set -eu

[ $# -ge 1 ] || {
    echo "usage: sh bench/linear_solvers.sh RYUSHI [THREADS]" >&2
    exit 1
}
RY=$1
THREADS=${2:-2}
CASES=${CASES:-dam2d dam3d embol3d}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT=${OUT:-$(mktemp -d)}
mkdir -p "$OUT"

field() { # field NAME LINE: the value of NAME= in a summary line (- when absent)
    v=$(printf '%s\n' "$2" | tr ' ' '\n' | sed -n "s/^$1=//p")
    printf '%s' "${v:--}"
}

one() { # one NAME CASE SPACING PRECOND REUSE [--set ...]
    name=$1 case=$2 dx=$3 pc=$4 reuse=$5
    shift 5
    log=$OUT/$name.log
    # (deflation, which some cases set, goes with the Jacobi preconditioner alone)
    [ "$pc" = jacobi ] || set -- "$@" --set scheme.solver.deflation=0
    if ! "$RY" run "$ROOT/$case" -o "$OUT/$name" --threads "$THREADS" --set output.vtk=false \
        --set spacing="$dx" --set scheme.solver.preconditioner="$pc" \
        --set scheme.solver.viscosity_preconditioner="$pc" --set scheme.solver.amg_reuse="$reuse" \
        "$@" >"$log" 2>&1; then
        echo "bench/linear_solvers.sh: $name failed (see $log)" >&2
        exit 1
    fi
    s=$(grep '^summary' "$log")
    steps=$(field steps "$s")
    wall=$(field wall_s "$s")
    vi=$(field viscous_iterations_mean "$s")
    vs=$(field viscous_solve_s "$s")
    printf '%-8s %-10s %-9s %5s %8s %6s %7s %9s %7s %9s %9s %10s %8s\n' "${name%%_*}" "$dx" "$pc" "$reuse" \
        "$(field particles "$s")" "$steps" "$(field ppe_iterations_mean "$s")" \
        "$(field ppe_solve_s "$s")" "$vi" "$vs" "$(awk "BEGIN{printf \"%.4g\", $wall/$steps}")" \
        "$(field particle_steps_per_s "$s")" "$(field peak_rss_mb "$s")"
}

printf '%-8s %-10s %-9s %5s %8s %6s %7s %9s %7s %9s %9s %10s %8s\n' case spacing precond reuse \
    particles steps p_iter p_solve_s v_iter v_solve_s step_s psteps_s peak_mb
for c in $CASES; do
    case $c in
    dam2d)
        for dx in 0.00142875 0.000714375; do
            for v in "jacobi 1" "boomeramg 1" "boomeramg 10"; do
                set -- $v
                one "dam2d_${dx}_$1_$2" cases/mps_dam_break_mm.yaml "$dx" "$1" "$2" \
                    --set time.end=0.1 --set time.output_interval=0.01
            done
        done
        ;;
    dam3d)
        for dx in 0.02 0.01; do
            for v in "jacobi 1" "boomeramg 1" "boomeramg 10"; do
                set -- $v
                one "dam3d_${dx}_$1_$2" cases/mps_dam_break_3d.yaml "$dx" "$1" "$2" \
                    --set time.end=0.2
            done
        done
        ;;
    embol3d)
        for f in "2.0e-4 cases/mps_embolization_3d_coarse.yaml" "1.0e-4 cases/mps_embolization_3d.yaml"; do
            set -- $f
            dx=$1 file=$2
            for v in "jacobi 1" "boomeramg 1" "boomeramg 10"; do
                set -- $v
                one "embol3d_${dx}_$1_$2" "$file" "$dx" "$1" "$2" \
                    --set time.max_steps=20 --set time.dt_max=1e-4
            done
        done
        ;;
    *)
        echo "bench/linear_solvers.sh: unknown case '$c'" >&2
        exit 1
        ;;
    esac
done
