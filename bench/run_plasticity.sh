#!/bin/bash
# Loading and unloading with the hardness's memory (docs/benchmarks.md, "Plasticity: loading and
# unloading"): an 80 degree cone on the paper's surface (512^2, H 0.8, h'rms 0.08, seed 1) and on a
# smooth one, to w = 24 in 6 steps and back to 0 in 12, at H = 0.05, 0.1 and 0.2 E*; prints the
# indentation analysis (indentation.csv) of each and the seconds of each run, and draws the residual
# impressions of the rough runs.
# usage: bench/run_plasticity.sh BUILD_DIR [OUT_DIR]
set -eu
build=$1
out=${2:-$(mktemp -d)}
cli="$build/indentmap"
mkdir -p "$out"
"$cli" surface --n 512 --slope 0.08 --seed 1 --out "$out/s.npy" > /dev/null
printf "%-7s %-5s %6s %8s %8s %8s %8s %10s %9s %7s\n" surface H N_max H_IT E_r h_c h_r dissipated loop_area seconds
for h in 0.05 0.1 0.2; do
  for surface in rough smooth; do
    input=("$out/s.npy")
    [ "$surface" = rough ] || input=(--smooth --n 512)
    run="$out/${surface}_$h"
    start=$(date +%s.%N)
    "$cli" indent "${input[@]}" --approach 4:24:6,22:0:12 --hardness "$h" --fields --out "$run" > /dev/null
    seconds=$(echo "$(date +%s.%N) - $start" | bc)
    awk -F, -v s="$surface" -v h="$h" -v t="$seconds" 'NR == 2 {
        printf "%-7s %-5s %6.0f %8.4f %8.4f %8.3f %8.3f %8.0f %9.2f %6.2f\n", s, h, $6, $12, $13, $9, $14, $17, $15 - $16, t }' \
      "$run/indentation.csv"
  done
done
"$cli" render height "$out"/rough_0.05/plastic_0018.npy "$out"/rough_0.1/plastic_0018.npy "$out"/rough_0.2/plastic_0018.npy \
  --titles "H = 0.05 E*,H = 0.1 E*,H = 0.2 E*" --columns 3 --quantity "plastic depth d / δ" \
  --out "$out/plastic_impressions.png"
echo "runs, impressions and figures in $out"
