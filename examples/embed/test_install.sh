#!/usr/bin/env bash
# make test-install: installs the engine from a build tree (engine target built) into a
# temporary prefix, then builds and runs examples/embed against it twice, with find_package and
# with pkg-config. The prefix and the example's build are removed afterwards.
#   examples/embed/test_install.sh BUILD_DIR
set -euo pipefail
build="$1"
here="$(cd "$(dirname "$0")" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"

cmake --install "$build" --component engine --prefix "$prefix"

cmake -S "$here" -B "$work/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release
cmake --build "$work/build"
echo "--- embed (CMake, find_package(ballbox))"
"$work/build/embed"

# lib/ or lib/<multiarch>/, as GNUInstallDirs chose for the build's prefix.
pc="$(find "$prefix" -name ballbox.pc)"
echo "--- embed (pkg-config)"
PKG_CONFIG_PATH="$(dirname "$pc")" "$here/pkgconfig_check.sh"

echo "test-install: passed (engine installed to a temporary prefix;" \
     "examples/embed built on it with find_package and with pkg-config, and ran)"
