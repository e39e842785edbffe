#!/bin/sh
# bench/peer_mps_basic.sh: ryushi's MPS against MPS-Basic (github.com/MPS-Basic/MPS-Basic, a
# C++17 MPS code with Eigen's BiCGSTAB and OpenMP) on MPS-Basic's 2D dam break at l0 = 5 mm:
# the same 6,955 particles (5,151 fluid in a 0.25 x 0.5 m column, walls of 2 + 2 dummy layers
# around a 1.0 x 0.6 m tank, open at the top), re = 3.1 l0, dt = 2e-4 s, 2,000 steps (0.4 s),
# water, no output. Runs alternate between the two programs; each prints its wall seconds and
# particle-steps/s; the medians and their ratio come last (docs/performance.md, "MPS against
# MPS-Basic").
#
# Building MPS-Basic outside this repository, offline (nothing of it is committed here): its
# CMakeLists fetches Eigen, googletest, yaml-cpp, fast-cpp-csv-parser and argparse at configure
# time; Debian's libeigen3-dev and googletest (apt) stand in for the first two and source
# copies of the other three (git clone or an archive of their repositories) for the rest:
#   cmake -S MPS_BASIC -B MPS_BASIC/build -DCMAKE_BUILD_TYPE=Release \
#     -DFETCHCONTENT_FULLY_DISCONNECTED=ON \
#     -DFETCHCONTENT_SOURCE_DIR_EIGEN=/usr/include/eigen3 \
#     -DFETCHCONTENT_SOURCE_DIR_GOOGLETEST=/usr/src/googletest \
#     -DFETCHCONTENT_SOURCE_DIR_YAML-CPP=YAML_CPP_SOURCE \
#     -DFETCHCONTENT_SOURCE_DIR_FAST-CPP-CSV-PARSER=CSV_PARSER_SOURCE \
#     -DFETCHCONTENT_SOURCE_DIR_ARGPARSE=ARGPARSE_SOURCE
#   cmake --build MPS_BASIC/build --target mps generate_dambreak -j 2
# The dam break's particles come from its generator (generator/generate_dambreak.cpp) with
# `double l0 = 0.025` changed to 0.005 before building it; this script runs it.
#
# Usage: sh bench/peer_mps_basic.sh RYUSHI MPS_BASIC_BUILD [THREADS]
#   MPS_BASIC_BUILD: the build folder holding `mps` and `generator/generate_dambreak`.
# Environment: REPS (runs of each, default 3), OUT (scratch folder, default a temporary one),
#              RY_SETS (KEY=VALUE overrides for ryushi, space-separated, e.g.
#              "scheme.solver.preconditioner=boomeramg").
# Exit status: 0 on success, 1 with a message on stderr when a run fails.
set -eu

[ $# -ge 2 ] || {
    echo "usage: sh bench/peer_mps_basic.sh RYUSHI MPS_BASIC_BUILD [THREADS]" >&2
    exit 1
}
RY=$1
MB=$2
THREADS=${3:-2}
REPS=${REPS:-3}
OUT=${OUT:-$(mktemp -d)}
mkdir -p "$OUT/mb/input/dambreak" "$OUT/mb/result"
NP=6955
STEPS=2000

# MPS-Basic's input: its generator writes input/dambreak/input.prof under the current folder.
(cd "$OUT/mb" && rm -f input/dambreak/input.* && "$MB/generator/generate_dambreak" >/dev/null)
n=$(sed -n 2p "$OUT/mb/input/dambreak/input.prof")
[ "$n" = "$NP" ] || {
    echo "bench/peer_mps_basic.sh: the generator gave $n particles, not $NP (l0 = 0.005?)" >&2
    exit 1
}
cat >"$OUT/mb/input/dambreak/settings.yml" <<EOF
dim: 2
particleDistance: 0.005
dt: 0.0002
endTime: 0.4
outputPeriod: 10.0
cflCondition: 0.3
numPhysicalCores: $THREADS
domainMin: [-0.1, -0.1, 0.0]
domainMax: [1.1, 2.0, 0.0]
defaultDensity: 1000.0
kinematicViscosity: 1.0e-06
xyz-input: true
gravity: [0.0, -9.8, 0.0]
gravity-norm: 9.8
gravity-angle: 0
surfaceDetection-numberDensity-threshold: 0.97
surfaceDetection-particleDistribution: true
surfaceDetection-particleDistribution-threshold: 1.0
pressureCalculationMethod: Implicit
compressibility: 0.45e-09
relaxationCoefficientForPressure: 0.2
soundSpeed: 17.1
collisionDistanceRatio: 0.5
coefficientOfRestitution: 0.2
radiusRatioForNumberDensity: 3.1
radiusRatioForGradient: 2.1
radiusRatioForLaplacian: 3.1
particlesPath: ./input.prof
outputVtkInBinary: true
EOF

# ryushi's: the same lattice (the column 51 x 101 particles, the tank's inside 201 x 121 points,
# 4 wall layers of which MPS makes the inner ones walls and the outer ones dummies), the same
# step, its own defaults otherwise (re 2.1 l0 for the gradient, 3.1 l0 for the Laplacian and
# the number density's source).
cat >"$OUT/ry.yaml" <<EOF
description: MPS-Basic's 2D dam break at l0 = 5 mm
dimension: 2
spacing: 0.005
gravity: [0.0, -9.8]
materials:
  - {name: water, density: 1000.0, viscosity: 1.0e-6}
bodies:
  - {name: column, type: box, lo: [-0.0025, -0.0025], hi: [0.2525, 0.5025]}
  - {name: tank, type: tank, lo: [-0.0025, -0.0025], hi: [1.0025, 0.6025], layers: 4, open_top: true}
domain: {lo: [-0.1, -0.1], hi: [1.1, 2.0]}
scheme: {name: mps, compressibility: 0.45e-9}
time: {end: 0.4, dt_max: 2.0e-4, cfl: 0.3, output_interval: 10.0}
output: {vtk: false}
EOF

ry_once() {
    sets=""
    for kv in ${RY_SETS:-}; do sets="$sets --set $kv"; done
    # shellcheck disable=SC2086
    "$RY" run "$OUT/ry.yaml" -o "$OUT/ry" --threads "$THREADS" $sets >"$OUT/ry.log" 2>&1 || {
        echo "bench/peer_mps_basic.sh: ryushi failed (see $OUT/ry.log)" >&2
        exit 1
    }
    s=$(grep '^summary' "$OUT/ry.log")
    np=$(printf '%s\n' "$s" | tr ' ' '\n' | sed -n 's/^particles=//p')
    st=$(printf '%s\n' "$s" | tr ' ' '\n' | sed -n 's/^steps=//p')
    w=$(printf '%s\n' "$s" | tr ' ' '\n' | sed -n 's/^wall_s=//p')
    echo "ryushi $np $st $w"
}

mb_once() {
    rm -rf "$OUT/mb/result" && mkdir -p "$OUT/mb/result"
    t0=$(date +%s.%N)
    (cd "$OUT/mb" && OMP_NUM_THREADS=$THREADS "$MB/mps" --setting input/dambreak/settings.yml \
        --output result >"$OUT/mb.log" 2>&1) || {
        echo "bench/peer_mps_basic.sh: MPS-Basic failed (see $OUT/mb.log)" >&2
        exit 1
    }
    t1=$(date +%s.%N)
    echo "mps-basic $NP $STEPS $(awk "BEGIN{print $t1 - $t0}")"
}

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "program particles steps wall_s particle_steps_per_s"
rep=0
while [ "$rep" -lt "$REPS" ]; do
    for p in ryushi mps-basic; do
        if [ "$p" = ryushi ]; then line=$(ry_once); else line=$(mb_once); fi
        set -- $line
        echo "$1 $2 $3 $4 $(awk "BEGIN{printf \"%.3g\", $2 * $3 / $4}")" | tee -a "$OUT/all.txt"
    done
    rep=$((rep + 1))
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
awk '{v[$1] = v[$1] " " $5} END {
    for (p in v) { n = split(v[p], a, " "); for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j)
        if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
        m[p] = n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
        printf "median %s %.3g particle-steps/s\n", p, m[p] }
    if (m["mps-basic"] > 0) printf "ratio ryushi / mps-basic %.2f\n", m["ryushi"] / m["mps-basic"] }' "$OUT/all.txt"
