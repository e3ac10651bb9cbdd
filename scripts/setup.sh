#!/usr/bin/env bash
# Installs whatever Debian packages are missing, then configures and builds sculpt.
#   scripts/setup.sh [--sanitize] [--target NAME]
#   build dir: build/release, or build/sanitize with ASan+UBSan (without the benchmark programs);
#   --target builds only that target
# Prints the build directory on its last line.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

sanitize=OFF
bench=ON
build="$root/build/release"
target=()
while (($#)); do
  case "$1" in
    --sanitize) sanitize=ON; bench=OFF; build="$root/build/sanitize" ;;
    --target) shift; target=(--target "${1:?--target needs a name}") ;;
    *) echo "setup.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
  shift
done

packages=(g++ make cmake pkg-config libeigen3-dev libboost-dev libopenmesh-dev
          libgtest-dev libgmock-dev libedit-dev python3
          libpng-dev  # libpng-dev: PNG pictures of solids (lib/render)
          lib3mf-dev  # lib3mf-dev: export and import of 3MF (lib/mesh/formats/threemf_format.cpp)
          libcgal-dev)  # libcgal-dev: the tests' independent mesh validator (tests/support)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo=""; [ "$(id -u)" = 0 ] || sudo="sudo"
  $sudo apt-get update -qq >&2
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSCULPT_SANITIZE="$sanitize" -DSCULPT_BUILD_BENCH="$bench" >&2
cmake --build "$build" -j "$jobs" "${target[@]}" >&2
echo "$build"
