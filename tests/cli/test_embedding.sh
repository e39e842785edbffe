#!/bin/sh
# The library as a user embeds it: installed with `cmake --install` into a prefix, the complete
# example of docs/embedding.md compiled against the installed header through pkg-config and run;
# libryushi.so exports the interface of ryushi.h alone and links no cairo; Python drives it
# through ctypes (tests/api/ctypes_dam_break.py), and the installed Python package finds it.
# usage: test_embedding.sh RYUSHI SOURCE_DIR
set -u
RY=$1
SRC=$2
. "$SRC/tests/cli/lib.sh"
BUILD=$(dirname "$RY")
LIB="$BUILD/libryushi.so"

cmake --install "$BUILD" --prefix "$T/inst" > "$T/install.log" 2>&1 && ok ||
    bad "cmake --install failed: $(cat "$T/install.log")"
for f in bin/ryushi lib/libryushi.so include/ryushi/ryushi.h lib/pkgconfig/ryushi.pc \
    lib/python3/dist-packages/ryushi/__init__.py; do
    [ -e "$T/inst/$f" ] || bad "not installed: $f"
done

# the example of docs/embedding.md, compiled against the installed library
sed -n '/^```c$/,/^```$/p' "$SRC/docs/embedding.md" | sed '1d;$d' > "$T/example.c"
flags=$(PKG_CONFIG_PATH="$T/inst/lib/pkgconfig" pkg-config --cflags --libs ryushi) ||
    bad "pkg-config does not find ryushi"
# shellcheck disable=SC2086
cc -std=c11 -Wall -Wextra -Werror "$T/example.c" $flags -Wl,-rpath,"$T/inst/lib" \
    -o "$T/example" 2> "$T/cc.log" && ok || bad "the example does not compile: $(cat "$T/cc.log")"
"$T/example" "$SRC/cases" "$T/ex" > "$T/example.log" 2>&1 && ok ||
    bad "the example failed: $(cat "$T/example.log")"
grep -q "fluid mass 125.000000 kg/m" "$T/example.log" && grep -q "t = 0.100 s" "$T/example.log" &&
    ok || bad "the example's output: $(cat "$T/example.log")"

# exports: ry_* functions only; no cairo
others=$(nm -D --defined-only "$LIB" | awk '$2 ~ /[TDBR]/ && $3 !~ /^ry_/ { print $3 }')
[ -z "$others" ] && ok || bad "libryushi.so exports more than ryushi.h: $others"
n=$(nm -D --defined-only "$LIB" | awk '$3 ~ /^ry_/' | wc -l)
m=$(grep -c '^RY_API ' "$SRC/include/ryushi/ryushi.h")
[ "$n" -eq "$m" ] && ok || bad "libryushi.so exports $n functions, ryushi.h declares $m"
ldd "$LIB" | grep -q cairo && bad "libryushi.so links cairo" || ok

# Python, through ctypes
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
"$PY" "$SRC/tests/api/ctypes_dam_break.py" "$LIB" "$SRC/cases" "$T/py" > "$T/py.log" 2>&1 && ok ||
    bad "ctypes: $(cat "$T/py.log")"

# the installed Python package finds the installed library
where=$(cd "$T" && env -u RYUSHI_LIBRARY PYTHONPATH="$T/inst/lib/python3/dist-packages" "$PY" -c \
    'import ryushi; print(ryushi.library)' 2>&1)
[ "$where" = "$T/inst/lib/libryushi.so" ] && ok ||
    bad "the installed package: $where (want $T/inst/lib/libryushi.so)"

printf "embedding tests: "
finish
