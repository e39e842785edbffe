#!/bin/sh
# bench/peer_splishsplash.sh: ryushi's IISPH against SPlisHSPlasH's IISPH
# (github.com/InteractiveComputerGraphics/SPlisHSPlasH) on SPlisHSPlasH's DamBreakModel scene at
# particle radius 0.01 m: 117,649 fluid particles (49^3, a 1 m cube) in a closed 4 x 3 x 1.5 m
# box, a fixed step of 1e-3 s (SPlisHSPlasH; ryushi at most 1e-3 s), 0.3 s, the cubic spline of
# support 0.04 m in both (about 30 neighbours), the solvers stopping at the same average density
# error, relaxation 0.5, no output. The same error: SPlisHSPlasH measures it after each Jacobi
# update, with a particle's new pressure against the neighbour sums of the old ones, which for a
# particle whose pressure is not clamped is (1 - omega) times the error before the update that
# ryushi measures (and SPlisHSPlasH leaves the clamped particles out, where ryushi counts the
# compressed ones). With omega = 0.5 SPlisHSPlasH's maxError 0.01 % is ryushi's tolerance 2e-4,
# the default of TOL below; TOL=1e-4 holds ryushi to twice the peer's accuracy. SPlisHSPlasH's walls are a volume map (Bender et al.
# 2019: no particles); ryushi's are two layers of particles (231,864), so both particle-steps
# per second are given: all particles, and fluid particles alone. Runs alternate; medians and
# ratios come last (docs/performance.md, "IISPH against SPlisHSPlasH").
#
# Building SPlisHSPlasH outside this repository, offline (nothing of it is committed here):
# Debian's libeigen3-dev and the X11/OpenGL/D-Bus headers its GUI libraries need (apt:
# libx11-dev libxrandr-dev libxinerama-dev libxcursor-dev libxi-dev libgl1-mesa-dev
# libglu1-mesa-dev libdbus-1-dev); source copies of Discregrid, GenericParameters,
# PositionBasedDynamics and CompactNSearch (InteractiveComputerGraphics on GitHub), each
# named in CMake/SetUpExternalProjects.cmake and CMake/NeighborhoodSearch.cmake by
# `SOURCE_DIR /path/to/copy` in place of its GIT_REPOSITORY and GIT_TAG lines; then
#   cmake -S SPH -B SPH/build -DCMAKE_BUILD_TYPE=Release -DUSE_PYTHON_BINDINGS=OFF
#   cmake --build SPH/build --target SPHSimulator -j 2
# (Measured with SPlisHSPlasH c5a063d and a CompactNSearch older than the one it pins, which
# lacks NeighborhoodSearch::reset: its one call, in SimulatorBase::reset, which only the GUI
# reaches, was removed.)
#
# Usage: sh bench/peer_splishsplash.sh RYUSHI SPLISHSPLASH_SOURCE [THREADS]
# Environment: REPS (runs of each, default 2), OUT (scratch folder, default a temporary one),
#              TOL (ryushi's scheme.tolerance, default 2e-4: the peer's criterion, above).
# Exit status: 0 on success, 1 with a message on stderr when a run fails.
set -eu

[ $# -ge 2 ] || {
    echo "usage: sh bench/peer_splishsplash.sh RYUSHI SPLISHSPLASH_SOURCE [THREADS]" >&2
    exit 1
}
RY=$1
SPH=$2
THREADS=${3:-2}
REPS=${REPS:-2}
OUT=${OUT:-$(mktemp -d)}
mkdir -p "$OUT"
NF=117649
TOL=${TOL:-2.0e-4}

# SPlisHSPlasH's scene, changed: IISPH, radius 0.01, the fixed step, 0.3 s, no export. It
# must sit beside the original (its box model is found relative to it).
SCENE=$SPH/data/Scenes/DamBreakModel_ryushi_bench.json
python3 - "$SPH/data/Scenes/DamBreakModel.json" "$SCENE" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
c = s["Configuration"]
c.update({"particleRadius": 0.01, "simulationMethod": 3, "cflMethod": 0, "timeStepSize": 0.001,
          "cflMaxTimeStepSize": 0.001, "stopAt": 0.3, "enablePartioExport": False,
          "enableVTKExport": False})
c.pop("DFSPH", None)
c["IISPH"] = {"minIterations": 2, "maxIterations": 100, "maxError": 0.01}
json.dump(s, open(sys.argv[2], "w"), indent=1)
EOF

# ryushi's: the same cube (49^3 on its lattice), box and kernel.
cat >"$OUT/ry.yaml" <<EOF
description: SPlisHSPlasH's DamBreakModel at particle radius 0.01 m (IISPH)
dimension: 3
spacing: 0.02
kernel: {type: cubic, h_over_dx: 1.0}
gravity: [0.0, -9.81, 0.0]
materials:
  - {name: water, density: 1000.0, viscosity: 1.0e-6}
bodies:
  - {name: column, type: box, lo: [-1.95, 0.05, -0.49], hi: [-0.97, 1.03, 0.49]}
  - {name: tank, type: tank, lo: [-2.0, 0.0, -0.75], hi: [2.0, 3.0, 0.75], layers: 2, open_top: false}
domain: {lo: [-2.2, -0.2, -0.95], hi: [2.2, 3.2, 0.95]}
scheme: {name: iisph, tolerance: $TOL, max_iterations: 100, relaxation: 0.5}
time: {end: 0.3, dt_max: 1.0e-3, cfl: 0.9, output_interval: 10.0}
output: {vtk: false}
EOF

field() { printf '%s\n' "$2" | tr ' ' '\n' | sed -n "s/^$1=//p"; }

ry_once() {
    "$RY" run "$OUT/ry.yaml" -o "$OUT/ry" --threads "$THREADS" >"$OUT/ry.log" 2>&1 || {
        echo "bench/peer_splishsplash.sh: ryushi failed (see $OUT/ry.log)" >&2
        exit 1
    }
    s=$(grep '^summary' "$OUT/ry.log")
    echo "ryushi $(field particles "$s") $(field steps "$s") $(field wall_s "$s") $(field iisph_iterations_mean "$s")"
}

sph_once() {
    OMP_NUM_THREADS=$THREADS "$SPH/bin/SPHSimulator" --no-gui --no-initial-pause \
        --output-dir "$OUT/sph" "$SCENE" >"$OUT/sph.log" 2>&1 || {
        echo "bench/peer_splishsplash.sh: SPlisHSPlasH failed (see $OUT/sph.log)" >&2
        exit 1
    }
    n=$(sed -n 's/^Number of fluid particles: //p' "$OUT/sph.log")
    ms=$(sed -n 's/^Average time: SimStep: \([0-9.e+-]*\) ms/\1/p' "$OUT/sph.log")
    steps=$(awk '/^Total number: Time step size:/ {printf "%d", $NF / 0.001 + 0.5}' "$OUT/sph.log")
    it=$(sed -n 's/^Average number: IISPH - iterations: //p' "$OUT/sph.log")
    echo "splishsplash $n $steps $(awk "BEGIN{print $ms * $steps / 1000}") $it"
}

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "program particles steps time_loop_s iterations_per_step particle_steps_per_s fluid_particle_steps_per_s"
rep=0
while [ "$rep" -lt "$REPS" ]; do
    for p in ryushi splishsplash; do
        if [ "$p" = ryushi ]; then line=$(ry_once); else line=$(sph_once); fi
        set -- $line
        echo "$1 $2 $3 $4 $5 $(awk "BEGIN{printf \"%.3g %.3g\", $2 * $3 / $4, $NF * $3 / $4}")" |
            tee -a "$OUT/all.txt"
    done
    rep=$((rep + 1))
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
awk '{a[$1] = a[$1] " " $6; f[$1] = f[$1] " " $7} END {
    for (p in a) { n = split(a[p], x, " "); split(f[p], y, " ")
        for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) {
            if (x[j] < x[i]) { t = x[i]; x[i] = x[j]; x[j] = t }
            if (y[j] < y[i]) { t = y[i]; y[i] = y[j]; y[j] = t } }
        ma[p] = n % 2 ? x[(n + 1) / 2] : (x[n / 2] + x[n / 2 + 1]) / 2
        mf[p] = n % 2 ? y[(n + 1) / 2] : (y[n / 2] + y[n / 2 + 1]) / 2
        printf "median %s %.3g particle-steps/s, %.3g fluid particle-steps/s\n", p, ma[p], mf[p] }
    if (mf["splishsplash"] > 0)
        printf "ratio ryushi / splishsplash: %.2f (all particles), %.2f (fluid)\n",
            ma["ryushi"] / ma["splishsplash"], mf["ryushi"] / mf["splishsplash"] }' "$OUT/all.txt"
