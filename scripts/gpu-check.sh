#!/usr/bin/env bash
# The GPU engine's checks on a machine with an NVIDIA GPU, in one go (issue 30; docs/benchmarks.md,
# "GPU engine"). The device machine has no package registry and another distribution, so the build is
# made here and carried there with the shared libraries it needs:
#   scripts/gpu-check.sh pack   on Debian 12: builds (Release, IM_GPU, bench_gpu) and gathers the programs
#                               (and BASELINE_BENCH, an earlier bench_gpu to time against, when given),
#                               their libraries (glibc apart, kept for a fallback loader), the Vulkan
#                               validation layer and the fonts into .gpu-carry/ and .gpu-carry.tar.xz
#                               (ignored by git; the device call carries the .tar.xz)
#   scripts/gpu-check.sh run    on the GPU machine, from the repository root: the Vulkan devices and
#                               GL_RENDERER (indentmap info), the GPU tests under the validation layers on
#                               the NVIDIA device, bench_gpu against the CPU engine on all cores (each GPU
#                               solve's time beside its submissions, the host's fence waits, per fine
#                               iteration: gathered after the benches, the baseline's beside), and
#                               fig4's frames rendered through EGL, and a profile of the largest solves
#                               (INDENTMAP_GPU_PROFILE); logs and pictures to ${OUT:-gpu-check-out}/
#   GPUCHECK_BIG=1 scripts/gpu-check.sh run   only the devices and one periodic cell of BIG_SIZE^2
#                               (32768 by default: Mueller's contact-mechanics challenge's size, 77.3
#                               GiB of device memory counted, VkFFT's multi-buffer mode) on the GPU:
#                               its time, the peak device memory in use (nvidia-smi) and the host's
#                               peak resident memory, in one call of under 5 minutes
#   GPUCHECK_MU10=1 scripts/gpu-check.sh run   the device, the GPU tests, then the adhesive sphere at
#                               Tabor's mu = 10 (scripts/gpu-adhesion.sh: MU10_L, MU10_LIMIT) in place of
#                               fig4, the benches and the profile (about 4 minutes)
#   GPUCHECK_TESTS=0 skips test_gpu_fft and test_gpu_solver (a second call after one that ran them)
#   GPUCHECK_PARTS=1 scripts/gpu-check.sh run   VkFFT's multi-buffer mode: test_gpu_fft (and
#                               test_gpu_fft_unpatched, carried when pack had UNPATCHED_FFT_TEST, a
#                               build without cmake/patch_vkfft.cmake's edit (d), expected to fail
#                               test_multi_buffer_transforms), test_gpu_solver's test_buffers_in_parts,
#                               then the periodic cells of 16384^2 and 32768^2 (big_periodic)
set -euo pipefail
cd "$(dirname "$0")/.."
carry=.gpu-carry

pack() {
  scripts/setup.sh build-gpu -DIM_GPU=ON -DBUILD_TESTING=ON
  cmake --build build-gpu --target bench_gpu -j "$(nproc)"
  rm -rf "$carry"
  mkdir -p "$carry"/{bin,lib,glibc,layers,fonts}
  cp build-gpu/indentmap build-gpu/test_gpu_solver build-gpu/test_gpu_fft build-gpu/bench_gpu build-gpu/test_adhesion \
    "$carry/bin/"
  # a baseline to time against on the same machine (BASELINE_BENCH=path to an earlier bench_gpu)
  if [ -n "${BASELINE_BENCH:-}" ]; then cp "$BASELINE_BENCH" "$carry/bin/bench_gpu_base"; fi
  if [ -n "${UNPATCHED_FFT_TEST:-}" ]; then cp "$UNPATCHED_FFT_TEST" "$carry/bin/test_gpu_fft_unpatched"; fi
  for program in "$carry"/bin/*; do ldd "$program"; done | awk '/=> \// {print $3}' | sort -u |
    while read -r library; do
      case "$(basename "$library")" in
        libc.so.*|libm.so.*|libpthread.so.*|libdl.so.*|librt.so.*) cp -L "$library" "$carry/glibc/" ;;
        *) cp -L "$library" "$carry/lib/" ;;
      esac
    done
  cp -L /lib64/ld-linux-x86-64.so.2 "$carry/glibc/"
  cp -L /usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so "$carry/layers/"
  cp /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json "$carry/layers/"
  cp /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf /usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf \
     "$carry/fonts/"
  # one compressed file: the folder is over the 64 MiB a device call carries (ICU's data alone is 31 MiB)
  tar cJf "$carry.tar.xz" "$carry"
  du -sh "$carry" "$carry.tar.xz"
}

# The NVIDIA driver's Vulkan ICD and EGL vendor files where the device machine keeps them.
driver_environment() {
  local nvidia=/usr/local/nvidia/share
  if [ -f "$nvidia/vulkan/icd.d/nvidia_icd.json" ]; then
    export VK_DRIVER_FILES="$nvidia/vulkan/icd.d/nvidia_icd.json" VK_ICD_FILENAMES="$nvidia/vulkan/icd.d/nvidia_icd.json"
  fi
  if [ -f "$nvidia/glvnd/egl_vendor.d/10_nvidia.json" ]; then
    export __EGL_VENDOR_LIBRARY_FILENAMES="$nvidia/glvnd/egl_vendor.d/10_nvidia.json"
  fi
  export VK_LAYER_PATH="$PWD/$carry/layers"
  export LD_LIBRARY_PATH="$PWD/$carry/lib:$PWD/$carry/layers:/usr/local/nvidia/lib64:${LD_LIBRARY_PATH:-}"
}

# One periodic solve of BIG_SIZE^2 on the GPU alone, nvidia-smi sampling the device memory in use
# every 200 ms; the peak goes to big.txt beside the solve's line (which has the host's peak RSS, as
# getrusage gives it). A 32768^2 cell's surface, plan and cascade take about a minute of host work.
big_periodic() {
  local out=$1 size=${BIG_SIZE:-32768} status=0
  nvidia-smi --query-gpu=memory.used --format=csv,noheader,nounits -lms 200 > "$out/big_memory.txt" &
  local sampler=$!
  timeout "${BIG_LIMIT:-270}" "${runner[@]}" "$carry/bin/bench_gpu" --cone "" --periodic "$size" --repeats 1 --cpu-limit 0 \
    --floor-limit 16384 2>&1 | tee "$out/big.txt" || status=1
  kill "$sampler" 2>/dev/null || true
  echo "peak device memory in use: $(sort -n "$out/big_memory.txt" | tail -1) MiB" | tee -a "$out/big.txt"
  return $status
}

# VkFFT's multi-buffer mode (GPUCHECK_PARTS=1): the transforms and a solve in small parts, then the
# two sizes whose buffers exceed one storage buffer's range.
parts_checks() {
  local out=$1 status=0
  timeout 60 "${runner[@]}" "$carry/bin/test_gpu_fft" 2>&1 | tee "$out/tests.txt" || status=1
  if [ -x "$carry/bin/test_gpu_fft_unpatched" ]; then
    echo "without patch (d), expected to fail test_multi_buffer_transforms:" | tee "$out/unpatched.txt"
    timeout 60 "${runner[@]}" "$carry/bin/test_gpu_fft_unpatched" 2>&1 | tail -25 | tee -a "$out/unpatched.txt"
  fi
  timeout 60 "${runner[@]}" "$carry/bin/test_gpu_solver" test_buffers_in_parts 2>&1 | tee -a "$out/tests.txt" ||
    status=1
  mkdir -p "$out/16384" "$out/32768"
  BIG_SIZE=16384 BIG_LIMIT=90 big_periodic "$out/16384" || status=1
  BIG_SIZE=32768 BIG_LIMIT=240 big_periodic "$out/32768" || status=1
  return $status
}

run() {
  local out=${OUT:-gpu-check-out}
  [ -d "$carry" ] || tar xJf "$carry.tar.xz"
  mkdir -p "$out" /usr/share/fonts/truetype/dejavu
  cp -n "$carry"/fonts/*.ttf /usr/share/fonts/truetype/dejavu/ 2>/dev/null || true
  driver_environment
  # the command line's own spin count, set here so that it does not re-execute itself through
  # /proc/self/exe (the carried loader, when it runs the programs)
  export GOMP_SPINCOUNT=3000
  # The machine's own glibc runs the programs when it is as new as Debian 12's; else the carried one.
  local runner=()
  if ! "$carry/bin/indentmap" --version >/dev/null 2>&1; then
    runner=("$PWD/$carry/glibc/ld-linux-x86-64.so.2" --library-path "$PWD/$carry/glibc:$LD_LIBRARY_PATH")
    echo "gpu-check: running with the carried glibc"
  fi
  { nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader || true; } | tee "$out/device.txt"
  { grep -m1 "model name" /proc/cpuinfo || true; } | tee -a "$out/device.txt"
  local status=0
  IM_RENDER_BACKEND=egl "${runner[@]}" "$carry/bin/indentmap" info 2>&1 | tee "$out/info.txt" || status=1
  if grep -q llvmpipe "$out/info.txt" && ! grep -qi nvidia "$out/info.txt"; then
    echo "gpu-check: only llvmpipe: the NVIDIA driver was not found" >&2
    exit 1
  fi
  if [ "${GPUCHECK_BIG:-0}" = 1 ]; then # the big cell alone: the tests and benches have runs of their own
    big_periodic "$out" || status=1
    return $status
  fi
  if [ "${GPUCHECK_PARTS:-0}" = 1 ]; then
    parts_checks "$out" || status=1
    return $status
  fi
  # each stage has a time limit of its own, so that one that hangs leaves the others their time
  if [ "${GPUCHECK_TESTS:-1}" = 1 ]; then # 0: a second call on the same machine, the tests already run
    timeout 120 "${runner[@]}" "$carry/bin/test_gpu_fft" 2>&1 | tee "$out/tests.txt" || status=1
    timeout 180 "${runner[@]}" "$carry/bin/test_gpu_solver" 2>&1 | tee -a "$out/tests.txt" || status=1
  fi
  if [ "${GPUCHECK_MU10:-0}" = 1 ]; then
    source scripts/gpu-adhesion.sh
    mu10_runs "$out" || status=1
    return $status
  fi
  local start=$SECONDS
  IM_RENDER_BACKEND=egl timeout 120 "${runner[@]}" "$carry/bin/indentmap" run scenes/fig4.ini 2>&1 | tail -5 |
    tee "$out/fig4.txt" || status=1
  echo "fig4 scene: $((SECONDS - start)) s through EGL" | tee -a "$out/fig4.txt"
  cp output/fig4/contact_panels.png output/fig4/frames/height_0011.png "$out/" 2>/dev/null || status=1
  # the same arguments for both, so that the two runs differ only in the build
  local sizes=(--cone 1024,2048,4096 --periodic 1024,2048,4096,8192 --history --repeats 3 --cpu-limit 2048)
  if [ -x "$carry/bin/bench_gpu_base" ]; then
    timeout 240 "${runner[@]}" "$carry/bin/bench_gpu_base" "${sizes[@]}" 2>&1 | tee "$out/bench_base.txt" || status=1
  fi
  timeout 240 "${runner[@]}" "$carry/bin/bench_gpu" "${sizes[@]}" 2>&1 | tee "$out/bench.txt" || status=1
  # the host's round trips beside the times, both builds' (docs/benchmarks.md: lavapipe's counts)
  grep -H "submissions" "$out"/bench_base.txt "$out/bench.txt" 2>/dev/null | sed 's|^.*/||' || true
  # where the device time goes (src/gpu/profile.h), on the largest sizes, in a run of its own so that
  # the timestamps stay out of the figures above
  INDENTMAP_GPU_PROFILE=1 timeout 120 "${runner[@]}" "$carry/bin/bench_gpu" --cone 4096 --periodic 8192 \
    --repeats 1 --cpu-limit 0 > "$out/profile.txt" 2>&1 || status=1
  cat "$out/profile.txt"
  return $status
}

case "${1:-}" in
  pack) pack ;;
  run) run ;;
  *) echo "usage: scripts/gpu-check.sh pack|run" >&2; exit 2 ;;
esac
