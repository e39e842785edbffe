#!/bin/sh
# bench/mps_walls.sh: what the walls cost an MPS step as unknowns of the pressure equation
# (scheme.wall_pressure: unknown, the default) and out of it (neumann; docs/reference/mps.md,
# "Walls"). The two alternate, REPS times; medians.
#
# Usage: sh bench/mps_walls.sh RYUSHI [THREADS]
# Environment: CASES (names from the list below, default "dam2d dam3d tank"), REPS (default 3),
#              OUT (scratch folder, default a temporary one).
# Cases (output off, from rest):
#   dam2d  cases/mps_dam_break_mm.yaml at a/80 (15,767 particles), 200 steps
#   dam3d  cases/mps_dam_break_3d.yaml at 0.01 m (86,696 particles), 40 steps
#   tank   cases/mps_embolization_3d.yaml, the seed's tank at 0.1 mm (179,840 particles), 10 steps
# Each run prints: the mode, seconds per step (the time loop's), the pressure equation's unknowns
# and the walls among them (wall and inflow particles, means per solve), iterations per solve,
# and per solve the seconds of the solver, of the assembly (matrix and right-hand side) and of the
# walls' extrapolated pressure, and the peak memory in MB. The medians' line gives the walls'
# share of a step: as unknowns, their share of the unknowns times the solve and the assembly,
# plus the extrapolation; out of the equation, the extrapolation and what the assembly grew by
# per fluid unknown (the hydrostatic terms of the walls' pairs).
# Exit status: 0 on success, 1 with a message on stderr when a run fails.
set -eu

[ $# -ge 1 ] || {
    echo "usage: sh bench/mps_walls.sh RYUSHI [THREADS]" >&2
    exit 1
}
RY=$1
THREADS=${2:-2}
CASES=${CASES:-dam2d dam3d tank}
REPS=${REPS:-3}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT=${OUT:-$(mktemp -d)}
mkdir -p "$OUT"

field() { # field NAME LINE: the value of NAME= in a summary line
    printf '%s\n' "$2" | tr ' ' '\n' | sed -n "s/^$1=//p"
}

run() { # run MODE CASE STEPS ARGS...: one line of the fields above
    mode=$1 c=$2 steps=$3
    shift 3
    "$RY" run "$ROOT/$c" -o "$OUT/run" --threads "$THREADS" --set time.max_steps="$steps" \
        --set output.vtk=false --set scheme.wall_pressure="$mode" "$@" >"$OUT/run.log" 2>&1 || {
        echo "bench/mps_walls.sh: $c ($mode) failed (see $OUT/run.log)" >&2
        exit 1
    }
    s=$(grep '^summary' "$OUT/run.log")
    echo "$mode $(awk "BEGIN { printf \"%.4f\", $(field wall_s "$s") / $(field steps "$s") }")" \
        "$(field ppe_unknowns_mean "$s") $(field ppe_wall_unknowns_mean "$s")" \
        "$(field ppe_iterations_mean "$s") $(field ppe_solve_s "$s") $(field ppe_assembly_s "$s")" \
        "$(field wall_extrapolation_s "$s") $(field peak_rss_mb "$s")"
}

bench() { # bench NAME CASE STEPS [ARGS...]
    name=$1 c=$2 steps=$3
    shift 3
    : >"$OUT/$name.all"
    rep=0
    while [ "$rep" -lt "$REPS" ]; do
        for mode in unknown neumann; do
            line=$(run "$mode" "$c" "$steps" "$@")
            echo "$name rep $rep: $line"
            echo "$line" >>"$OUT/$name.all"
        done
        rep=$((rep + 1))
    done
    awk -v name="$name" '
        function med(m, c,   k, i, j, t, v) {
            k = 0
            for (i = 1; i <= NR; ++i) if (mode[i] == m) v[++k] = val[i, c]
            for (i = 1; i <= k; ++i) for (j = i + 1; j <= k; ++j) if (v[j] < v[i]) { t = v[i]; v[i] = v[j]; v[j] = t }
            return k % 2 ? v[(k + 1) / 2] : (v[k / 2] + v[k / 2 + 1]) / 2
        }
        { mode[NR] = $1; for (c = 2; c <= NF; ++c) val[NR, c] = $c }
        END {
            for (c = 2; c <= 9; ++c) { u[c] = med("unknown", c); n[c] = med("neumann", c) }
            fu = (u[3] - u[4]) / u[3]                 # fluid share of the unknowns (walls solved)
            before = (u[4] / u[3] * (u[6] + u[7]) + u[8]) / u[2]
            grow = n[7] - u[7] * fu; if (grow < 0) grow = 0
            after = (n[8] + grow) / n[2]
            printf "%s median: s/step %.4f -> %.4f (x%.2f), unknowns %d (walls %d) -> %d, iterations %.1f -> %.1f, solve s %.4f -> %.4f, assembly s %.4f -> %.4f, extrapolation s %.5f -> %.5f, peak MB %d -> %d; walls %.1f %% of a step -> %.1f %%\n",
                name, u[2], n[2], u[2] / n[2], u[3], u[4], n[3], u[5], n[5], u[6], n[6], u[7], n[7], u[8], n[8], u[9], n[9], 100 * before, 100 * after
        }' "$OUT/$name.all"
}

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg), threads $THREADS"
for name in $CASES; do
    case $name in
    dam2d) bench dam2d cases/mps_dam_break_mm.yaml 200 --set spacing=0.000714375 ;;
    dam3d) bench dam3d cases/mps_dam_break_3d.yaml 40 --set spacing=0.01 ;;
    tank) bench tank cases/mps_embolization_3d.yaml 10 ;;
    *)
        echo "bench/mps_walls.sh: unknown case '$name'" >&2
        exit 1 ;;
    esac
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
