#!/usr/bin/env bash
# Sweeps (docs/scenes.md): a list of alpha runs each angle as a sweep point in its own folder;
# sweep.csv gathers the families. Physics check: A/A_cone depends on rho_c = cot(alpha) / h'rms
# alone. Doubling cot(alpha) and h'rms scales every height by 2 (linear elasticity: the same
# contact at the load with the same smooth contact area N*), so (80 deg, 0.04) and
# (70.5746 deg, 0.08), both at rho_c = 4.408, must give the same contact, to less than one grid
# cell of the N* = 300 cells; the other two points (rho_c = 2.20, 8.82) differ from it. Keys:
# --resume reads back every point it kept, and solves only a new angle. Statistics: each family's mean
# and sample standard deviation in sweep.csv and the point's table1.csv are those of its members' files,
# computed here; one surface a family has no spread (nan, no error bar), and table1.md shows the
# paper's values only beside the paper's alpha, H and lambda_s.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
scene() {
  cat >"$dir/s.ini" <<INI
[scene]
name = s
output = $dir/${3:-out}
[surfaces]
n = 64
hurst = 0.8
lambda_s = 4
slopes = 0.04, 0.08
seeds = ${2:-1:3}
[punch]
shape = cone
alpha = $1
[loading]
control = load
load_star = 300
[output]
table = yes
plots = fig2
INI
}
scene "80, 70.5746"
"$cli" run "$dir/s.ini" >"$dir/log" 2>&1
check "sweep runs" test $? -eq 0
for f in sweep.csv fig2.png fig2.pdf alpha_80_hurst_0.8_lambda_s_4/table1.csv \
  alpha_70.5746_hurst_0.8_lambda_s_4/table1.csv; do
  check "wrote $f" test -s "$dir/out/$f"
done
check "run.json records the sweep's lists" python3 -c 'import json, sys
s = json.load(open(sys.argv[1]))["sweep"]
sys.exit(not (s["alpha"] == [80, 70.5746] and s["hurst"] == [0.8] and s["lambda_s"] == [4] and s["points"] == 2))' \
  "$dir/out/run.json"
t=$dir/out/sweep.csv
check "four rows: two angles x two slopes" test "$(wc -l <"$t")" -eq 5
# rows: 2 = (80, 0.04), 3 = (80, 0.08), 4 = (70.57, 0.04), 5 = (70.57, 0.08)
value() { awk -F, -v r="$1" -v c="$2" 'NR == r { print $c }' "$t"; }
check "equal rho_c" awk -v a="$(value 2 5)" -v b="$(value 5 5)" 'BEGIN { exit !(a > 4.408 && a < 4.409 && (a - b) ^ 2 < 1e-10) }'
check "equal rho_c, equal A/A_cone (within one cell of N*)" \
  awk -v a="$(value 2 7)" -v b="$(value 5 7)" 'BEGIN { d = a - b; exit !(d * d < (1 / 300) ^ 2) }'
check "other rho_c, other A/A_cone" \
  awk -v a="$(value 2 7)" -v b="$(value 3 7)" -v c="$(value 4 7)" 'BEGIN { exit !(a != b && a != c) }'
check "the point's table is its rows" awk -F, -v m="$(value 4 7)" \
  'NR == 2 { d = $7 - m; exit !(d * d < 1e-12) }' "$dir/out/alpha_70.5746_hurst_0.8_lambda_s_4/table1.csv"
# The members' statistics, computed here from their files (area_ratio of table/member_FF_SEED.csv).
members_statistics() {
  python3 - "$dir/out/$1" "$t" <<'PY'
import csv, glob, math, statistics, sys
point, sweep = sys.argv[1], sys.argv[2]
alpha = float(point.split("alpha_")[1].split("_")[0])
table = {float(r["slope"]): r for r in csv.DictReader(open(point + "/table1.csv"))}
rows = {float(r["slope"]): r for r in csv.DictReader(open(sweep)) if float(r["alpha"]) == alpha}
families = {}
for path in glob.glob(point + "/table/member_*.csv"):
    member = next(csv.DictReader(open(path)))
    families.setdefault(float(member["slope"]), []).append(float(member["area_ratio"]))
ok = len(families) == 2 and all(len(v) == 3 for v in families.values())
for slope, ratios in families.items():
    mean, sd = statistics.mean(ratios), statistics.stdev(ratios)
    row = rows[slope]
    ok &= int(row["surfaces"]) == 3 and math.isclose(float(row["area_ratio_mean"]), mean, rel_tol=1e-9)
    ok &= math.isclose(float(row["area_ratio_sd"]), sd, rel_tol=1e-9)
    ok &= abs(float(table[slope]["area_ratio_mean"]) - mean) <= 5e-7 and abs(float(table[slope]["area_ratio_sd"]) - sd) <= 5e-7
sys.exit(not ok)
PY
}
check "alpha 80: sweep.csv and table1.csv hold the members' mean and sample sd" members_statistics alpha_80_hurst_0.8_lambda_s_4
check "alpha 70.57: sweep.csv and table1.csv hold the members' mean and sample sd" \
  members_statistics alpha_70.5746_hurst_0.8_lambda_s_4
check "alpha 80: table1.md beside the paper's values" grep -q '^| 0.04 .*| 0.985 ± 0.031 (37211) |$' \
  "$dir/out/alpha_80_hurst_0.8_lambda_s_4/table1.md"
check "alpha 70.57: table1.md shows no paper value (it is the paper's alpha = 80)" \
  bash -c "! grep -q '(37211)\|(35152)' '$dir/out/alpha_70.5746_hurst_0.8_lambda_s_4/table1.md'"
touch "$dir/out/alpha_80_hurst_0.8_lambda_s_4/table/.im.tmp.killed" # as a killed run leaves one
"$cli" run --resume "$dir/s.ini" >"$dir/log" 2>&1
check "resume runs" test $? -eq 0
check "a point's stale temporary removed" test ! -e "$dir/out/alpha_80_hurst_0.8_lambda_s_4/table/.im.tmp.killed"
check "resume reads every point back" test "$(grep -c '0 solved, 6 read back' "$dir/log")" -eq 2
scene "80, 75"
"$cli" run --resume "$dir/s.ini" >"$dir/log" 2>&1
check "resume with a new angle runs" test $? -eq 0
check "the kept angle is read back, the new one solved" \
  grep -q '0 solved, 6 read back.*6 solved, 0 read back' <(tr '\n' ' ' <"$dir/log")
check "a new angle, a new folder" test -s "$dir/out/alpha_75_hurst_0.8_lambda_s_4/table1.csv"
check "sweep.csv now has 75" test "$(awk -F, 'NR > 1 && $1 == 75' "$t" | wc -l)" -eq 2
# a list of lambda_s: the surfaces differ, so do their keys
sed -i 's/^lambda_s = 4$/lambda_s = 4, 8/' "$dir/s.ini"
"$cli" run --resume "$dir/s.ini" >"$dir/log" 2>&1
check "a lambda_s list runs" test $? -eq 0
check "four points" test "$(grep -c '^indentmap: sweep point' "$dir/log")" -eq 4
check "lambda_s = 8 solved anew" test "$(grep -c '6 solved, 0 read back' "$dir/log")" -eq 2
check "sweep.csv: 8 rows" test "$(wc -l <"$t")" -eq 9
# One surface a family: no standard deviation to give (it used to print 0, "± 0.000").
scene "80, 70" 2 one
"$cli" run --quiet "$dir/s.ini" >"$dir/log" 2>&1
check "one seed runs" test $? -eq 0
check "one seed: sweep.csv's sd is nan" test "$(awk -F, 'NR > 1 && $8 == "nan"' "$dir/one/sweep.csv" | wc -l)" -eq 4
check "one seed: table1.csv's sds are nan" \
  test "$(awk -F, 'NR > 1 && $8 == "nan" && $11 == "nan"' "$dir/one/alpha_80_hurst_0.8_lambda_s_4/table1.csv" | wc -l)" -eq 2
check "one seed: table1.md without ±" \
  grep -q '^| 0.08 | [0-9.]* | 2.20 | [0-9]* | [0-9.]* | 0.894 |' "$dir/one/alpha_80_hurst_0.8_lambda_s_4/table1.md"
# The bundled angle sweep runs (from a scratch folder: its output is output/angle_sweep) and
# A/A_cone rises with rho_c along the six angles, as eq. (12) does.
scenes=$(cd "$(dirname "$0")/../scenes" && pwd)
program=$(cd "$(dirname "$cli")" && pwd)/$(basename "$cli")
(cd "$dir" && "$program" run --quiet "$scenes/angle_sweep.ini" >/dev/null 2>&1)
check "angle_sweep.ini runs" test $? -eq 0
a=$dir/output/angle_sweep/sweep.csv
check "angle_sweep: six angles" test "$(wc -l <"$a")" -eq 7
check "angle_sweep: A/A_cone rises with rho_c, and so does eq. (12)" awk -F, 'NR > 1 { r[NR] = $5; m[NR] = $7; t[NR] = $9 }
  END { for (i = 3; i <= NR; ++i) for (j = 2; j <= NR; ++j) if (r[i] > r[j] && (m[i] <= m[j] || t[i] <= t[j])) exit 1 }' "$a"
finish
