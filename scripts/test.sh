#!/usr/bin/env bash
# Sets up, builds with -Werror and runs the whole test suite; then the same tests under
# AddressSanitizer and UndefinedBehaviorSanitizer (skip those with IM_SKIP_SANITIZE=1).
set -euo pipefail
cd "$(dirname "$0")/.."
# setup.sh installs Mesa's llvmpipe, so an OpenGL context must exist: a renderer test that cannot
# get one fails here instead of reporting itself skipped (IM_REQUIRE_GL=0 allows the skip).
export IM_REQUIRE_GL=${IM_REQUIRE_GL:-1}
# Likewise setup.sh installs Chromium, so the viewer page's browser tests must run, not skip.
export IM_REQUIRE_CHROMIUM=${IM_REQUIRE_CHROMIUM:-1}
# And Mesa's lavapipe, so the GPU engine's tests must find a Vulkan device (IM_REQUIRE_GPU=0 allows the skip).
export IM_REQUIRE_GPU=${IM_REQUIRE_GPU:-1}
scripts/setup.sh build -DIM_WERROR=ON
(cd build && ctest --output-on-failure -j "$(nproc)")
# The optional engines and readers off: the library and the command line must still build (the GPU,
# MPI and Gwyddion parts are optional by design; a call into one from the core once broke this).
cmake -S . -B build-minimal -DIM_WERROR=ON -DIM_GPU=OFF -DIM_MPI=OFF -DIM_GWYDDION=OFF -DIM_PYTHON=OFF \
  -DBUILD_TESTING=OFF > /dev/null
cmake --build build-minimal --target indentmap_cli -j "$(nproc)" > /dev/null
if [ "${IM_SKIP_SANITIZE:-0}" != 1 ]; then
  scripts/setup.sh build-asan -DIM_WERROR=ON -DIM_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo
  # Mesa's on-disk shader cache off: with it, LeakSanitizer's tracer crashed ("Tracer caught signal 11")
  # at exit of EGL renders whose shaders came from the cache, a failure of the tool, not a leak (the
  # same runs pass with the cache off, and without the sanitizers either way).
  (cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 MESA_SHADER_CACHE_DISABLE=true \
     ctest --output-on-failure -j "$(nproc)" -LE slow)
fi
