#!/usr/bin/env bash
# Racing writers of one .npy and its .json sidecar: in each of 12 trials, 12 writers of different seeds
# write `surface --out r.npy` at once; the pair left behind must be one writer's whole: the data and the
# sidecar byte for byte those the sidecar's seed writes alone.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
export OMP_NUM_THREADS=1

writers=12
for seed in $(seq "$writers"); do
  "$cli" surface --n 128 --seed "$seed" --out "$dir/alone_$seed.npy" >/dev/null
done

# sidecar_seed FILE: the generator's seed a surface's sidecar states.
sidecar_seed() { python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["generator"]["seed"])' "$1"; }

mixed=0
for trial in $(seq 12); do
  rm -f "$dir/r.npy" "$dir/r.npy.json"
  for seed in $(seq "$writers"); do
    "$cli" surface --n 128 --seed "$seed" --out "$dir/r.npy" >/dev/null &
  done
  wait
  seed=$(sidecar_seed "$dir/r.npy.json")
  if ! cmp -s "$dir/r.npy" "$dir/alone_$seed.npy" || ! cmp -s "$dir/r.npy.json" "$dir/alone_$seed.npy.json"; then
    echo "trial $trial: r.npy is not the surface of seed $seed its sidecar states"
    mixed=$((mixed + 1))
  fi
done
check "12 trials of $writers racing writers: every pair one writer's" test "$mixed" -eq 0
check "no temporary file left" test -z "$(find "$dir" -name '.im.tmp.*')"
finish
