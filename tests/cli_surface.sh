#!/usr/bin/env bash
# Command-line tests of `indentmap surface`, `info` and the top level: exit codes, messages, files.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

source "$(dirname "$0")/lib.sh"

check "version" bash -c "'$cli' --version | grep -q '^indentmap [0-9]'"
check "help lists surface" bash -c "'$cli' --help | grep -q surface"
check "surface --help" bash -c "'$cli' surface --help | grep -q -- --lambda-s"
check "info" bash -c "'$cli' info | grep -q 'fftw: fftw-3'"
check "unknown command" expect_exit 2 "'nope' is not a command" "$cli" nope
check "bad slope" expect_exit 2 "--slope: 'abc' is not a finite number" "$cli" surface --slope abc
check "negative slope" expect_exit 2 "--slope = -1" "$cli" surface --slope -1
check "bad hurst" expect_exit 2 "--hurst = 1.5" "$cli" surface --hurst 1.5
check "bad slope definition" expect_exit 2 "--slope-def" "$cli" surface --slope-def central

# Generation writes the surface, its sidecar, a PNG and CSVs.
"$cli" surface --n 64 --slope 0.05 --lambda-s 4 --seed 3 --out "$dir/s.npy" --png "$dir/s.png" \
  --psd "$dir/psd.csv" --histograms "$dir/h.csv" >"$dir/stats" 2>&1
check "generation succeeds" test $? -eq 0
check "sidecar has the seed" grep -q '"seed": 3' "$dir/s.npy.json"
check "sidecar has the version" grep -q '"version": "' "$dir/s.npy.json"
check "png is a PNG" bash -c "head -c 8 '$dir/s.png' | od -An -c | grep -q 'P   N   G'"
check "psd csv header" bash -c "head -1 '$dir/psd.csv' | grep -qx 'q,c_iso,modes'"
check "histogram csv has three quantities" bash -c "cut -d, -f1 '$dir/h.csv' | sort -u | grep -c -E '^(height|slope|curvature)$' | grep -qx 3"
check "printed h'rms is the target" grep -q "h'rms spectral   0.05$" "$dir/stats"

# The same seed gives the same bytes for any thread count.
OMP_NUM_THREADS=1 "$cli" surface --n 96 --seed 9 --out "$dir/one.npy" >/dev/null
OMP_NUM_THREADS=2 "$cli" surface --n 96 --seed 9 --out "$dir/two.npy" >/dev/null
check "thread-count determinism" cmp -s "$dir/one.npy" "$dir/two.npy"

# Measuring files, good and bad.
check "stats of a written file" bash -c "'$cli' surface --stats '$dir/s.npy' | grep -q 'h_rms'"
printf '# Width: 3 um\n1 2 3\n4 five 6\n' >"$dir/bad.txt"
check "text matrix line number" expect_exit 2 "bad.txt:3: 'five' is not a number" "$cli" surface --stats "$dir/bad.txt"
head -c 100 "$dir/s.npy" >"$dir/cut.npy"
check "truncated npy" expect_exit 2 "truncated" "$cli" surface --stats "$dir/cut.npy"
check "missing file" expect_exit 1 "cannot open" "$cli" surface --stats "$dir/none.npy"
check "unwritable output" expect_exit 1 "/no/such/dir/s.npy" "$cli" surface --n 32 --out /no/such/dir/s.npy
check "no temporary files left" bash -c "! ls '$dir' | grep -q tmp"

finish
