#!/usr/bin/env bash
# Installs the built library into a scratch prefix, then builds and runs examples/ as a separate
# CMake project through find_package(sculpt): the install rules, the exported targets and the
# umbrella header work for another project.
#   find_package_test.sh <build dir> <source dir> [extra compiler and linker flags]
set -euo pipefail
build=$1 source=$2 flags=${3:-}
scratch="$build/find_package_test"
rm -rf "$scratch"
cmake --install "$build" --prefix "$scratch/install" >/dev/null
cmake -S "$source/examples" -B "$scratch/build" -DCMAKE_PREFIX_PATH="$scratch/install" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" >/dev/null
cmake --build "$scratch/build" -j 2 >/dev/null
out=$("$scratch/build/goblet_volume")
echo "$out"
[[ $out == volume* ]]
