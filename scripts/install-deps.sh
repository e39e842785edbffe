#!/bin/sh
# Installs the Debian packages ryushi needs to build, test, fuzz (clang with libFuzzer and its
# OpenMP runtime), draw its pictures, solve by algebraic multigrid (hypre, with OpenMPI), run
# distributed (ryushi-mpi) and be driven from Python (python/ryushi: NumPy; its tests: pytest, PyYAML).
# Idempotent: packages already present are skipped; nothing is downloaded otherwise.
set -eu
PKGS="cmake make gcc pkg-config python3 python3-numpy python3-pytest python3-yaml libfyaml-dev libcmocka-dev libcairo2-dev zlib1g-dev clang-format clang libclang-rt-14-dev libomp-dev libopenmpi-dev openmpi-bin libhypre-dev"
missing=""
for p in $PKGS; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $p"
  fi
done
if [ -z "$missing" ]; then
  exit 0
fi
echo "install-deps: installing$missing"
SUDO=""
if [ "$(id -u)" != "0" ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "install-deps: need root (or sudo) to install:$missing" >&2; exit 1; fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq || true
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq --no-install-recommends $missing
