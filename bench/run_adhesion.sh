#!/bin/bash
# Adhesion (docs/benchmarks.md, "Adhesion"): approach and retraction of an 80 degree cone and of a sphere
# (R = 128 delta) on the paper's surface (256^2, H 0.8, lambda_s 4, h'rms 0.08, seed 1) at three works of
# adhesion w = 0.01, 0.03, 0.1 E* delta (range delta_c = 1 delta, so the stress w / delta_c and the Dugdale
# zone length pi E* delta_c^2 / (8 w) = 39, 13, 3.9 patches). Each history approaches from w = -1 to 8 in
# steps of 1 and retracts to -4 in steps of 0.5. Prints the pull-off force and approach, the jumps, the
# work lost, and the solver's iterations and seconds per step against the repulsive solve of the same
# steps (w >= 0, no adhesion); draws the contact maps at the largest load and at the last step in contact
# (patches under tension on the blue ramp of their tension, its own colour bar) and the force-distance curves.
# usage: bench/run_adhesion.sh BUILD_DIR [OUT_DIR]
set -eu
build=$1
out=${2:-$(mktemp -d)}
cli="$build/indentmap"
mkdir -p "$out"
"$cli" surface --n 256 --slope 0.08 --seed 1 --out "$out/s.npy" > /dev/null
steps="-1:8:10,7.5:-4:24"
# mean iterations and seconds per step over the steps with w >= 0 (columns 2, 9, 11 of history.csv)
per_step() { awk -F, 'NR > 1 && $2 >= 0 { n++; it += $9; s += $11 } END { printf "%.1f %.4f", it / n, s / n }' "$1"; }
printf "%-6s %-5s %9s %7s %7s %7s %9s | %8s %8s | %8s %8s\n" punch w pull_off at_w jump_in last_in work_lost \
  it/step s/step rep_it rep_s
for punch in cone sphere; do
  shape=(--punch cone); [ "$punch" = sphere ] && shape=(--punch sphere --radius 128)
  "$cli" indent "$out/s.npy" "${shape[@]}" --approach "0:8:9,7.5:0:16" --out "$out/${punch}_repulsive" > /dev/null
  for w in 0.01 0.03 0.1; do
    run="$out/${punch}_$w"
    "$cli" indent "$out/s.npy" "${shape[@]}" --adhesion-work "$w" --adhesion-range 1 --approach "$steps" --fields \
      --out "$run" > /dev/null
    python3 - "$run/run.json" "$punch" "$w" "$(per_step "$run/history.csv")" "$(per_step "$out/${punch}_repulsive/history.csv")" <<'PY'
import json, sys
a = json.load(open(sys.argv[1]))["adhesion"]
mine, theirs = sys.argv[4].split(), sys.argv[5].split()
none_as_nan = lambda v: v if v is not None else float('nan')  # null: the steps did not pass the pull-off
print(f"{sys.argv[2]:6s} {sys.argv[3]:5s} {none_as_nan(a['pull_off_force']):9.3f} {none_as_nan(a['pull_off_approach']):7.2f} "
      f"{a['jump_in_approach'] if a['jump_in_approach'] is not None else float('nan'):7.2f} "
      f"{a['jump_out_approach'] if a['jump_out_approach'] is not None else float('nan'):7.2f} "
      f"{none_as_nan(a['hysteresis_work']):9.3f} | {mine[0]:>8s} {mine[1]:>8s} | {theirs[0]:>8s} {theirs[1]:>8s}")
PY
  done
done
# the strongest adhesion: contact maps at the largest load (step 10, w = 8) and at the last step in
# contact while retracting, cone and sphere side by side
last_in_contact() { awk -F, 'NR > 11 && $5 > 0 { k = $1 } END { printf "%04d", k }' "$1/history.csv"; }
cone_last=$(last_in_contact "$out/cone_0.1")
sphere_last=$(last_in_contact "$out/sphere_0.1")
"$cli" render contact "$out"/cone_0.1/force_0010.npy "$out/cone_0.1/force_$cone_last.npy" \
  "$out"/sphere_0.1/force_0010.npy "$out/sphere_0.1/force_$sphere_last.npy" --columns 4 \
  --titles "cone w = 8,cone last contact,sphere w = 8,sphere last contact" --out "$out/adhesion_maps.png" > /dev/null
echo "cone's last contact at step $cone_last, sphere's at $sphere_last; runs and figures in $out"
