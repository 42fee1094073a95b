#!/usr/bin/env bash
# Builds the libFuzzer harnesses (clang, ASan, UBSan) into BUILD_DIR (default build-fuzz):
#   fuzz/build.sh [BUILD_DIR]
# Fuzzing is optional, so scripts/setup.sh does not install its packages; this script checks for
# clang and the libFuzzer runtime and installs them as root, or prints the command to run.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build-fuzz}

# Debian 12: clang 14; libFuzzer's runtime (libclang_rt.fuzzer) is in libclang-rt-14-dev.
PACKAGES=(clang libclang-rt-14-dev libomp-14-dev)

libfuzzer_works() {
  command -v clang >/dev/null || return 1
  local probe
  probe=$(mktemp -d)
  printf '#include <stddef.h>\n#include <stdint.h>\nint LLVMFuzzerTestOneInput(const uint8_t *d, size_t n) { (void)d; (void)n; return 0; }\n' \
    > "$probe/probe.c"
  clang -fsanitize=fuzzer,address,undefined "$probe/probe.c" -o "$probe/probe" 2>/dev/null
  local ok=$?
  rm -rf "$probe"
  return $ok
}

if ! libfuzzer_works; then
  cmd="apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends ${PACKAGES[*]}"
  if [ "$(id -u)" -eq 0 ]; then
    echo "fuzz/build.sh: clang cannot link a libFuzzer program; installing ${PACKAGES[*]}"
    bash -c "$cmd"
  else
    echo "fuzz/build.sh: clang cannot link a libFuzzer program (-fsanitize=fuzzer); run as root:" >&2
    echo "  sudo bash -c '$cmd'" >&2
    exit 1
  fi
fi

cmake -S fuzz -B "$build_dir" -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build_dir" -j "$(nproc)" --target fuzzers
echo "fuzz/build.sh: harnesses in $build_dir: $(cd "$build_dir" && ls fuzz_* | tr '\n' ' ')"
