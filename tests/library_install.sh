#!/usr/bin/env bash
# library_install: libmeadow as a host gets it. `cmake --install` of the
# build into a fresh prefix; src/examples/host_glfw.c copied out of the
# source tree and built there with pkg-config alone, then again through
# the CMake package (find_package(meadow)); the pkg-config build run
# headless for a few frames on the installed scene scenes/lawn.json, from a
# folder with no shaders/ or scenes/, writing a PNG.
# Usage: library_install.sh BUILD_DIR [extra C flags, e.g. the sanitizers']
set -euo pipefail
build=$1
cflags=${2:-}
src=$PWD
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
pc=$(dirname "$(find "$tmp/prefix" -name meadow.pc)")
lib=$(dirname "$(find "$tmp/prefix" -name 'libmeadow.so' | head -n 1)")
cp "$src/src/examples/host_glfw.c" "$tmp/"
cd "$tmp"
export PKG_CONFIG_PATH=$pc
# shellcheck disable=SC2046,SC2086
cc $cflags -std=c11 -Wall -Werror -o host host_glfw.c $(pkg-config --cflags --libs meadow epoxy glfw3 egl) -lm
LD_LIBRARY_PATH=$lib ./host --headless --frames 12 --scene "$tmp/prefix/share/meadow/scenes/lawn.json" --out host.png
test -s host.png || { echo "FAIL: host_glfw wrote no PNG"; exit 1; }
cat > CMakeLists.txt <<'CM'
cmake_minimum_required(VERSION 3.20)
project(host C)
find_package(meadow REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(DEPS REQUIRED IMPORTED_TARGET epoxy glfw3 egl)
add_executable(host host_glfw.c)
target_link_libraries(host PRIVATE meadow::meadow PkgConfig::DEPS m)
CM
cmake -S . -B cmake-build -DCMAKE_PREFIX_PATH="$tmp/prefix" -DCMAKE_C_FLAGS="$cflags" >/dev/null
cmake --build cmake-build >/dev/null
test -x cmake-build/host || { echo "FAIL: the CMake package build made no host"; exit 1; }
if [ -n "${MEADOW_TEST_OUT:-}" ]; then mkdir -p "$MEADOW_TEST_OUT" && cp host.png "$MEADOW_TEST_OUT/"; fi
echo "ok: installed, built with pkg-config and find_package, rendered host.png"
