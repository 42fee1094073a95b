#!/usr/bin/env bash
# The main job on its built-in default: sets up, builds, and writes real images under output/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh build
out=output/surface
mkdir -p "$out"
./build/indentmap surface --n 512 --hurst 0.8 --slope 0.08 --lambda-s 4 --lambda-r 512 --seed 1 \
  --out "$out/surface.npy" --png "$out/height.png" --psd "$out/psd.csv" --histograms "$out/histograms.csv"
echo "demo: wrote $(ls "$out" | tr '\n' ' ')in $out/"
