#!/usr/bin/env bash
# The two commands of this project on a fresh Debian 12 machine (both set everything up first:
# Debian packages, a Python virtual environment, the build):
#
#   ./run.sh main   runs the main job on the default drive: results, plots and a summary
#                   (--scene cvt: on the default chain CVT)
#   ./run.sh test   runs all tests (C++ unit and system tests with ctest, Python tests with pytest),
#                   then the sanitizer stage: the C++ tests and the FMI call-sequence fuzz built
#                   with AddressSanitizer and UndefinedBehaviorSanitizer (any report fails it)
#   ./run.sh sweep  speed sweeps and run-ups on Dask with Campbell diagrams (options of
#                   python -m harness sweep; set-up first, as the other two)
#   ./run.sh package the FMUs for download: dist/ChainDrive.fmu and dist/CVTChain.fmu with linux64
#                   (glibc 2.17) and win64 binaries and their sources (python -m harness package)
#   ./run.sh export --drive FILE [--out DIR]  the FMU of a drive: DIR/<name>.fmu, its interface
#                   generated from the drive (python -m harness export), with the packaged binaries
#                   where ./run.sh package made them, else the native build's
#
# ./run.sh test packages the FMUs too (their cross builds beside the native build and the C++
# tests) and runs them on both platforms (the Windows binary under wine) and from their sources.
#
# Each command sets up only what changed since the last set-up (stamps of pyproject.toml and of
# the build's sources; see setup): a second ./run.sh main --help answers at once. ./run.sh test
# always builds. Installing Debian packages needs root (or sudo). Environment: CHAINDRIVE_BUILD (build
# directory, default ./build), CHAINDRIVE_SANITIZE_BUILD (the sanitizer build, default
# ./build-sanitize), CHAINDRIVE_SANITIZE_STAGE (0 skips the sanitizer stage; default 1),
# CHAINDRIVE_VENV (default ./.venv), CHAINDRIVE_RESULTS (default ./results).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$ROOT"
export CHAINDRIVE_BUILD="${CHAINDRIVE_BUILD:-$ROOT/build}"
SANITIZE_BUILD="${CHAINDRIVE_SANITIZE_BUILD:-$ROOT/build-sanitize}"
VENV="${CHAINDRIVE_VENV:-$ROOT/.venv}"

APT_PACKAGES=(build-essential cmake ninja-build pkg-config libeigen3-dev libsundials-dev libsuitesparse-dev
              nlohmann-json3-dev libgtest-dev python3 python3-venv python3-pip
              libtbb12 procps)  # procps: pgrep (run.sh); libtbb12: the ecos co-simulation library of PyPI ecospy (tests/python/fmu/test_grid.py)
# the tests run the packaged FMUs' Windows binaries under wine (tests/python/package), from a
# master program built with MinGW-w64's GCC (harness/package/compare.py)
TEST_APT_PACKAGES=(wine64 gcc-mingw-w64-x86-64-win32)

install_system_packages() {
  local missing=()
  for p in "${APT_PACKAGES[@]}" "$@"; do
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

# The set-up is skipped when nothing it depends on changed since it last succeeded (pip and cmake
# take some 7 s even with nothing to do): a stamp in the virtual environment holds the hash of
# pyproject.toml and the optional dependencies installed, one in the build directory the hash of
# what the build is made from (the CMake files, the sources, the model descriptions, the C++ tests)
# and of the environment it was configured with.
PIP_STAMP="$VENV/.chaindrive-pip-stamp"
BUILD_STAMP="$CHAINDRIVE_BUILD/.chaindrive-build-stamp"
BUILD_INPUTS=(CMakeLists.txt cmake src fmu modelDescription tests/cpp tests/fuzz)

pyproject_hash() { sha256sum < pyproject.toml | cut -d' ' -f1; }

build_inputs_hash() {
  { echo "$VENV $CHAINDRIVE_BUILD"
    find "${BUILD_INPUTS[@]}" -type f -print0 | sort -z | xargs -0 sha256sum
  } | sha256sum | cut -d' ' -f1
}

# $1: optional dependencies (comma list); true if pyproject.toml is unchanged and they are installed
python_ready() {
  [ -x "$VENV/bin/python" ] && [ -f "$PIP_STAMP" ] || return 1
  local hash="" installed="" extra
  { read -r hash; read -r installed; } < "$PIP_STAMP" || true
  [ "$hash" = "$(pyproject_hash)" ] || return 1
  for extra in ${1//,/ }; do
    [[ ",$installed," == *",$extra,"* ]] || return 1
  done
}

build_ready() {
  [ -f "$BUILD_STAMP" ] && [ -f "$CHAINDRIVE_BUILD/ChainDrive.fmu" ] && [ "$(cat "$BUILD_STAMP")" = "$(build_inputs_hash)" ]
}

create_venv() {
  if [ ! -x "$VENV/bin/python" ]; then
    echo "== creating the Python environment $VENV"
    python3 -m venv "$VENV"
  fi
}

# The builds need of Python only fmpy's FMI 2 headers (CMakeLists.txt) and zig (the cross
# builds): pyproject.toml's fmpy and ziglang first, without their dependencies (pip adds those
# with the rest), so that every build can start while pip installs the rest
build_python_ready() {
  create_venv
  "$VENV/bin/python" -c "import importlib.util as u; assert u.find_spec('fmpy') and u.find_spec('ziglang')" \
    2>/dev/null && return 0
  local pins
  pins="$(grep -o '"\(fmpy\|ziglang\)==[^"]*"' pyproject.toml | tr -d '"' | paste -sd ' ')"
  echo "== installing $pins into $VENV (what the builds need of Python)"
  # shellcheck disable=SC2086
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check --no-deps $pins
}

# $1: the package's optional dependencies to install (pyproject.toml), besides those installed before
setup_python() {
  python_ready "$1" && return 0
  local first="" extras="$1" installed=""
  create_venv
  [ -f "$PIP_STAMP" ] || first=1
  # the extras installed before stay: a later call that asks for fewer finds them in the stamp
  [ -f "$PIP_STAMP" ] && installed="$(sed -n 2p "$PIP_STAMP")"
  [ -n "$installed" ] && extras="$(echo "$installed,$1" | tr ',' '\n' | sort -u | paste -sd, -)"
  local hash
  hash="$(pyproject_hash)"
  # the harness as a package (pyproject.toml), editable: harness/ is used in place
  if [ -n "$first" ]; then
    echo "== installing the Python packages of pyproject.toml (numpy, scipy, matplotlib, fmpy, dask, ...; extras" \
         "[$extras]) into $VENV: the first time takes several minutes, pip shows its progress"
    "$VENV/bin/python" -m pip install --disable-pip-version-check -e ".[$extras]"
  else
    echo "== updating the Python packages of pyproject.toml [$extras] in $VENV"
    "$VENV/bin/python" -m pip install -q --disable-pip-version-check -e ".[$extras]"
  fi
  printf '%s\n%s\n' "$hash" "$extras" > "$PIP_STAMP"
}

build() {
  configure_build
  compile_build
}

configure_build() {
  local first=""
  [ -f "$CHAINDRIVE_BUILD/build.ninja" ] || first=" (the first build takes about 10 minutes on 2 cores)"
  echo "== building into $CHAINDRIVE_BUILD$first"
  cmake -S . -B "$CHAINDRIVE_BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE="$VENV/bin/python" >/dev/null
}

compile_build() {
  local hash
  hash="$(build_inputs_hash)"  # (before the build: a source changed meanwhile is built next time)
  cmake --build "$CHAINDRIVE_BUILD" -j "$(nproc)"
  echo "$hash" > "$BUILD_STAMP"
}

# The sanitizer stage: a second build with -DCHAINDRIVE_SANITIZE=ON (AddressSanitizer with the
# leak checker, UndefinedBehaviorSanitizer), then its ctest: the C++ tests of
# tests/cpp/sanitizer_tests.txt (the code that reads a user's input and the code indexed by it)
# and FmiCallFuzz (random FMI call sequences, tests/fuzz, in two halves) and DriveFuzz (random drive
# descriptions through the export and the FMU's initialization). Debug with -O1: Eigen's
# index and size assertions stay on (an index past a row that stays inside the matrix's
# allocation is invisible to AddressSanitizer), and -O1 keeps Eigen's inlining: the C++ tests
# take about 7 times the CPU time of the release build. -g1: line tables, all a report's stack
# needs (a batch of the core 99 CPU s against 118 s with -g).
# the sanitizers' options, for the build (GoogleTest's discovery runs the test program) and ctest:
# every report ends the process with a non-zero status (with -fno-sanitize-recover=all from
# CMake): the test fails and so does this command; leaks are reported at exit (and by the fuzz
# after every few sequences); detect_stack_use_after_return costs some 15 % and finds
# references to dead locals
sanitizer_options() {
  export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1:print_stacktrace=1:strict_string_checks=1:check_initialization_order=1:strict_init_order=1:detect_stack_use_after_return=1"
  export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:report_error_type=1"
}

# (the test programs only; the build runs the sanitized test binary too: GoogleTest's test discovery)
sanitizer_build() {
  sanitizer_options
  cmake -S . -B "$SANITIZE_BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
        -DCMAKE_C_FLAGS_DEBUG="-O1 -g1" -DCHAINDRIVE_SANITIZE=ON -DPython3_EXECUTABLE="$VENV/bin/python" \
        -DCHAINDRIVE_TEST_CACHE_DIR="$CHAINDRIVE_BUILD/calibration-cache" >/dev/null
  cmake --build "$SANITIZE_BUILD" -j "$(nproc)" --target test_programs
}

sanitizer_tests() {
  sanitizer_options
  local start=$SECONDS
  echo "== sanitizer stage: C++ tests and FmiCallFuzz (ctest)"
  # the span calibrations the release build's ctest and pytest computed, for the fuzz as for the
  # tests (CHAINDRIVE_TEST_CACHE_DIR above): computing them is not repeated under the sanitizers
  export CHAINDRIVE_CACHE_DIR="$CHAINDRIVE_BUILD/calibration-cache"
  ctest --test-dir "$SANITIZE_BUILD" --output-on-failure -j 2
  echo "== sanitizer stage: ctest took $((SECONDS - start)) s; the fuzz reported:"
  sed -n '/^fmi_call_fuzz: [0-9]* sequences, seeds/,/^  failing sequences/p' "$SANITIZE_BUILD/Testing/Temporary/LastTest.log" |
    grep -v ' 0 sequences, '  # (the plans a run did not take)
}

# $1: a background job's pid, $2: its log, $3: what it is; prints the log once the job ended and
# stops the command if it failed
wait_for_background() {
  local status=0
  wait "$1" || status=$?
  cat "$2"
  if [ "$status" != 0 ]; then
    echo "$3 failed (exit status $status; log: $2)" >&2
    exit 1
  fi
}

# the builds run in the background end with the command, also when a stage before them failed
stop_background_jobs() {
  local pid
  for pid in $(jobs -p); do
    kill_tree "$pid"
  done
}

# (each process stopped before its children are listed: it starts none meanwhile)
kill_tree() {
  local child
  kill -STOP "$1" 2>/dev/null || return 0
  for child in $(pgrep -P "$1"); do
    kill_tree "$child"
  done
  kill "$1" 2>/dev/null || true
  kill -CONT "$1" 2>/dev/null || true
}

# Debian packages, the Python environment and the build, each when needed (nothing when the
# stamps say that nothing changed)
setup() {
  python_ready test && build_ready && return 0
  install_system_packages
  setup_python test
  build_ready || build
}

case "${1:-}" in
  main)
    shift
    setup
    "$VENV/bin/python" -m harness run "$@"
    ;;
  sweep)
    shift
    setup
    "$VENV/bin/python" -m harness sweep "$@"
    ;;
  export)
    shift
    setup
    "$VENV/bin/python" -m harness export "$@"
    ;;
  package)
    shift
    python_ready test,package || { install_system_packages; setup_python test,package; }
    "$VENV/bin/python" -m harness package "$@"
    ;;
  test)
    shift
    trap stop_background_jobs EXIT
    stage=$SECONDS
    install_system_packages
    # the native build (always: ctest needs the build of the sources as they are; cheap when
    # nothing changed) starts as soon as it can: the tests' Debian packages and pip's install of
    # the rest (some minutes on a fresh machine, mostly downloads) run beside it
    build_python_ready
    configure_build
    native_log="$CHAINDRIVE_BUILD/native-build.log"
    echo "== the native build: beside the set-up (log: $native_log)"
    # (at nice 5: on a fresh machine the longest chain is the cross builds', zig compiling its
    # runtimes one file at a time, and it gets three quarters of a core beside the native build)
    (renice -n 5 -p "$BASHPID" >/dev/null; compile_build) > "$native_log" 2>&1 &
    native_pid=$!
    if [ "${CHAINDRIVE_SANITIZE_STAGE:-1}" != 0 ]; then
      # the sanitizer stage's build beside everything, at the lowest priority (nice 19): it takes
      # only the CPU the other stages leave idle (downloads, links, the ends of the builds; pytest
      # leaves it almost nothing) and finishes after pytest
      mkdir -p "$SANITIZE_BUILD"
      sanitize_log="$SANITIZE_BUILD/sanitizer-build.log"
      echo "== the sanitizer stage's build: beside the rest at the lowest priority (log: $sanitize_log)"
      (renice -n 19 -p "$BASHPID" >/dev/null; sanitizer_build) > "$sanitize_log" 2>&1 &
      sanitize_pid=$!
    fi
    # the FMUs' cross builds (linux64, win64) run beside the native build and the C++ tests: on a
    # fresh machine most of their time is zig compiling each platform's C runtime and libc++ one
    # source at a time, which leaves a core to the rest
    cross_log="$CHAINDRIVE_BUILD/package-binaries.log"
    echo "== the FMUs' linux64 and win64 binaries: building beside the rest (log: $cross_log)"
    "$VENV/bin/python" -m harness package --binaries-only > "$cross_log" 2>&1 &
    cross_pid=$!
    install_system_packages "${TEST_APT_PACKAGES[@]}"
    setup_python test,package
    wait_for_background "$native_pid" "$native_log" "the native build"
    echo "== set-up and build: $((SECONDS - stage)) s"; stage=$SECONDS
    echo "== C++ tests"
    ctest --test-dir "$CHAINDRIVE_BUILD" --output-on-failure -j 2
    echo "== C++ tests: $((SECONDS - stage)) s"; stage=$SECONDS
    echo "== the FMUs for download (dist/)"
    wait_for_background "$cross_pid" "$cross_log" "the FMUs' cross builds"
    echo "== the cross builds finished $((SECONDS - stage)) s after the C++ tests"
    "$VENV/bin/python" -m harness package
    echo "== packaging: $((SECONDS - stage)) s"; stage=$SECONDS
    echo "== Python tests"
    # the span model's calibrations (src/span/calibration_cache.h) kept beside the build, as ctest's;
    # one worker per core (pytest-xdist), each test file on one worker (its module fixtures made once),
    # the files in the order collected: the slowest first (tests/python/conftest.py), not xdist's
    # default of the files with the most tests first
    CHAINDRIVE_CACHE_DIR="${CHAINDRIVE_CACHE_DIR:-$CHAINDRIVE_BUILD/calibration-cache}" \
      "$VENV/bin/python" -m pytest -q -n auto --dist loadfile --no-loadscope-reorder --durations=15 tests/python "$@"
    echo "== Python tests: $((SECONDS - stage)) s"
    if [ "${CHAINDRIVE_SANITIZE_STAGE:-1}" != 0 ]; then
      stage=$SECONDS
      wait_for_background "$sanitize_pid" "$sanitize_log" "the sanitizer build"
      echo "== sanitizer stage: its build finished $((SECONDS - stage)) s after pytest"
      (sanitizer_tests)
    fi
    ;;
  *)
    echo "usage: ./run.sh main [options of python -m harness run] | ./run.sh test | ./run.sh sweep [options of python -m harness sweep] | ./run.sh package [options of python -m harness package] | ./run.sh export --drive FILE [--out DIR]" >&2
    exit 2
    ;;
esac
