#!/usr/bin/env bash
# Scenes over surface files (issue 13, reliability finding 4): the theory is taken at the files' own
# measured h'rms (not the default slope 0.08 or a `slopes` label), a list of files is the ensemble,
# and `slopes`/`seeds` and the generator's parameters beside `file` are refused at their line. The h'rms is spectral for generated files
# of spectral h'rms (their sidecar says so: the h'rms their family had generated, researcher finding R5)
# and by forward differences for any other file, as `indent` measures them.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

source "$(dirname "$0")/lib.sh"

"$cli" surface --n 64 --slope 0.16 --seed 2 --out "$dir/a.npy" >/dev/null
"$cli" surface --n 64 --slope 0.12 --seed 5 --out "$dir/b.npy" >/dev/null
"$cli" surface --n 32 --slope 0.12 --seed 5 --out "$dir/small.npy" >/dev/null
fd_slope() { "$cli" surface --stats "$1" --detrend none --window none | awk '/^h.rms fd/ { print $3 }'; }
spectral_slope() { "$cli" surface --stats "$1" --detrend none --window none | awk '/^h.rms spectral/ { print $3 }'; }

scene() { # scene NAME FILE-LINE [EXTRA-LINE]
  printf '[scene]\nname = %s\noutput = %s\n[surfaces]\n%s\n%s\n[loading]\nload_star = 100\n[output]\ntable = yes\n' \
    "$1" "$1" "$2" "${3:-}" >"$dir/$1.ini"
}

# One file: the table's slope is the file's h'rms, spectral for a generated file: its target, as its
# family had it generated; its eq. (12) column is `indentmap theory` at that h'rms.
scene one "file = a.npy"
"$cli" run --quiet "$dir/one.ini" >/dev/null 2>"$dir/one.err"
check "one file: runs" test $? -eq 0
slope=$(spectral_slope "$dir/a.npy")
row=$(sed -n 2p "$dir/one/table1.csv")
check "one file: slope column is the file's spectral h'rms, its target ($slope)" \
  test "$(cut -d, -f1 <<<"$row")" = "$slope" -a "$slope" = 0.16
theory=$("$cli" theory --alpha 80 --slope "$slope" --format csv | awk -F, 'NR == 2 { print $4 }')
check "one file: eq. (12) column is indentmap theory at it ($theory)" \
  awk -v a="$(cut -d, -f9 <<<"$row")" -v b="$theory" 'BEGIN { exit !(a - b < 1e-6 && b - a < 1e-6) }'
check "one file: the definition is stated" grep -q "measured by the spectrum" "$dir/one/table1.md"
check "one file: table1.md counts in the singular" grep -q "the 1 file of \`file\`" "$dir/one/table1.md"
check "... and 1 surface per h'rms" grep -q "1 surface per h'rms" "$dir/one/table1.md"
check "one file: run.json records it" grep -q '"slope_definition": "spectral, of each surface' "$dir/one/run.json"
check "one file: run.json says what chose it" grep -q '"chosen_by": "default: generated surfaces' "$dir/one/run.json"
check "one file: run.json records the length unit" grep -q '"length_unit": "delta"' "$dir/one/run.json"

# Any other file (a scan: its spectrum would count the steps across its edges; here the same generated
# surface without its sidecar): forward differences.
cp "$dir/a.npy" "$dir/scan.npy"
scene scan "file = scan.npy"
"$cli" run --quiet "$dir/scan.ini" >/dev/null 2>"$dir/scan.err"
check "a scan: runs" test $? -eq 0
fd=$(fd_slope "$dir/scan.npy")
check "a scan: slope column is its fd h'rms ($fd)" grep -q "^$fd," "$dir/scan/table1.csv"
check "a scan: the definition is stated" grep -q "measured by forward differences" "$dir/scan/table1.md"
check "a scan: run.json records it" grep -q '"slope_definition": "forward differences' "$dir/scan/run.json"
check "a scan: run.json says what chose it" grep -q '"chosen_by": "default: measured surfaces' "$dir/scan/run.json"

# Two files are an ensemble of two: slope the rms of theirs, one member each with its own h'rms.
scene two "file = a.npy, b.npy"
"$cli" run --quiet "$dir/two.ini" >/dev/null 2>"$dir/two.err"
check "two files: runs" test $? -eq 0
sb=$(spectral_slope "$dir/b.npy")
rms=$(awk -v a="$slope" -v b="$sb" 'BEGIN { printf "%.6g", sqrt((a * a + b * b) / 2) }')
check "two files: 2 surfaces, slope the rms ($rms)" grep -q "^$rms,2," "$dir/two/table1.csv"
check "two files: table1.md counts in the plural" grep -q "The surfaces are the 2 files of \`file\`" "$dir/two/table1.md"
check "two files: members keep their own h'rms" \
  bash -c "cat '$dir'/two/table/member_00_*.csv | grep -v '^family' | cut -d, -f2 | sort -u | wc -l | grep -qx 2"
check "two files: sd over different surfaces is not 0" \
  awk -F, 'NR == 2 { exit !($8 > 0) }' "$dir/two/table1.csv"

scene slopes "file = a.npy" "slopes = 0.16"
check "slopes beside file refused at its line" expect_exit 2 "slopes.ini:6: slopes beside \`file\` (line 5)" \
  "$cli" run --quiet "$dir/slopes.ini"
scene seeds "file = a.npy" "seeds = 1:3"
check "seeds beside file refused at its line" expect_exit 2 "seeds.ini:6: seeds beside \`file\` (line 5)" \
  "$cli" run --quiet "$dir/seeds.ini"
# the generator's parameters beside files were taken without effect (a flat_k over files with
# `slope_definition = fd` measured them spectrally all the same): refused at their line
for key in "hurst = 0.5" "lambda_s = 8" "lambda_r = 32" "lambda_0 = 40" "slope_definition = fd"; do
  name=${key%% *}
  scene "$name" "file = a.npy" "$key"
  check "$name beside file refused at its line" expect_exit 2 "$name.ini:6: $name beside \`file\` (line 5)" \
    "$cli" run --quiet "$dir/$name.ini"
done
scene mixed "file = a.npy, small.npy"
check "files of different grids refused" expect_exit 2 "small.npy is 32 x 32 with delta 1  but $dir/a.npy is 64 x 64" \
  "$cli" run --quiet "$dir/mixed.ini"

# Pixels 1 x 2 um (issue 25): refused naming the key; `resample_square = yes` resamples them, and
# A file in metres (researcher finding R3): table1's mean h_rms is in units of delta, as run.json's
# units say, not in the file's length unit (it printed 0.00 for heights of 0.27 delta).
"$cli" surface --n 64 --slope 0.1 --seed 5 --delta 1e-7 --unit m --out "$dir/metres.nc" >/dev/null
h_over_delta=$("$cli" surface --stats "$dir/metres.nc" --detrend none --window none |
  awk '/^grid/ { delta = $7 } /^h_rms / { printf "%.6g", $2 / delta }')
scene metres "file = metres.nc"
"$cli" run --quiet "$dir/metres.ini" >/dev/null 2>"$dir/metres.err"
check "a file in metres: table1.csv's height_rms_mean is h_rms / delta ($h_over_delta)" \
  test "$(sed -n 2p "$dir/metres/table1.csv" | cut -d, -f3)" = "$h_over_delta"
check "... and table1.md's mean h_rms/δ column" \
  grep -q "| $(printf '%.2f' "$h_over_delta") | " "$dir/metres/table1.md"

# run.json records the key and, per file, the spacings' difference and the method.
"$cli" surface --n 64 --slope 0.1 --out "$dir/square.txt" >/dev/null
(printf '# Width: 64 um\n# Height: 128 um\n'; grep -v '^#' "$dir/square.txt") >"$dir/rect.txt"
scene rect "file = rect.txt"
check "non-square pixels refused naming the key" expect_exit 2 "resample_square = yes in a scene" \
  "$cli" run --quiet "$dir/rect.ini"
scene rect "file = rect.txt" "resample_square = yes"
"$cli" run --quiet "$dir/rect.ini" >/dev/null 2>"$dir/rect.err"
check "resample_square: runs" test $? -eq 0
check "resample_square: run.json records it" python3 -c '
import json, sys
files = json.load(open(sys.argv[1]))["surface_files"]
entry = files["files"][0]
sys.exit(not (files["resample_square"] is True and entry["resampled"] == "bilinear"
              and abs(entry["spacing_difference"] - 2 / 3) < 1e-15 and files["delta"] == 1.0))' "$dir/rect/run.json"


# Generated families record the definition of their target ([surfaces] slope_definition), not always
# "spectral".
scene fdgen "n = 32" "slope_definition = fd"
"$cli" run --quiet "$dir/fdgen.ini" >/dev/null 2>"$dir/fdgen.err"
check "generated fd family: runs" test $? -eq 0
check "generated fd family: run.json says finite differences" \
  bash -c "grep -A1 '\"theory_slope_rms\"' '$dir/fdgen/run.json' | grep -q '\"definition\": \"finite differences\"'"

# A Gwyddion text export without its `# Value units:` line (finding D8b): its heights are taken in the Width's
# unit, as `surface --stats` and `indent` read it, and the scene says so, naming the scene and the file.
grep -v '^# Value units:' "$(dirname "$0")/data/instruments/matrix-3.txt" >"$dir/no-value-units.txt"
scene unstated "file = no-value-units.txt"
"$cli" run --quiet "$dir/unstated.ini" >/dev/null 2>"$dir/unstated.err"
check "no Value units: runs" test $? -eq 0
check "... and warns, naming the scene, the file and the unit taken" grep -qF \
  "$dir/unstated.ini: $dir/no-value-units.txt: no '# Value units:' line: its heights are taken in µm, the lateral unit" \
  "$dir/unstated.err"
check "... once" test "$(grep -c "Value units" "$dir/unstated.err")" = 1

finish
