#!/bin/sh
# Soak run: a small dam break (10 x 20 fluid particles in the seed tank) for STEPS steps
# (default 1e6), with series.csv rows every simulated second, checkpoints every 100,000 steps
# (two kept) and VTK output every 50 s. While it runs, the resident memory and the number of
# open file descriptors of the process are sampled every 5 s. At the end: fluid mass drift,
# kinetic energy (bounded: it must not grow past its first peak), memory and descriptors first
# vs last sample. Results in OUT/soak.txt (default OUT: out/soak).
# usage: sh bench/soak.sh [STEPS] [OUT]   (from the repository root, after make build)
set -eu
STEPS=${1:-1000000}
OUT=${2:-out/soak}
RY=${RY:-build/ryushi}
rm -rf "$OUT"
mkdir -p "$OUT"
"$RY" run cases/dam_break_seed.yaml -o "$OUT/run" --threads 1 \
    --set spacing=0.025 --set time.end=1e9 --set time.max_steps="$STEPS" \
    --set time.output_interval=1.0 --set checkpoint.every_steps=100000 --set checkpoint.keep=2 \
    --set output.vtk=false > "$OUT/run.log" 2>&1 &
pid=$!
echo "t_s rss_kb fds" > "$OUT/samples.txt"
start=$(date +%s)
while kill -0 "$pid" 2>/dev/null; do
    rss=$(awk '/^VmRSS/ {print $2}' "/proc/$pid/status" 2>/dev/null || echo "")
    fds=$(ls "/proc/$pid/fd" 2>/dev/null | wc -l)
    [ -n "$rss" ] && echo "$(($(date +%s) - start)) $rss $fds" >> "$OUT/samples.txt"
    sleep 5
done
wait "$pid" || { echo "soak: the run failed"; tail -3 "$OUT/run.log"; exit 1; }
wall=$(($(date +%s) - start))
awk -F, -v steps="$STEPS" -v wall="$wall" '
    NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    NR == 2 { m0 = $col["mass"]; kmax = 0 }
    { m = $col["mass"]; k = $col["kinetic_energy"]; if (k > kmax) kmax = k; n = NR - 1;
      dm = (m - m0) / m0; if (dm < 0) dm = -dm; if (dm > dmax) dmax = dm; t = $1; s = $2;
      if (NR > 2 && $col["outside"] > out) out = $col["outside"] }
    END { printf "steps %d, simulated %.1f s, %d rows, wall %d s\n", s, t, n, wall;
          printf "fluid mass: largest relative change %.3g\n", dmax;
          printf "kinetic energy: largest %.6g J, last %.6g J\n", kmax, k;
          printf "particles outside the domain: at most %d\n", out }' \
    "$OUT/run/series.csv" > "$OUT/soak.txt"
awk 'NR == 2 { r0 = $2; f0 = $3 } NR > 1 { r = $2; f = $3; if ($2 > rmax) rmax = $2;
     if ($3 > fmax) fmax = $3 }
     END { printf "resident memory: first %d kB, last %d kB, largest %d kB\n", r0, r, rmax;
           printf "open file descriptors: first %d, last %d, largest %d\n", f0, f, fmax }' \
    "$OUT/samples.txt" >> "$OUT/soak.txt"
grep summary "$OUT/run.log" >> "$OUT/soak.txt"
cat "$OUT/soak.txt"
