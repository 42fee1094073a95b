#!/usr/bin/env bash
# plots = flat_k: eq. (2)'s k measured on a scene's surfaces in the periodic half-space and fed
# into eq. (12). Checks: the files; k the same for every h'rms (linear elasticity: heights scaled
# by c scale the pressure at a given contact by c, so A/A0 depends on p_m / (h'rms E*) alone); k
# near the published 2; the eq. (12) column equal to `indentmap theory` with that k; the simulated
# column the table's mean.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
field() { awk -F, -v r="$2" -v c="$3" 'NR == r { print $c }' "$1"; }
close() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'; }

cat >"$dir/k.ini" <<INI
[scene]
name = k
output = $dir/out
[surfaces]
n = 64
hurst = 0.8
lambda_s = 4
slopes = 0.04, 0.08
seeds = 1:2
[punch]
shape = cone
alpha = 80
[loading]
control = load
load_star = 300
[output]
table = yes
plots = flat_k
INI
"$cli" run "$dir/k.ini" >"$dir/log" 2>&1
check "scene runs" test $? -eq 0
for f in flat_k.csv flat_k.png flat_k.pdf flat/flat_contact.csv; do
  check "wrote $f" test -s "$dir/out/$f"
done
t=$dir/out/flat_k.csv
check "two families" test "$(wc -l <"$t")" -eq 3
check "64 points per family" test "$(field "$t" 2 3)" -eq 32
check "k independent of h'rms" close "$(field "$t" 2 4)" "$(field "$t" 3 4)" 1e-5
check "k near the published 2" awk -v k="$(field "$t" 2 4)" 'BEGIN { exit !(k > 1.6 && k < 2.4) }'
check "k has an error bar" awk -v e="$(field "$t" 2 5)" 'BEGIN { exit !(e > 0 && e < 0.2) }'
for row in 2 3; do
  slope=$(field "$t" $row 1)
  k=$(field "$t" $row 4)
  expected=$("$cli" theory --alpha 80 --slope "$slope" --k "$k" --format csv | awk -F, 'NR == 2 { print $4 }')
  check "eq. (12) with the measured k, row $row" close "$(field "$t" $row 11)" "$expected" 1e-9
  k2=$("$cli" theory --alpha 80 --slope "$slope" --format csv | awk -F, 'NR == 2 { print $4 }')
  check "eq. (12) with k = 2, row $row" close "$(field "$t" $row 13)" "$k2" 1e-9
done
mean=$(awk -F, 'NR == 2 { print $7 }' "$dir/out/table1.csv")
check "simulated column is the table's mean" close "$(field "$t" 2 14)" "$mean" 1e-6 # table1.csv: 6 decimals
# The sweep's pressures are x h'rms E*, and the contact grows with them.
check "p_m = x h'rms E*" awk -F, 'NR > 1 { d = $5 - $4 * $2; if (d < -1e-15 || d > 1e-15) bad = 1 } END { exit bad }' \
  "$dir/out/flat/flat_contact.csv"
check "contact grows with the pressure" awk -F, 'NR > 2 && $3 == seed && $1 == fam && $6 < prev { bad = 1 }
  NR > 1 { prev = $6; seed = $3; fam = $1 } END { exit bad }' "$dir/out/flat/flat_contact.csv"
# The same surfaces written to files give the same k and eq. (12) (researcher finding R5: files were
# normalised by their forward-difference h'rms, generated families by their spectral target; k 1.9183
# against 1.9488 on 128² surfaces of h'rms 0.1): the flat contacts take each surface's spectral h'rms as
# solved, and the table the spectral h'rms of generated files (their sidecar says so), as their families
# have it; without the sidecars the flat contacts still give the same k.
for seed in 1 2; do
  "$cli" surface --n 64 --hurst 0.8 --lambda-s 4 --slope 0.08 --seed $seed --out "$dir/s$seed.npy" >/dev/null
done
sed -e '/^slopes/d' -e '/^seeds/d' -e '/^n = 64/d' -e '/^hurst/d' -e '/^lambda_s/d' -e "s|^output = .*|output = $dir/files|" \
  -e "s|^\[surfaces\]|[surfaces]\nfile = $dir/s1.npy, $dir/s2.npy|" "$dir/k.ini" >"$dir/files.ini"
"$cli" run "$dir/files.ini" >"$dir/files.log" 2>&1
check "the surfaces as files: runs" test $? -eq 0
same() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 1e-9 * (a < 0 ? -a : a)) }'; }
f=$dir/files/flat_k.csv
for c in 1:slope 4:k 10:rho_c 11:eq.12 13:eq.12_k2 14:simulated; do
  check "files as generated: flat_k ${c#*:}" same "$(field "$f" 2 "${c%%:*}")" "$(field "$t" 3 "${c%%:*}")"
done
for c in 1:slope 4:rho_c 9:eq.12; do
  check "files as generated: table1 ${c#*:}" test "$(field "$dir/files/table1.csv" 2 "${c%%:*}")" = \
    "$(field "$dir/out/table1.csv" 3 "${c%%:*}")"
done
rm "$dir/s1.npy.json" "$dir/s2.npy.json"
sed -e "s|^output = .*|output = $dir/bare|" -e 's/^table = yes/table = no/' "$dir/files.ini" >"$dir/bare.ini"
"$cli" run "$dir/bare.ini" >"$dir/bare.log" 2>&1
check "files without sidecars: runs" test $? -eq 0
for c in 1:slope 4:k 11:eq.12; do
  check "files without sidecars: flat_k ${c#*:}" same "$(field "$dir/bare/flat_k.csv" 2 "${c%%:*}")" "$(field "$t" 3 "${c%%:*}")"
done
# A measured scan is not periodic (researcher finding R6): its flat contacts, solved on the periodic
# cell, are warned about as [punch] periodic's are; the generated surfaces above (periodic) are not.
check "generated surfaces: no periodicity warning" bash -c "! grep -q 'is not periodic' '$dir/log'"
awk 'BEGIN { for (y = 0; y < 64; ++y) { line = ""; for (x = 0; x < 64; ++x) line = line (x ? " " : "") 0.05 * x + 0.3 * sin(x * 1.3 + y * 0.7) * cos(y * 2.1); print line } }' \
  >"$dir/ramp.txt"
sed -e '/^slopes/d' -e '/^seeds/d' -e '/^n = 64/d' -e '/^hurst/d' -e '/^lambda_s/d' -e "s|^output = .*|output = $dir/ramp|" \
  -e "s|^\[surfaces\]|[surfaces]\nfile = $dir/ramp.txt|" -e 's/^table = yes/table = no/' "$dir/k.ini" >"$dir/ramp.ini"
"$cli" run "$dir/ramp.ini" >"$dir/ramp.log" 2>&1
check "a scan that is not periodic: runs" test $? -eq 0
check "... and is warned about" grep -q "ramp.txt: the surface of family 0, seed 0 is not periodic" "$dir/ramp.log"
finish
