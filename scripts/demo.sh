#!/bin/sh
# make demo: runs the seed's 40x80 dam break to 0.6 s and says where the output went.
set -eu
RYUSHI=${1:-build/ryushi}
OUT=out/demo_dam_break
"$RYUSHI" run cases/dam_break_seed.yaml -o "$OUT"
echo
echo "demo: output in $OUT/"
echo "  $OUT/dam_break_seed.pvd   open in ParaView (File > Open) as a time series"
echo "  $OUT/series.csv           surge front front_x, mass, kinetic energy over time"
echo "  $OUT/case_resolved.yaml   every parameter of the run, defaults included"
