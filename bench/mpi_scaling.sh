#!/bin/sh
# Strong and weak scaling of ryushi-mpi on the 2D seed dam break (WCSPH), 200 steps without VTK
# output, each configuration REPEATS times (default 3), medians reported (docs/parallel.md).
#   strong: 63,545 and 252,080 particles on 1 and 2 ranks of 1 thread, beside the serial
#           program on 1 and 2 OpenMP threads;
#   weak:   about 32,000 particles per rank on 1 and 2 ranks.
# usage: sh bench/mpi_scaling.sh [BUILD_DIR] [REPEATS]
set -eu
B=${1:-build}
REP=${2:-3}
CASE=cases/dam_break_seed.yaml
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
OUT=$(mktemp -d /tmp/ryushi_mpi_bench_XXXXXX)
trap 'rm -rf "$OUT"' EXIT

# one LABEL SPACING RANKS THREADS: median particle-steps/s (and communication share) of REP runs
one() {
    label=$1; sp=$2; np=$3; th=$4
    : > "$OUT/rates"
    i=0
    while [ "$i" -lt "$REP" ]; do
        if [ "$np" -eq 0 ]; then
            OMP_NUM_THREADS=$th "$B/ryushi" run "$CASE" -o "$OUT/run" --threads "$th" \
                --set spacing="$sp" --set time.max_steps=200 --set output.vtk=false > "$OUT/log"
        else
            OMP_NUM_THREADS=$th mpirun --oversubscribe -np "$np" "$B/ryushi-mpi" run "$CASE" \
                -o "$OUT/run" --threads "$th" --set spacing="$sp" --set time.max_steps=200 \
                --set output.vtk=false > "$OUT/log" 2>&1
        fi
        grep '^summary' "$OUT/log" | tr ' ' '\n' | awk -F= '
            $1 == "particles" { n = $2 } $1 == "particle_steps_per_s" { r = $2 }
            $1 == "comm_share" { c = $2 } $1 == "halo" { h = $2 }
            END { print r, (c == "" ? "-" : c), n, (h == "" ? "-" : h) }' >> "$OUT/rates"
        i=$((i + 1))
    done
    sort -g "$OUT/rates" | awk -v label="$label" -v np="$np" -v th="$th" '
        { r[NR] = $1; c[NR] = $2; n = $3; h = $4 }
        END { m = int((NR + 1) / 2);
              printf "%-8s %9d %6s %7s %12.4g %8s %7s   (runs:", label, n,
                     np == 0 ? "serial" : np, th, r[m], c[m], h;
              for (k = 1; k <= NR; ++k) printf " %.3g", r[k]; print ")" }'
}

echo "ryushi-mpi scaling: $CASE, 200 steps, medians of $REP runs; $(nproc) cores"
printf "%-8s %9s %6s %7s %12s %8s %7s\n" test particles ranks threads psteps/s comm halo
for sp in 0.00145 0.000725; do
    one strong "$sp" 0 1
    one strong "$sp" 1 1
    one strong "$sp" 2 1
    one strong "$sp" 0 2
done
one weak 0.00205 1 1
one weak 0.00145 2 1
