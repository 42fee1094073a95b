#!/usr/bin/env bash
# Command-line tests of `indentmap theory`: the paper's Table 1, the CSV layout, sweeps, gamma(r/a),
# the normalisations, and refusals of bad arguments (exit 2, a message naming the option).
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

source "$(dirname "$0")/lib.sh"
# field FILE ROW COLUMN: one CSV cell (ROW 1 is the header).
field() { awk -F, -v r="$2" -v c="$3" 'NR == r { print $c }' "$1"; }
# close A B TOLERANCE: |A - B| <= TOLERANCE.
close() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'; }

check "listed in help" bash -c "'$cli' --help | grep -q '^  theory'"
check "theory --help" bash -c "'$cli' theory --help | grep -q -- --normalisation"

# The paper's Table 1 (alpha = 80 degrees): rho_c and the eq. (12) column.
"$cli" theory --alpha 80 --slope 0.01,0.02,0.04,0.08,0.16 --format csv >"$dir/t.csv"
check "table exits 0" test $? -eq 0
check "csv header" bash -c "head -1 '$dir/t.csv' | grep -qx 'slope,rho_c,area_ratio_eq6,area_ratio_eq12'"
check "five rows" test "$(wc -l <"$dir/t.csv")" -eq 6
rho=(17.63 8.82 4.41 2.20 1.10)
eq12=(0.998 0.992 0.969 0.894 0.719)
for i in 0 1 2 3 4; do
  check "Table 1 rho_c row $i" close "$(field "$dir/t.csv" $((i + 2)) 2)" "${rho[$i]}" 0.005
  check "Table 1 eq. (12) row $i" close "$(field "$dir/t.csv" $((i + 2)) 4)" "${eq12[$i]}" 0.0005
  check "eq. (12) below eq. (6), row $i" awk -v a="$(field "$dir/t.csv" $((i + 2)) 4)" \
    -v b="$(field "$dir/t.csv" $((i + 2)) 3)" 'BEGIN { exit !(a < b) }'
done
check "aligned table has the same header" bash -c \
  "'$cli' theory --alpha 80 --slope 0.08 | grep -qE '^ +slope +rho_c +area_ratio_eq6 +area_ratio_eq12$'"
# A smooth surface: rho_c = inf, full contact.
"$cli" theory --alpha 80 --slope 0 --format csv >"$dir/smooth.csv"
check "smooth surface" bash -c "sed -n 2p '$dir/smooth.csv' | grep -qx '0,inf,1,1'"
# The aligned table keeps six significant digits of a small ratio, as the CSV has them (it printed
# "0.000000" for eq. (6)'s 1.76327e-07 at h'rms 1e6, and 2 digits at 2.2e-5).
"$cli" theory --alpha 80 --slope 1e6 --format csv >"$dir/tiny.csv"
tiny_table=$("$cli" theory --alpha 80 --slope 1e6 | awk 'NR == 3 { print $3, $4 }')
for column in 1 2; do
  check "table: small ratio, column $column, to 6 digits of the CSV's" awk -v t="$(echo "$tiny_table" | cut -d' ' -f$column)" \
    -v c="$(field "$dir/tiny.csv" 2 $((column + 2)))" 'BEGIN { d = (t - c) / c; if (d < 0) d = -d; exit !(c > 0 && d < 5e-6) }'
done
# k enters rho_c = k cot(alpha) / (2 h'rms).
"$cli" theory --alpha 80 --slope 0.08 --k 4 --format csv >"$dir/k4.csv"
check "--k 4 doubles rho_c" close "$(field "$dir/k4.csv" 2 2)" 4.40817 0.00001

# A log sweep of rho_c.
"$cli" theory --rho 0.1:100:50 --format csv >"$dir/sweep.csv"
check "sweep header" bash -c "head -1 '$dir/sweep.csv' | grep -qx 'rho_c,area_ratio_eq6,area_ratio_eq12'"
check "sweep has 50 rows" test "$(wc -l <"$dir/sweep.csv")" -eq 51
check "sweep starts at 0.1" close "$(field "$dir/sweep.csv" 2 1)" 0.1 1e-12
check "sweep ends at 100" close "$(field "$dir/sweep.csv" 51 1)" 100 1e-9
check "sweep is log-spaced" awk -F, 'NR > 2 { r = $1 / prev; if (NR > 3 && (r - q > 1e-9 || q - r > 1e-9)) bad = 1; q = r }
  NR > 1 { prev = $1 } END { exit bad }' "$dir/sweep.csv"

# The normalisations: MG's beta = sqrt(2) rho_c / k equals PR's sqrt(pi)/2 rho_c' at
# rho_c' = 2 sqrt(2) rho_c / (sqrt(pi) k), so both must print the same ratios there.
"$cli" theory --rho 1:1:1 --normalisation mg --format csv >"$dir/mg.csv"
"$cli" theory --rho 0.7978845608028654:0.7978845608028654:1 --format csv >"$dir/pr.csv"
check "mg = pr at the matching rho_c (eq. 6)" close "$(field "$dir/mg.csv" 2 2)" "$(field "$dir/pr.csv" 2 2)" 1e-11
check "mg = pr at the matching rho_c (eq. 12)" close "$(field "$dir/mg.csv" 2 3)" "$(field "$dir/pr.csv" 2 3)" 1e-11
check "mg differs from pr" bash -c "! cmp -s <(cut -d, -f2- '$dir/mg.csv') <('$cli' theory --rho 1:1:1 --format csv | cut -d, -f2-)"

# gamma(r/a): 101 points, full contact at the apex, none at the rim, decreasing in between.
"$cli" theory --alpha 80 --slope 0.01,0.16 --gamma --format csv >"$dir/g.csv"
check "gamma header" bash -c "head -1 '$dir/g.csv' | grep -qx 'r_over_a,gamma_slope_0.01,gamma_slope_0.16'"
check "gamma has 101 points" test "$(wc -l <"$dir/g.csv")" -eq 102
check "gamma = 1 at the apex" bash -c "sed -n 2p '$dir/g.csv' | grep -qx '0,1,1'"
check "gamma = 0 at the rim" bash -c "tail -1 '$dir/g.csv' | grep -qx '1,0,0'"
check "gamma decreases outwards" awk -F, 'NR > 2 && ($2 > p2 || $3 > p3) { bad = 1 } NR > 1 { p2 = $2; p3 = $3 } END { exit bad }' "$dir/g.csv"
check "rougher is never denser" awk -F, 'NR > 1 && $3 > $2 { bad = 1 } END { exit bad }' "$dir/g.csv"
check "rougher is sparser at r = a/2" awk -F, '$1 == 0.5 { found = 1; sparser = $3 < $2 } END { exit !(found && sparser) }' "$dir/g.csv"

# Refusals: exit 2 and a message naming the option.
check "negative slope" expect_exit 2 "--slope = -0.01" "$cli" theory --alpha 80 --slope 0.01,-0.01
check "unparsable slope" expect_exit 2 "--slope: 'abc' is not a finite number" "$cli" theory --alpha 80 --slope 0.01,abc
check "empty slope item" expect_exit 2 "--slope: '' is not a finite number" "$cli" theory --alpha 80 --slope 0.01,,0.02
check "trailing comma" expect_exit 2 "--slope: '' is not a finite number" "$cli" theory --alpha 80 --slope 0.01,
check "alpha 90" expect_exit 2 "--alpha = 90: expected 0 < alpha < 90" "$cli" theory --alpha 90 --slope 0.1
check "alpha 0" expect_exit 2 "--alpha = 0: expected 0 < alpha < 90" "$cli" theory --alpha 0 --slope 0.1
check "alpha 95" expect_exit 2 "--alpha = 95" "$cli" theory --alpha 95 --slope 0.1
check "alpha nan" expect_exit 2 "--alpha: 'nan' is not a finite number" "$cli" theory --alpha nan --slope 0.1
check "slope without alpha" expect_exit 2 "--slope needs --alpha" "$cli" theory --slope 0.1
check "nothing to compute" expect_exit 2 "give either --slope" "$cli" theory
check "slope and rho" expect_exit 2 "give either --slope" "$cli" theory --alpha 80 --slope 0.1 --rho 1:2:3
check "rho missing count" expect_exit 2 "--rho: '1:2': expected MIN:MAX:N" "$cli" theory --rho 1:2
check "rho zero" expect_exit 2 "--rho = 0" "$cli" theory --rho 0:2:5
check "rho reversed" expect_exit 2 "expected MIN <= MAX" "$cli" theory --rho 2:1:5
check "rho count 0" expect_exit 2 "--rho = 0: expected an integer" "$cli" theory --rho 1:2:0
check "rho count text" expect_exit 2 "--rho: 'x' is not an integer" "$cli" theory --rho 1:2:x
check "bad format" expect_exit 2 "--format: 'xml'" "$cli" theory --rho 1:2:3 --format xml
check "bad normalisation" expect_exit 2 "--normalisation: 'persson'" "$cli" theory --rho 1:2:3 --normalisation persson
check "bad k" expect_exit 2 "--k = 0" "$cli" theory --rho 1:2:3 --k 0
check "stray argument" expect_exit 2 "unexpected argument 'extra'" "$cli" theory --rho 1:2:3 extra

# Other punches (the local density of contact with Hertz's and Boussinesq's pressures).
"$cli" theory --punch sphere --rho 0.001:10:9 --format csv >"$dir/sphere.csv"
check "sphere header" bash -c "head -1 '$dir/sphere.csv' | grep -qx 'rho,area_ratio_eq3,area_ratio_gamma'"
check "sphere linear at small rho" close "$(field "$dir/sphere.csv" 2 3)" 0.001 1e-6
check "sphere gamma below eq. (3)" awk -F, 'NR > 1 && $3 >= $2 && $2 < 1 { bad = 1 } END { exit bad }' "$dir/sphere.csv"
"$cli" theory --punch flat --rho 0.001:100:9 --format csv >"$dir/flat.csv"
check "flat header" bash -c "head -1 '$dir/flat.csv' | grep -qx 'rho,area_ratio_constant,area_ratio_gamma'"
check "flat linear at small rho" close "$(field "$dir/flat.csv" 2 3)" 0.001 1e-6
check "flat saturates" close "$(field "$dir/flat.csv" 10 3)" 1 1e-12
# At the crossover load N_c = pi^3 (3/4)^2 (h'rms / 2)^3 E* R^2 the Hertzian mean pressure is p_rough.
n_c=$(awk 'BEGIN { pi = atan2(0, -1); printf "%.17g", pi^3 * 0.5625 * 0.08^3 * 500^2 }')
"$cli" theory --punch sphere --slope 0.16 --radius 500 --load "$n_c" --format csv >"$dir/nc.csv"
check "sphere at N_c has rho = 1" close "$(field "$dir/nc.csv" 2 2)" 1 1e-9
"$cli" theory --punch sphere --rho 1:1:1 --format csv >"$dir/rho1.csv"
check "slope route = rho route" close "$(field "$dir/nc.csv" 2 4)" "$(field "$dir/rho1.csv" 2 3)" 1e-9
"$cli" theory --punch flat --rho 1:1:1 --gamma --format csv >"$dir/fg.csv"
check "flat gamma is 1 at the rim" close "$(field "$dir/fg.csv" 102 2)" 1 0
check "punch refused" expect_exit 2 "--punch" "$cli" theory --punch wedge --rho 1:1:1
check "sphere needs radius and load" expect_exit 2 "needs --radius and --load" "$cli" theory --punch sphere --slope 0.1
check "cone takes no load" expect_exit 2 "--radius and --load are for" "$cli" theory --alpha 80 --slope 0.1 --load 3
check "sphere takes no alpha" expect_exit 2 "--alpha is for the cone" "$cli" theory --punch flat --alpha 80 --rho 1:1:1

finish
