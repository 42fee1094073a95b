#!/usr/bin/env bash
# The GPU engine on an NVIDIA card for this wave's plastic memory (docs/benchmarks.md, "Plasticity"): the
# GPU tests under the validation layers (a loading-unloading cycle under both controls among them) and one
# loading-unloading history of the paper's cone on a 1024^2 surface at H = 0.05, on the GPU and on all CPU
# cores. Run on the device machine from the repository root after scripts/gpu-check.sh pack here.
set -uo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-gpu-plastic-out}
mkdir -p "$out"
[ -d .gpu-carry ] || tar xJf .gpu-carry.tar.xz
carry=.gpu-carry
eval "$(sed -n '/^driver_environment()/,/^}/p' scripts/gpu-check.sh)"
driver_environment
export GOMP_SPINCOUNT=3000
bin=.gpu-carry/bin
runner=()
"$bin/indentmap" --version >/dev/null 2>&1 ||
  runner=("$PWD/.gpu-carry/glibc/ld-linux-x86-64.so.2" --library-path "$PWD/.gpu-carry/glibc:$LD_LIBRARY_PATH")
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader || true; } | tee "$out/device.txt"
timeout 150 "${runner[@]}" "$bin/test_gpu_solver" > "$out/tests.txt" 2>&1; echo "test_gpu_solver exit $?" | tee -a "$out/tests.txt"
grep -E "OK|FAIL|PASSED" "$out/tests.txt"
"${runner[@]}" "$bin/indentmap" surface --n 1024 --slope 0.08 --seed 1 --out "$out/s.npy" > /dev/null
for device in gpu cpu; do
  timeout 120 "${runner[@]}" "$bin/indentmap" indent "$out/s.npy" --approach 8:48:6,44:0:12 --hardness 0.05 \
    --device "$device" --out "$out/$device" > "$out/$device.txt" 2>&1
  echo "$device: exit $?, $(head -1 "$out/$device.txt")"
  # the solves' own seconds and iterations, summed over the steps (the machine has no bc)
  awk -v d="$device" '/^step/ { for (i = 1; i <= NF; ++i) { if ($i == "s") t += $(i - 1); if ($i == "iterations") n += $(i + 1) } }
                      END { printf "%s: %d steps solved in %.3f s, %d iterations\n", d, NR, t, n }' "$out/$device.txt"
done
paste -d' ' <(cut -d, -f3,23 "$out/gpu/history.csv") <(cut -d, -f3,23 "$out/cpu/history.csv") | head -20
cat "$out/gpu/indentation.csv" "$out/cpu/indentation.csv" 2>/dev/null | cut -d, -f5-13
