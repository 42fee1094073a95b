#!/usr/bin/env bash
# Numerical extremes of the solver through the command line: loads so small that the contact is a
# single patch (under load control the search direction then vanishes on the contact set), and
# zero load and approach. Each must converge with finite numbers.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
finite_rows() { ! grep -qi "nan\|inf" <(cut -d, -f1-5 "$1"); }

"$cli" surface --n 64 --slope 0.16 --seed 2 --out "$dir/s.npy" >/dev/null
# One patch carries the load: n_p = 1 on a rough surface at N = 1e-4 E* delta^2.
"$cli" indent "$dir/s.npy" --load 1e-4,1e-3,0.01 --out "$dir/tiny" >"$dir/log" 2>&1
check "tiny loads converge (rough)" test $? -eq 0
check "first step is a single patch" awk -F, 'NR == 2 { exit !($5 == 1) }' "$dir/tiny/history.csv"
check "tiny loads are finite" finite_rows "$dir/tiny/history.csv"
"$cli" indent --smooth --n 32 --load 1e-6 --out "$dir/smooth" >"$dir/log" 2>&1
check "tiny load converges (smooth apex)" test $? -eq 0
check "smooth apex load is imposed" awk -F, 'NR == 2 { exit !($3 > 0.99e-6 && $3 < 1.01e-6) }' "$dir/smooth/history.csv"
"$cli" indent "$dir/s.npy" --approach 0,0.5 --out "$dir/zero" >"$dir/log" 2>&1
check "zero approach converges" test $? -eq 0
check "zero approach has no contact" awk -F, 'NR == 2 { exit !($3 == 0 && $5 == 0) }' "$dir/zero/history.csv"

finish
