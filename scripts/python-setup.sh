#!/bin/sh
# `make python`: puts the repository's python/ on the path of Debian's python3 (a ryushi.pth
# file in the user's site-packages), so that `python3 -c 'import ryushi'` works from anywhere;
# the package finds the library in build/ (RYUSHI_LIBRARY overrides). Run after the build.
# usage: sh scripts/python-setup.sh [BUILD_DIR]
set -eu
BUILD=${1:-build}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
SITE=$("$PY" -m site --user-site)
mkdir -p "$SITE"
echo "$ROOT/python" > "$SITE/ryushi.pth"
if [ "$BUILD" != build ]; then
  echo "python: the library is in $BUILD/: set RYUSHI_LIBRARY=$ROOT/$BUILD/libryushi.so"
  export RYUSHI_LIBRARY="$ROOT/$BUILD/libryushi.so"
fi
cd /
version=$("$PY" -c 'import ryushi; print(ryushi.__version__)')
echo "python: ryushi $version for $PY ($SITE/ryushi.pth -> $ROOT/python)"
echo "python: try  $PY -c 'import ryushi; help(ryushi.Simulation)'  (docs/python.md)"
