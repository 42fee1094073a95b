#!/usr/bin/env bash
# `indentmap info`'s Vulkan devices, and the build's patched copy of Debian's VkFFT header
# (cmake/patch_vkfft.cmake): the packaged header does not compile as C11, the patched copy does,
# its glslang resource tables are gone in favour of glslang's own, and the patch refuses a header
# it was not written for. Exits 77 (skipped) in a build without the GPU layer (IM_GPU off), after
# checking that info says so. CMakeLists.txt passes IM_HAVE_GPU, IM_VKFFT_HEADER,
# IM_VKFFT_PATCHED, IM_CC and IM_CMAKE.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

source "$(dirname "$0")/lib.sh"
source_dir=$(cd "$(dirname "$0")/.." && pwd)

if [ "${IM_HAVE_GPU:-0}" != 1 ]; then
  check "info: no GPU layer" bash -c "'$cli' info | grep -qx 'Vulkan devices: not built (IM_GPU off)'"
  [ "$failures" -eq 0 ] || exit 1
  echo "SKIPPED: the library is built without the GPU layer (IM_GPU off)"
  exit 77
fi
# `indentmap info` lists the Vulkan devices (lavapipe at least, as setup.sh installs it), or says
# why there are none.
check "info lists Vulkan devices" bash -c "'$cli' info | grep -A1 '^Vulkan devices:\$' | grep -q '^  .*, Vulkan [0-9]*\.[0-9]*, float64 \(yes\|no\), [0-9]* MiB device-local\$'"
check "info without a Vulkan driver" bash -c "VK_ICD_FILENAMES=/nonexistent.json '$cli' info | grep -q '^Vulkan devices: none: no Vulkan driver'"
patched=$IM_VKFFT_PATCHED
cc=${IM_CC:-cc}
# The project's language and definitions (CMakeLists.txt), syntax only: the errors are the front end's.
flags=(-std=c11 -D_XOPEN_SOURCE=700 -Wall -Wextra -fsyntax-only)
printf '#include <vkFFT.h>\nint main(void) { return 0; }\n' >"$dir/use.c"

# refused PHRASE COMMAND...: COMMAND fails and its output holds PHRASE (CMake wraps its messages,
# so whitespace is compared loosely).
refused() {
  local phrase=$1; shift
  if "$@" >"$dir/out" 2>&1; then echo "succeeded: $*"; return 1; fi
  tr -s ' \n' '  ' <"$dir/out" | grep -qF -- "$phrase" || { cat "$dir/out"; return 1; }
}

check "the patched header exists" test -s "$patched"
check "Debian's header does not compile as C11" refused "error: empty scalar initializer" \
  "$cc" "${flags[@]}" -I"$(dirname "$IM_VKFFT_HEADER")" "$dir/use.c"
check "the patched header compiles as C11" bash -c '"$@" >"$0/cc.log" 2>&1 || { cat "$0/cc.log"; exit 1; }' \
  "$dir" "$cc" "${flags[@]}" -I"$(dirname "$patched")" "$dir/use.c"
check "no pre-glslang-12 resource table is left" bash -c "! grep -q 'default_resource = {' '$patched'"
check "glslang's default resource is used twice" \
  test "$(grep -c 'glslang_default_resource(),' "$patched")" -eq 2
# (d): the forward R2C decomposition's input block count, in VkFFT's multi-buffer mode
check "no input block count is written into the output's" \
  bash -c "! grep -q 'outputBufferBlockNum = .*inputBufferBlockSize' '$patched'"
check "the R2C decomposition counts its input's blocks" \
  test "$(grep -c 'inputBufferBlockNum = .*inputBufferBlockSize .*indentmap' "$patched")" -eq 2

# Another VkFFT version (here: one handle initializer already fixed) stops the build, naming the text.
sed '0,/VkCommandBuffer commandBuffer = {};/s//VkCommandBuffer commandBuffer = 0;/' "$IM_VKFFT_HEADER" >"$dir/other.h"
check "a different header is refused" refused "expected 3 occurrence(s) of 'VkCommandBuffer commandBuffer = {};', found 2" \
  "$IM_CMAKE" -DINPUT="$dir/other.h" -DOUTPUT="$dir/out/vkFFT.h" -P "$source_dir/cmake/patch_vkfft.cmake"
check "nothing written for it" test ! -e "$dir/out/vkFFT.h"
sed 's|/\* .generalConstantMatrixVectorIndexing = \*/ 1,|/* changed */ 1,|' "$IM_VKFFT_HEADER" >"$dir/tables.h"
check "changed resource tables are refused" refused "expected 2 glslang resource tables" \
  "$IM_CMAKE" -DINPUT="$dir/tables.h" -DOUTPUT="$dir/out/vkFFT.h" -P "$source_dir/cmake/patch_vkfft.cmake"
finish
