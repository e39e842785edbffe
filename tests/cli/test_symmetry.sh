#!/bin/sh
# Symmetry planes (domain.symmetry, docs/reference/symmetry.md): half, a quarter or an eighth
# of a symmetric problem, run with its planes, gives the full run's series.csv (the whole
# problem's measurements) within a relative 1e-6 in every column (validation/symmetry.yaml;
# the sums are taken in another order and the full run is mirror-symmetric only up to
# rounding; counts exactly): a hydrostatic column (IISPH, and MPS with implicit viscosity, its
# pressure profile on the plane too), the 3D dam break cut along its width (WCSPH, and MPS
# with its pressure solved by Jacobi, deflated and by BoomerAMG), the 2D embolization tank
# with mixed viscosity, drops cut by two planes (IISPH with CSF, MPS with the potential model)
# and a 3D drop by three (IISPH), the 3D cantilever (solid) and the open-boundary channel cut
# along its axis. The VTK output holds the simulated part; a run stopped at a checkpoint and
# continued ends bitwise identical to an uninterrupted one; an unstable run keeps its last
# good state.
# usage: test_symmetry.sh RYUSHI SOURCE_DIR
set -u
RY=$1
SRC=$2
. "$SRC/tests/cli/lib.sh"
# the tolerance of `ryushi validate symmetry` (validation/symmetry.yaml): 1e-6
TOL=$(sed -n 's/^ *series_max_dev: *//p' "$SRC/validation/symmetry.yaml")
[ -n "$TOL" ] || { echo "FAIL: no series_max_dev in validation/symmetry.yaml"; exit 1; }

# pair NAME CASE "FULL ARGS" "PART ARGS" [SKIP]: both runs; their series.csv agree in every
# column (but SKIP) within 1e-6 (absolute below 1e-12; the time step, written to six digits,
# within 1e-5), with the same rows
pair() {
    p_name=$1; p_case=$2; p_full=$3; p_part=$4; p_skip=${5:-}
    # shellcheck disable=SC2086
    "$RY" run "$SRC/cases/$p_case" -o "$T/${p_name}_full" $p_full > "$T/${p_name}_full.log" 2>&1 ||
        { bad "$p_name: the full run failed: $(tail -3 "$T/${p_name}_full.log")"; return; }
    # shellcheck disable=SC2086
    "$RY" run "$SRC/cases/$p_case" -o "$T/${p_name}_part" $p_full $p_part \
        > "$T/${p_name}_part.log" 2>&1 ||
        { bad "$p_name: the run with planes failed: $(tail -3 "$T/${p_name}_part.log")"; return; }
    agree "$T/${p_name}_full/series.csv" "$T/${p_name}_part/series.csv" "$p_name" "$p_skip"
}

# agree A B WHAT [SKIP]: CSV files A and B have the same header and rows, every value within
# 1e-6 (a column named dt within 1e-5; none of the column named SKIP)
agree() {
    if awk -F, -v skip="${4:-}" -v rel="$TOL" 'NR == FNR { a[FNR] = $0; n = FNR; next }
        FNR == 1 { if ($0 != a[1]) { print "headers differ"; bad = 1 } for (j = 1; j <= NF; j++) h[j] = $j; next }
        { split(a[FNR], x, ","); rows++
          for (j = 1; j <= NF; j++) { if (h[j] == skip) continue
            d = x[j] - $j; if (d < 0) d = -d; m = x[j] < 0 ? -x[j] : x[j]
            tol = h[j] == "dt" ? 1e-5 : rel
            if (d > tol * m && d > 1e-12) { print "row " FNR " " h[j] ": " x[j] " vs " $j; bad = 1 } } }
        END { if (FNR != n) { print n " rows vs " FNR; bad = 1 }
              if (rows < 3) { print "only " rows " rows"; bad = 1 } exit bad }' \
        "$1" "$2" > "$T/agree.out"; then
        ok
    else
        bad "$3: $(head -5 "$T/agree.out")"
    fi
}

# 1. Hydrostatic columns cut at their middle: IISPH, and MPS (implicit viscosity, its solve's
# velocity components carrying the mirror's signs) with its pressure profile along the plane.
pair iisph_column hydrostatic_iisph.yaml "--set time.end=0.4 --set time.output_interval=0.1" \
    "--set domain.lo=[0.2,-0.02] --set domain.symmetry=[x_lo]"
pair mps_column mps_hydrostatic.yaml \
    "--set time.end=0.5 --set time.output_interval=0.1 --set profiles[0].average_from=0" \
    "--set domain.lo=[0.1,-0.05] --set domain.symmetry=[x_lo]"
agree "$T/mps_column_full/profile_column.csv" "$T/mps_column_part/profile_column.csv" \
    "MPS column: the pressure profile along the plane"

# 2. The 3D dam break cut along its width (0.25 m, ten spacings each side of the plane).
D3="--set spacing=0.025 --set time.end=0.3 --set time.output_interval=0.05"
HALF="--set domain.hi=[1.1,0.125,1.5] --set domain.symmetry=[y_hi]"
pair wcsph_dam dam_break_3d.yaml "$D3" "$HALF"
pair mps_dam mps_dam_break_3d.yaml "$D3" "$HALF"
# MPS folds the copies' coefficients of its pressure equation onto their originals and solves
# the half in one piece: deflation and BoomerAMG serve it as they serve the whole (their
# iterations differ: the coarse spaces are not the same)
pair mps_dam_deflated mps_dam_break_3d.yaml "$D3 --set scheme.solver.deflation=4" "$HALF" \
    ppe_iterations
pair mps_dam_amg mps_dam_break_3d.yaml "$D3 --set scheme.solver.preconditioner=boomeramg" \
    "$HALF" ppe_iterations

# The 2D embolization tank halved through the catheter's axis, its viscosity mixed (implicit
# for the embolic liquid, explicit for the water: each copy on its original's side of the split)
pair mps_tank mps_embolization_unified_2d_coarse.yaml \
    "--set time.end=0.01 --set time.output_interval=0.002 --set scheme.viscosity=mixed" \
    "--set domain.lo=[0,-1e-3] --set domain.symmetry=[x_lo]" ppe_iterations

# 3. Drops at rest cut by two planes through their centre: a quarter simulated.
QUARTER="--set domain.lo=[0,0] --set domain.symmetry=[x_lo,y_lo]"
pair iisph_drop iisph_drop_rest_2d.yaml "--set time.end=0.004 --set time.output_interval=0.001" \
    "$QUARTER"
# and a 3D one by three: an eighth
pair iisph_drop_3d iisph_drop_rest_3d.yaml \
    "--set time.end=0.001 --set time.output_interval=0.00025 --set output.vtk=false" \
    "--set domain.lo=[0,0,0] --set domain.symmetry=[x_lo,y_lo,z_lo]"
pair mps_drop mps_drop_rest_2d.yaml "--set time.end=0.002 --set time.output_interval=0.00025" \
    "$QUARTER"

# 4. The 3D cantilever (its end load the whole beam's) and the open-boundary channel (its
# inflow and outflow volumes the whole channel's), each cut by its plane of symmetry.
pair cantilever cantilever_3d.yaml "--set time.end=3 --set time.output_interval=1" \
    "--set domain.lo=[-0.2,0,-0.6] --set domain.symmetry=[y_lo]"
pair channel channel_inflow.yaml "--set time.end=0.5 --set time.output_interval=0.1" \
    "--set domain.hi=[0.5,0.05] --set domain.symmetry=[y_hi]"

# 5. The VTK output holds the simulated part (half the particles), series.csv the whole.
pts=$(grep -a -o 'NumberOfPoints="[0-9]*"' "$T/mps_dam_part/mps_dam_break_3d_00006.vtp" | tr -dc '0-9')
whole=$(tail -1 "$T/mps_dam_part/series.csv" | cut -d, -f4)
[ "$((2 * pts))" = "$whole" ] && ok || bad "VTK: $pts points, series.csv $whole particles"

# 6. Restart: stopped at step 37 (between searches) and continued on another thread count.
"$RY" run "$SRC/cases/mps_dam_break_3d.yaml" -o "$T/ck" $D3 $HALF --set time.max_steps=37 \
    > "$T/ck.log" 2>&1 || bad "the run stopped at step 37 failed: $(tail -3 "$T/ck.log")"
# shellcheck disable=SC2086
"$RY" run "$SRC/cases/mps_dam_break_3d.yaml" $D3 $HALF --threads 2 --restart "$T/ck" \
    > "$T/ck2.log" 2>&1 || bad "restart failed: $(tail -3 "$T/ck2.log")"
n=0
for f in "$T/mps_dam_part"/*.vtp "$T/mps_dam_part"/*.csv; do
    n=$((n + 1))
    cmp -s "$f" "$T/ck/$(basename "$f")" || bad "restart: $(basename "$f") differs"
done
[ "$n" -ge 7 ] && ok || bad "restart: only $n files compared"

# 7. A run that goes unstable (gravity 200 times too strong) keeps its last good state, the
# simulated part, bitwise that of a run stopped at that step.
UNST="--set domain.symmetry=[y_hi] --set domain.hi=[1.1,0.125,1.5] --set gravity=[0,0,-2000]"
# shellcheck disable=SC2086
out=$("$RY" run "$SRC/cases/dam_break_3d.yaml" $D3 $UNST -o "$T/u" 2>&1)
good=$(printf '%s' "$out" | sed -n 's/.*last good state (step \([0-9]*\),.*/\1/p')
if [ -n "$good" ]; then
    # shellcheck disable=SC2086
    "$RY" run "$SRC/cases/dam_break_3d.yaml" $D3 $UNST --set time.max_steps="$good" -o "$T/u2" \
        > /dev/null 2>&1
    cmp -s "$T/u/dam_break_3d_last_good.vtp" "$T/u2/dam_break_3d_00001.vtp" && ok ||
        bad "the last good state (step $good) differs from a run stopped there"
else
    bad "unstable run: no last good state: $out"
fi

finish
