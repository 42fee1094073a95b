#!/usr/bin/env bash
# Gap and contact-patch size distributions (measure.h: im_measure_write_distributions), from
# `indent --distributions` and a scene's [output] distributions. Checks: the gap density integrates
# to the non-contact fraction 1 - n_p / (nx ny); the patch histogram's patches are the list's rows
# and its cells add up to n_p of history.csv (or of the table's member); a smooth cone's contact is
# one patch; the flags' files are refused when they would replace an input.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
close() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'; }
integral() { awk -F, 'NR > 1 && $1 != "inf" { s += $4 * ($2 - $1) } END { printf "%.12g", s }' "$1"; }
column_sum() { awk -F, -v c="$2" 'NR > 1 { s += $c } END { print s + 0 }' "$1"; }

"$cli" surface --n 128 --slope 0.16 --seed 2 --out "$dir/s.npy" >/dev/null 2>&1
"$cli" indent "$dir/s.npy" --load 50,100 --distributions --out "$dir/ind" >/dev/null 2>&1
check "indent --distributions runs" test $? -eq 0
for step in 1 2; do
  p=$dir/ind/distributions_000$step
  for f in gaps patches patch_list; do check "step $step: $f" test -s "${p}_$f.csv"; done
  n_p=$(awk -F, -v s=$step 'NR == s + 1 { print $5 }' "$dir/ind/history.csv")
  check "step $step: gaps integrate to 1 - n_p / N" close "$(integral "${p}_gaps.csv")" "$(awk -v n="$n_p" 'BEGIN { printf "%.12g", 1 - n / 16384 }')" 1e-9
  check "step $step: histogram cells = n_p" test "$(column_sum "${p}_patches.csv" 4)" -eq "$n_p"
  check "step $step: histogram patches = list rows" test "$(column_sum "${p}_patches.csv" 3)" -eq "$(($(wc -l <"${p}_patch_list.csv") - 1))"
  check "step $step: perimeters agree" test "$(column_sum "${p}_patches.csv" 6)" = "$(column_sum "${p}_patch_list.csv" 4)"
  check "step $step: no infinite gap under a cone" grep -qx 'inf,inf,0,0' "${p}_gaps.csv"
done
# A step without contact (load 0) has distributions too: all gaps, no patch (it failed: "list is NULL").
"$cli" indent "$dir/s.npy" --load 0,50 --distributions --out "$dir/zero" >/dev/null 2>&1
check "a step at load 0: its distributions" test $? -eq 0 -a -s "$dir/zero/distributions_0001_gaps.csv"
check "a step at load 0: no patch" test "$(wc -l <"$dir/zero/distributions_0001_patch_list.csv")" -eq 1
check "several patches" test "$(wc -l <"$dir/ind/distributions_0002_patch_list.csv")" -gt 3

cat >"$dir/d.ini" <<INI
[scene]
name = d
output = $dir/out
[surfaces]
n = 64
slopes = 0, 0.16
seeds = 1:2
[punch]
shape = cone
alpha = 80
[loading]
control = load
load_star = 300
[output]
table = yes
distributions = yes
INI
"$cli" run "$dir/d.ini" >"$dir/log" 2>&1
check "scene with distributions runs" test $? -eq 0
for f in 00 01; do
  for k in gaps patches patch_list; do check "family $f: $k" test -s "$dir/out/distributions/family_${f}_$k.csv"; done
done
for f in distributions.png distributions.pdf; do check "wrote $f" test -s "$dir/out/$f"; done
check "smooth cone: one patch" test "$(wc -l <"$dir/out/distributions/family_00_patch_list.csv")" -eq 2
member=$(ls "$dir"/out/table/member_01_1.csv)
n_p=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "contact_patches") c = i } NR == 2 { print $c }' "$member")
check "rough family: cells = the table's n_p" test "$(column_sum "$dir/out/distributions/family_01_patches.csv" 4)" -eq "$n_p"
check "rough family: gaps integrate" close "$(integral "$dir/out/distributions/family_01_gaps.csv")" "$(awk -v n="$n_p" 'BEGIN { printf "%.12g", 1 - n / 4096 }')" 1e-9

# --resume with damaged distribution files: each is removed with a notice and made again, byte for byte.
cp -r "$dir/out" "$dir/first"
printf '\1\2\0\3 binary garbage' >"$dir/out/distributions/family_01_gaps.csv"
printf 'x\0y' >"$dir/out/distributions/family_00_patch_list.csv"
"$cli" run --resume "$dir/d.ini" >"$dir/log" 2>&1
check "resume over damaged distributions runs" test $? -eq 0
for f in family_01_gaps family_00_patch_list; do
  check "resume: $f.csv damaged: notice" grep -q "distributions/$f.csv holds binary data.*damaged, removed, and made again" "$dir/log"
done
for f in "$dir"/first/distributions/*.csv; do
  check "resume: $(basename "$f") as the first run's" cmp -s "$f" "$dir/out/distributions/$(basename "$f")"
done
finish
