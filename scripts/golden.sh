#!/bin/sh
# scripts/golden.sh: a fingerprint of ryushi's results on a set of short runs that together
# reach every scheme, both WCSPH pair loops, walls, open boundaries, surface tension, rheology,
# two-phase flow and the solid schemes. A restructuring that must not change a single result
# compares the fingerprints of the builds before and after:
#
#   sh scripts/golden.sh OLD/ryushi > before.txt
#   sh scripts/golden.sh build/ryushi > after.txt
#   diff before.txt after.txt            # no output: byte-identical series.csv and VTK files
#
# Each line: case label, file, SHA-256 of the file. Runs on THREADS threads (default 2); the
# results do not depend on it. Environment: CASES (labels from the list below, default all).
# Exit status: 0 on success, 1 with a message on stderr when a run fails.
set -eu

[ $# -ge 1 ] || {
    echo "usage: sh scripts/golden.sh RYUSHI" >&2
    exit 1
}
BIN=$1
THREADS=${THREADS:-2}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

# label | case file | --set arguments (steps bounded so that the whole set runs in minutes)
LIST='
dam_list|dam_break_seed|spacing=0.0125 time.end=0.12 time.output_interval=0.04 scheme.pair_loop=list
dam_cells|dam_break_seed|spacing=0.0125 time.end=0.12 time.output_interval=0.04 scheme.pair_loop=cells
dam_3d|dam_break_3d|time.max_steps=20
dam_energy_list|dam_break_seed|spacing=0.0125 time.end=0.08 time.output_interval=0.04 scheme.energy=true scheme.variable_h=true scheme.pair_loop=list
dam_energy_cells|dam_break_seed|spacing=0.0125 time.end=0.08 time.output_interval=0.04 scheme.energy=true scheme.variable_h=true scheme.pair_loop=cells
cavity|cavity_seed|time.max_steps=300
channel|channel_inflow|time.end=0.4
rayleigh_taylor|rayleigh_taylor|time.max_steps=200
wcsph_drop|wcsph_droplet_square|time.max_steps=200
sph_oldroyd|sph_oldroyd_b_startup|time.max_steps=200
iisph_air|dam_break_mm_iisph_air|time.max_steps=60
iisph_drop|iisph_droplet_square|time.max_steps=60
iisph_carreau|iisph_carreau_poiseuille|time.max_steps=60
eye|eye_posterior_drain|time.max_steps=10
mps_drop|mps_droplet_square|time.max_steps=60
mps_cube|mps_droplet_cube20|time.max_steps=10
mps_two_liquid|mps_two_liquid_drop|time.max_steps=40
mps_oldroyd|mps_oldroyd_b_startup|time.max_steps=60
mps_emb2d|mps_embolization_2d_coarse|time.max_steps=40
mps_emb3d|mps_embolization_3d_coarse|time.max_steps=4
mps_thin|mps_thin_wall_cavities|time.max_steps=40
cantilever|cantilever|time.max_steps=400
plate_tl|oscillating_plate_tl|time.max_steps=200
plate|oscillating_plate|time.max_steps=200
buckling|filament_buckling|time.max_steps=200
'

echo "$LIST" | while IFS='|' read -r label file sets; do
    [ -n "$label" ] || continue
    if [ -n "${CASES:-}" ]; then
        case " $CASES " in *" $label "*) ;; *) continue ;; esac
    fi
    args="--set output.vtk=true"
    for s in $sets; do args="$args --set $s"; done
    out="$WORK/$label"
    # shellcheck disable=SC2086 # the --set arguments are words
    if ! OMP_NUM_THREADS=$THREADS "$BIN" run "$ROOT/cases/$file.yaml" $args --threads "$THREADS" \
        -o "$out" >"$WORK/$label.log" 2>&1; then
        echo "golden: error: $label ($file) failed:" >&2
        tail -5 "$WORK/$label.log" >&2
        exit 1
    fi
    (cd "$out" && find . -maxdepth 1 -type f \( -name 'series.csv' -o -name '*.vtp' \
        -o -name 'profile_*.csv' \) | sort | while read -r f; do
        echo "$label ${f#./} $(sha256sum "$f" | cut -d' ' -f1)"
    done)
done
