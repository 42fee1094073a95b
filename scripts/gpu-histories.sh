#!/usr/bin/env bash
# The GPU engine on an NVIDIA card for the histories that go up and down (docs/benchmarks.md,
# "Plasticity" and "Adhesion"): the GPU tests under the validation layers (loading-unloading cycles
# and adhesive approach-retraction among them), then each history below on the GPU and on all CPU
# cores of the same machine, with the solves' summed seconds and iterations and the two engines'
# histories side by side. Run on the device machine from the repository root after
# `scripts/gpu-check.sh pack` here.
#   plastic:  the paper's cone on a 1024^2 surface loaded to w = 48 and unloaded to 0, H = 0.05 E*
#   adhesion: the paper's cone on a 1024^2 surface, Maugis-Dugdale w = 0.03 E* delta, range 1 delta,
#             approached from w = -1 to 16 and retracted to -4 (bench/run_adhesion.sh's history, 4x the grid)
#   periodic adhesion: the 1024^2 surface as a periodic cell under a rigid flat, w = 0.02, range 0.5, mean
#             gaps from 2 down to 0.8 and back to 2
set -uo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-gpu-histories-out}
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
if [ "${SKIP_TESTS:-0}" != 1 ]; then
  timeout 150 "${runner[@]}" "$bin/test_gpu_solver" > "$out/tests.txt" 2>&1
  echo "test_gpu_solver exit $?" | tee -a "$out/tests.txt"
  grep -E "OK|FAIL|PASSED" "$out/tests.txt"
fi
"${runner[@]}" "$bin/indentmap" surface --n 1024 --slope 0.08 --seed 1 --out "$out/s.npy" > /dev/null

# history NAME COLUMNS INDENT-ARGUMENTS...: the history on both engines; COLUMNS (cut -f) compared
history() {
  local name=$1 columns=$2
  shift 2
  for device in gpu cpu; do
    local run="$out/${name}_$device"
    timeout 150 "${runner[@]}" "$bin/indentmap" indent "$out/s.npy" "$@" --device "$device" --out "$run" \
      > "$run.txt" 2>&1
    echo "$name $device: exit $?, $(head -1 "$run.txt")"
    # the solves' own seconds and iterations, summed over the steps (the machine has no bc)
    awk -v d="$name $device" '/^step/ { ++k; for (i = 1; i <= NF; ++i) { if ($i == "s") t += $(i - 1); if ($i == "iterations") n += $(i + 1) } }
                        END { printf "%s: %d steps solved in %.3f s, %d iterations\n", d, k, t, n }' "$run.txt"
  done
  paste -d' ' <(cut -d, -f"$columns" "$out/${name}_gpu/history.csv") <(cut -d, -f"$columns" "$out/${name}_cpu/history.csv") |
    head -40
}

history plastic 3,23 --approach 8:48:6,44:0:12 --hardness 0.05
cat "$out/plastic_gpu/indentation.csv" "$out/plastic_cpu/indentation.csv" 2>/dev/null | cut -d, -f5-13
history adhesion 2,3,5 --adhesion-work 0.03 --adhesion-range 1 --approach -1:16:18,15.5:-4:40
for device in gpu cpu; do
  python3 -c "import json,sys; a=json.load(open(sys.argv[1]))['adhesion']; print(sys.argv[2], {k: a[k] for k in ('pull_off_force','pull_off_approach','most_tensile_load','work_done','hysteresis_work')})" \
    "$out/adhesion_$device/run.json" "$device" 2>/dev/null || grep -A8 '"adhesion"' "$out/adhesion_$device/run.json"
done
history periodic_adhesion 3,5,25,28 --periodic --adhesion-work 0.02 --adhesion-range 0.5 --mean-gap 2:0.8:5,1.1:2:4
