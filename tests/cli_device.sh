#!/usr/bin/env bash
# The solver's engine chosen by the user (issue 30): `indent --device`, a scene's [solver] device and
# the run records that say which. With the GPU engine built (IM_HAVE_GPU=1) the device is whatever
# Vulkan device opens first (lavapipe in CI): its history must equal the CPU's to the tolerance, step
# for step, with the same contact patch counts. Without it, gpu is refused by name and auto falls
# back to the CPU. Bad words are refused in both front ends.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
. "$(dirname "$0")/lib.sh"

"$cli" surface --n 96 --slope 0.08 --seed 2 --out "$dir/s.npy" >/dev/null
indent() { "$cli" indent "$dir/s.npy" --approach 0.5:3:3 --tol 1e-10 --no-wisdom --out "$dir/$1" "${@:2}"; }

check "--device bogus refused" expect_exit 2 "--device 'bogus': expected cpu, gpu or auto" indent bad --device bogus
printf '[scene]\nname = d\noutput = %s/sd\n[surfaces]\nn = 32\n[solver]\ndevice = tpu\n[output]\nplots = fig5\n' "$dir" >"$dir/d.ini"
check "[solver] device = tpu refused" expect_exit 2 "device" "$cli" run --quiet "$dir/d.ini"

indent cpu --device cpu >"$dir/cpu.txt" 2>&1
check "cpu: device cpu said" grep -q ", device cpu$" "$dir/cpu.txt"
check "cpu: run.json records device cpu" grep -q '"device": "cpu"' "$dir/cpu/run.json"
check "cpu: run.json names the engine's device" grep -q '"device_name": "cpu"' "$dir/cpu/run.json"
indent auto --device auto >"$dir/auto.txt" 2>&1
check "auto runs" test -s "$dir/auto/history.csv"

# columns: step, approach, load, load_star, contact_patches (loads to 1e-10, counts exactly)
same_history() {
  python3 - "$1" "$2" <<'PY'
import csv, sys
a, b = (list(csv.DictReader(open(p))) for p in sys.argv[1:3])
assert len(a) == len(b) == 3, (len(a), len(b))
for x, y in zip(a, b):
    assert abs(float(x["load"]) - float(y["load"])) <= 1e-10 * abs(float(x["load"])), (x["load"], y["load"])
    assert x["contact_patches"] == y["contact_patches"], (x["contact_patches"], y["contact_patches"])
PY
}

if [ "${IM_HAVE_GPU:-0}" = 1 ]; then
  indent gpu --device gpu >"$dir/gpu.txt" 2>&1
  check "gpu: runs" test -s "$dir/gpu/history.csv"
  check "gpu: the device named" bash -c "grep ', device ' '$dir/gpu.txt' | grep -vq ', device cpu$'"
  check "gpu: run.json records device gpu" grep -q '"device": "gpu"' "$dir/gpu/run.json"
  check "gpu: run.json names the Vulkan device" bash -c "grep '\"device_name\"' '$dir/gpu/run.json' | grep -vq '\"cpu\"'"
  check "gpu: the CPU's history to 1e-10" same_history "$dir/cpu/history.csv" "$dir/gpu/history.csv"
  printf '[scene]\nname = d\noutput = %s/sg\n[surfaces]\nn = 64\nslopes = 0.08\nseeds = 1\n[loading]\nsteps = 0.5:2:2\n[solver]\ndevice = gpu\ntol = 1e-10\n[output]\nplots = fig5\n' "$dir" >"$dir/g.ini"
  sed 's/device = gpu/device = cpu/; s/sg$/sc/' "$dir/g.ini" >"$dir/c.ini"
  "$cli" run --quiet "$dir/g.ini" >/dev/null 2>&1
  "$cli" run --quiet "$dir/c.ini" >/dev/null 2>&1
  check "scene on the gpu: the CPU's member history" bash -c \
    "diff <(tail -n +2 '$dir/sc/histories/member_00_1.csv' | cut -d, -f1,5) <(tail -n +2 '$dir/sg/histories/member_00_1.csv' | cut -d, -f1,5)"
  # the device memory estimated before any work (docs/solver.md, "Limits"): listed, and a scene on a
  # device the engine may fill only 1 MiB of refused naming it, with no output folder
  "$cli" info --memory 256 >"$dir/memory.txt"
  check "info --memory: the GPU's host and device memory" grep -q "periodic   gpu: host [0-9.e-]* GiB, device [0-9.e-]* GiB of .*'s [0-9.e-]* GiB$" "$dir/memory.txt"
  check "info --memory: the CPU's" grep -q "half-space cpu: host [0-9.e-]* GiB$" "$dir/memory.txt"
  sed 's/sg$/small/; s/n = 64/n = 256/' "$dir/g.ini" >"$dir/small.ini"
  # (under AddressSanitizer without leak detection for this one run: the estimate opens and closes a Vulkan
  # context, and lavapipe, unloaded with it, leaves 128 bytes of its one-time setup that LeakSanitizer can
  # no longer name for tests/gpu_lsan.supp; its exit code would hide the refusal's)
  ASAN_OPTIONS=detect_leaks=0 INDENTMAP_GPU_MAX_MEMORY=1048576 "$cli" run --quiet "$dir/small.ini" >/dev/null \
    2>"$dir/small.err"
  echo $? >"$dir/small.status"
  check "a GPU too small for the scene: exit 2" test "$(cat "$dir/small.status")" -eq 2
  check "a GPU too small: the device, the memory needed and the memory it has" grep -q \
    "small.ini: \[solver\] device = gpu: a 256 x 256 solve needs [0-9.]* GiB of device memory .* has 0.000977 GiB" "$dir/small.err"
  check "a GPU too small: no output folder" test ! -e "$dir/small"
  # a scene's solves estimated on their window where the heights are known before any work (a smooth surface):
  # a 256^2 grid whose whole-grid plan needs 0.0112 GiB runs in 4 MiB, its 32 x 32 window's plan fitting;
  # in 64 KiB that window is refused, naming its size and the grid's
  printf '[scene]\nname = w\noutput = %s/sw\n[surfaces]\nn = 256\nslopes = 0\nseeds = 1\n[loading]\nsteps = 0.5:2:2\n[solver]\ndevice = gpu\n[output]\nplots = fig5\n' "$dir" >"$dir/w.ini"
  scene_in() { ASAN_OPTIONS=detect_leaks=0 INDENTMAP_GPU_MAX_MEMORY=$1 "$cli" run --quiet "$dir/w.ini"; }
  check "a scene whose grid exceeds the device and whose window fits: runs" scene_in 4194304
  check "its history written" test -s "$dir/sw/histories/member_00_1.csv"
  rm -rf "$dir/sw"
  check "a scene whose window exceeds the device: refused naming the window and the grid" expect_exit 2 \
    "w.ini: [solver] device = gpu, solves on a 32 x 32 window of the 256 x 256 grid: a 32 x 32 solve needs" scene_in 65536
  check "a window refused: no output folder" test ! -e "$dir/sw"
  # INDENTMAP_GPU_MAX_MEMORY is a whole number of bytes: other text refused naming it (exit 2), under auto too;
  # indent's plan on a device too small refused by the engine with the estimate's status (IM_ENOMEM: exit 2)
  with_max_memory() { ASAN_OPTIONS=detect_leaks=0 INDENTMAP_GPU_MAX_MEMORY=$1 indent "${@:2}"; }
  for text in 12GiB abc -5 1e400 nan; do
    check "INDENTMAP_GPU_MAX_MEMORY=$text refused" expect_exit 2 \
      "INDENTMAP_GPU_MAX_MEMORY=$text: expected a whole number of bytes" with_max_memory "$text" bad --device auto
  done
  check "indent on a GPU too small: exit 2 naming the device's memory" expect_exit 2 \
    "needs 0.00 GiB of device memory for its fields" with_max_memory 4096 small --device gpu
else
  check "info --memory: no GPU engine" bash -c "'$cli' info --memory 64 | grep -q 'periodic   gpu: none (.*no GPU engine'"
  # exit 1, not 2: the arguments are valid, this build cannot run them (IM_EUNSUPPORTED)
  check "gpu refused without the engine" expect_exit 1 "no GPU engine" indent gpu --device gpu
  check "auto falls back to the cpu" grep -q ", device cpu$" "$dir/auto.txt"
fi
finish
