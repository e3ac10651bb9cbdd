#!/usr/bin/env bash
# Installs the Debian packages a command needs when they are missing, then configures and builds sculpt.
#   scripts/setup.sh [--tests] [--sanitize] [--bench] [--werror] [--target NAME]...
#   (none)      what the sculpt executable needs; builds build/release (Release)
#   --tests     also what the tests need (GoogleTest, CGAL, clang-format, lld) and the test programs
#   --sanitize  the AddressSanitizer + UndefinedBehaviorSanitizer build, build/sanitize: -O2, line
#               tables, assertions on (no NDEBUG), no use-after-scope, null or alignment checks
#               (CMakeLists.txt says why); implies --tests
#   --bench     the benchmark programs of tests/bench (build/release), not built otherwise
#   --werror    warnings are errors (CI)
#   --target    builds only that target (may be given more than once)
# The terminal gets one line per step; apt's output goes to build/logs/apt.log and the build's to
# build/logs/<release|sanitize>.log, whose path and last errors are printed when a step fails.
# Compiles go through ccache (installed here; the cache is ~/.cache/ccache, kept between runs).
# Prints the build directory on its last line (stdout; everything else goes to stderr).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

tests=OFF sanitize=OFF bench=OFF werror=OFF kind=release
targets=()
while (($#)); do
  case "$1" in
    --tests) tests=ON ;;
    --sanitize) sanitize=ON; tests=ON; kind=sanitize ;;
    --bench) bench=ON ;;
    --werror) werror=ON ;;
    --target) shift; targets+=("${1:?--target needs a name}") ;;
    *) echo "setup.sh: unknown option '$1' (see the comment at the top of scripts/setup.sh)" >&2; exit 2 ;;
  esac
  shift
done
build="$root/build/$kind"
logs="$root/build/logs"
mkdir -p "$logs"
say() { echo "setup: $*" >&2; }
fail() {  # fail LOG MESSAGE: the message, the log's errors and last lines, its path; exit 1
  say "$2 (full log: $1)"
  { grep -E "error:|FAILED:|^E: " "$1" | head -n 20; echo "..."; tail -n 15 "$1"; } | sed 's/^/  | /' >&2
  exit 1
}

# --- Debian packages: the executable's, then the tests' ---
packages=(g++ cmake ninja-build ccache pkg-config
          libeigen3-dev libboost-dev libopenmesh-dev  # Eigen, Spirit X3, OpenMesh (.om files)
          libedit-dev   # line editing and history in the REPL (BSD licence)
          libpng-dev    # PNG pictures (lib/render)
          libtbb-dev    # oneTBB: set operations on every core (lib/base/parallel.hpp)
          lib3mf-dev    # 3MF export and import (lib/mesh/formats/threemf_format.cpp)
          libjs-three)  # three.js, served by sculpt --view to its page at run time (lib/view)
if [ "$tests" = ON ]; then
  packages+=(libgtest-dev libgmock-dev python3
             libcgal-dev    # the tests' independent mesh validator (tests/support/cgal_mesh_check.*)
             clang-format   # the format check (scripts/check_format.sh)
             lld            # LLVM's linker: the test programs link 3.5 times faster (CMakeLists.txt)
             chromium chromium-driver python3-selenium)  # the view's page in a browser (tests/view/browser_test.py)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  say "installing ${#missing[@]} Debian packages: ${missing[*]} (log: build/logs/apt.log)"
  sudo=""; [ "$(id -u)" = 0 ] || sudo="sudo"
  start=$SECONDS
  { $sudo apt-get update -q && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"; } \
    > "$logs/apt.log" 2>&1 || fail "$logs/apt.log" "installing packages failed"
  say "installed in $((SECONDS - start)) s"
fi

# --- configure ---
cmake_args=(-S "$root" -B "$build" -G Ninja -DSCULPT_BUILD_TESTS="$tests" -DSCULPT_BUILD_BENCH="$bench"
            -DSCULPT_SANITIZE="$sanitize" -DSCULPT_WERROR="$werror")
if [ "$sanitize" = ON ]; then
  cmake_args+=(-DCMAKE_BUILD_TYPE=Sanitize)
else
  cmake_args+=(-DCMAKE_BUILD_TYPE=Release)
fi
if [ -f "$build/CMakeCache.txt" ] && ! grep -q "CMAKE_GENERATOR:INTERNAL=Ninja" "$build/CMakeCache.txt"; then
  say "build/$kind was configured with another generator: configuring it anew"
  rm -rf "$build"
fi
log="$logs/$kind.log"
cmake "${cmake_args[@]}" > "$log" 2>&1 || fail "$log" "configuring build/$kind failed"

# --- build: ninja's [n/m] lines become a line every quarter ---
what="${targets[*]:-everything}"
say "building $what in build/$kind (log: build/logs/$kind.log)"
start=$SECONDS
ninja_targets=()
((${#targets[@]})) && ninja_targets=("${targets[@]}")
set +e
NINJA_STATUS="[%f/%t] " ninja -C "$build" "${ninja_targets[@]}" 2>&1 | tee -a "$log" | awk '
  match($0, /^\[[0-9]+\/[0-9]+\]/) {
    split(substr($0, 2, RLENGTH - 2), n, "/")
    q = int(4 * n[1] / n[2])
    if (q > last && n[2] > 0) { printf "setup:   %d of %d steps\n", n[1], n[2] > "/dev/stderr"; last = q }
  }'
status=${PIPESTATUS[0]}
set -e
[ "$status" = 0 ] || fail "$log" "building build/$kind failed"
say "built in $((SECONDS - start)) s"
echo "$build"
