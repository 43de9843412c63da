#!/usr/bin/env bash
# The same program built with pkg-config alone (no CMake), then run:
#   PKG_CONFIG_PATH=<prefix>/lib/pkgconfig examples/embed/pkgconfig_check.sh
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
flags="$(pkg-config --cflags --libs ballbox)"
echo "pkg-config ballbox $(pkg-config --modversion ballbox): $flags"
# shellcheck disable=SC2086  # the flags are separate words
c++ -std=c++20 -O2 "$here/main.cpp" $flags -o "$out/embed"
"$out/embed"
