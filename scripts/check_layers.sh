#!/bin/sh
# scripts/check_layers.sh: the library's layers hold (docs/ARCHITECTURE.md).
#
#   sh scripts/check_layers.sh SOURCE_DIR [OBJECT_DIR]
#
# Every file under src/ and include/ryushi/ belongs to a layer, by its folder (src/) or by the
# table below (public headers). A file may include a header, and an object file may call a
# function, of its own layer or a lower one only; no two files depend on each other through a
# chain of includes and calls (no cycle); no source file is longer than MAX_LINES (800). With
# OBJECT_DIR (a CMake build's CMakeFiles folder), the calls are read from the object files' symbol
# tables (nm); without it, only the includes and the sizes are checked.
# Exit status: 0 when everything holds; 1 with each violation on stderr.
set -eu

[ $# -ge 1 ] || {
    echo "usage: sh scripts/check_layers.sh SOURCE_DIR [OBJECT_DIR]" >&2
    exit 1
}
ROOT=$1
OBJ=${2:-}
MAX_LINES=${MAX_LINES:-800}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$ROOT"

# The layers, lowest first. A folder of src/ names its layer; so does each public header.
cat >"$WORK/layers" <<'EOF'
0 util src/util/
1 io src/io/
2 core src/core/ src/kernel/ src/neighbor/ src/geometry/
3 pairs src/pairs/
4 physics src/physics/ src/linalg/ src/boundary/
5 schemes src/schemes/
6 measure src/measure/
7 sim src/sim/
8 api src/api/
9 validate src/validate/ src/plot/
10 cli src/cli/ src/parallel/
EOF
cat >"$WORK/headers" <<'EOF'
util status.h atomic_file.h clock.h
io case.h csv.h checkpoint.h stl.h
core particles.h kernel.h kernel_shapes.h corrected.h neighbor.h bench.h geometry.h sim.h material.h beam.h
physics rheology.h surface_tension.h collisions.h open_boundary.h
schemes mps.h schemes.h
measure probes.h solid.h
sim run.h output.h
api ryushi.h
validate plot.h manifest.h validate.h
EOF

# file -> layer number (every file under src/ and include/ryushi/)
find src include/ryushi -type f \( -name '*.c' -o -name '*.h' \) | sort >"$WORK/files"
awk 'FNR == NR && FILENAME ~ /layers$/ { num[$2] = $1; for (k = 3; k <= NF; ++k) dir[$k] = $1; next }
     FILENAME ~ /headers$/ { for (k = 2; k <= NF; ++k) hdr["include/ryushi/" $k] = num[$1]; next }
     { f = $0; l = ""
       if (f in hdr) l = hdr[f]
       else for (d in dir) if (index(f, d) == 1) l = dir[d]
       if (l == "") { print "check_layers: " f ": no layer (add its folder or header to scripts/check_layers.sh)" > "/dev/stderr"; bad = 1 }
       else print f, l }
     END { exit bad }' "$WORK/layers" "$WORK/headers" "$WORK/files" >"$WORK/layer_of" || status=1
status=${status:-0}

# include edges: file -> included file (quoted includes that resolve to a file here)
# shellcheck disable=SC2046 # file names without spaces
grep -H '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' $(cat "$WORK/files") |
    sed 's/^\([^:]*\):.*"\([^"]*\)".*/\1 \2/' | while read -r f inc; do
    case $inc in
    ryushi/*) t=include/$inc ;;
    *) t=src/$inc ;;
    esac
    if [ -f "$t" ]; then echo "$f $t include"; fi
done >"$WORK/edges"

# call edges: the object of file A uses a symbol the object of file B defines
if [ -n "$OBJ" ]; then
    find "$OBJ" -path '*.dir/src/*' -name '*.c.o' | sort | while read -r o; do
        src=src/${o#*.dir/src/}
        src=${src%.o}
        [ -f "$src" ] || continue # an object left from a file since moved or removed
        nm -g "$o" | awk -v s="$src" 'NF == 3 && $2 ~ /[TDBRC]/ { print "D", s, $3 } NF == 2 && $1 == "U" { print "U", s, $2 }'
    done >"$WORK/symbols"
    awk '$1 == "D" { def[$3] = $2; next } { use[n] = $2; sym[n++] = $3 }
         END { for (k = 0; k < n; ++k) if ((sym[k] in def) && def[sym[k]] != use[k]) print use[k], def[sym[k]], "call", sym[k] }' \
        "$WORK/symbols" | sort -u >>"$WORK/edges"
fi

# no edge goes up a layer
awk 'FNR == NR { layer[$1] = $2; next }
     ($1 in layer) && ($2 in layer) && layer[$1] + 0 < layer[$2] + 0 {
         what = $3 == "call" ? "calls " $4 " of" : "includes"
         print "check_layers: " $1 " (layer " layer[$1] ") " what " " $2 " (layer " layer[$2] "): a lower layer may not use a higher one"
         bad = 1 }
     END { exit bad }' "$WORK/layer_of" "$WORK/edges" >&2 || status=1

# no cycle between files (tsort names the files of each loop)
awk '$1 != $2 { print $1, $2 }' "$WORK/edges" | sort -u >"$WORK/pairs"
if ! tsort "$WORK/pairs" >/dev/null 2>"$WORK/tsort"; then
    sed -e '/input contains a loop/d' -e 's/^tsort: /check_layers: in a cycle: /' "$WORK/tsort" >&2
    status=1
fi

# no file too long to read
while read -r f; do
    n=$(wc -l <"$f")
    if [ "$n" -gt "$MAX_LINES" ]; then
        echo "check_layers: $f: $n lines (at most $MAX_LINES)" >&2
        status=1
    fi
done <"$WORK/files"

if [ "$status" -eq 0 ]; then
    echo "check_layers: $(wc -l <"$WORK/files") files in 11 layers, $(wc -l <"$WORK/pairs") dependencies: no upward use, no cycle, none over $MAX_LINES lines"
fi
exit "$status"
