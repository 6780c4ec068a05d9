#!/usr/bin/env bash
# The two commands of this project on a fresh Debian 12 machine (both set everything up first:
# Debian packages, a Python virtual environment, the build):
#
#   ./run.sh main   runs the main job on the default drive: results, plots and a summary
#   ./run.sh test   runs all tests (C++ unit and system tests with ctest, Python tests with pytest)
#
# Installing Debian packages needs root (or sudo). Environment: CHAINDRIVE_BUILD (build
# directory, default ./build), CHAINDRIVE_VENV (default ./.venv), CHAINDRIVE_RESULTS (default ./results).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$ROOT"
export CHAINDRIVE_BUILD="${CHAINDRIVE_BUILD:-$ROOT/build}"
VENV="${CHAINDRIVE_VENV:-$ROOT/.venv}"

APT_PACKAGES=(build-essential cmake ninja-build pkg-config libeigen3-dev libsundials-dev libsuitesparse-dev
              nlohmann-json3-dev libgtest-dev python3 python3-venv python3-pip)

install_system_packages() {
  local missing=()
  for p in "${APT_PACKAGES[@]}"; do
    dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "== installing Debian packages: ${missing[*]}"
    local sudo=""
    [ "$(id -u)" -ne 0 ] && sudo="sudo"
    $sudo apt-get update -q
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q "${missing[@]}"
  fi
}

setup_python() {
  if [ ! -x "$VENV/bin/python" ]; then
    echo "== creating the Python environment $VENV"
    python3 -m venv "$VENV"
  fi
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check -r harness/requirements.txt
}

build() {
  echo "== building into $CHAINDRIVE_BUILD"
  cmake -S . -B "$CHAINDRIVE_BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE="$VENV/bin/python" >/dev/null
  cmake --build "$CHAINDRIVE_BUILD" -j "$(nproc)"
}

setup() {
  install_system_packages
  setup_python
  build
}

case "${1:-}" in
  main)
    shift
    setup
    "$VENV/bin/python" -m harness.main "$@"
    ;;
  test)
    shift
    setup
    echo "== C++ tests"
    ctest --test-dir "$CHAINDRIVE_BUILD" --output-on-failure -j 2
    echo "== Python tests"
    "$VENV/bin/python" -m pytest -q tests/python "$@"
    ;;
  *)
    echo "usage: ./run.sh main [options of python -m harness.main] | ./run.sh test" >&2
    exit 2
    ;;
esac
