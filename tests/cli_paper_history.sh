#!/usr/bin/env bash
# A history of the paper's fig5 scene that once broke down (h'rms = 0.08, seed 4, 25 approaches to
# w = 30, tol 1e-6: at w = 28.8 the conjugate direction stopped descending after the contact set
# changed, and the solve failed with a negative step length). It must complete, with the load
# increasing at every step and A/A_cone in the range of the paper's ensemble. Slow (512 x 512).
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$cli" surface --n 512 --hurst 0.8 --slope 0.08 --lambda-s 4 --lambda-r 512 --seed 4 --out "$dir/s.npy" >/dev/null
"$cli" indent "$dir/s.npy" --approach 1.2:30:25 --tol 1e-6 --out "$dir/run" >/dev/null
status=$?
awk -F, -v status="$status" '
NR > 1 { rows++; if ($3 <= last) bad = "load does not increase at step " $1; last = $3; ratio = $6 }
END {
  if (status != 0) bad = "indent exited " status
  else if (rows != 25) bad = rows " steps, expected 25"
  else if (ratio < 0.85 || ratio > 1.05) bad = "final A/A_cone " ratio
  if (bad) { print "FAIL: " bad; print "0 passed, 1 failed"; exit 1 }
  print "1 passed, 0 failed"
}' "$dir/run/history.csv"
