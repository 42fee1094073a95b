#!/usr/bin/env bash
# Instrument files (issue 25): each read with the grid, spacing, unit and h_rms Gwyddion 2.62 gives for
# it, or refused with a reason that names what the file is. tests/data/instruments/ holds a few
# (MIT, see its README); the 61 files of the workplace's shared/test-data/surfaces/ are checked too
# when that folder is beside the checkout.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
here=$(cd "$(dirname "$0")" && pwd)
data=$here/data/instruments
source "$here/lib.sh"

# The text readers (no Gwyddion needed).
stats "$data/matrix-4.txt" >"$dir/vision" 2>&1
check "Vision export: grid and pixel size" grep -q 'grid             75 x 305, delta = 3.69862e-07 m' "$dir/vision"
check "Vision export: heights through the conversion factor" grep -q 'height conversion factor 2.91818e-08' "$dir/vision"
stats "$data/xyz-1-different-order.txt" >"$dir/xyz" 2>&1
check "scrambled x y z points: a 4 x 4 map" grep -q 'grid             4 x 4, delta = 1 *$' "$dir/xyz"
check "German Gwyddion export: Breite and Höhe read, non-square refused naming both" expect_exit 2 \
  "x spacing 4.11333333 and y spacing 1.419725 µm" "$cli" surface --stats "$data/gwyddion-export-german.txt"

# Line scans named as such (issue 25), whatever stands above their numbers or holds them.
line_scan="a line scan (a 1-D profile), not a map"
check "csv-1: a header row naming x and height" expect_exit 2 \
  "under the header row 'X_(microns),y1' (line 1): $line_scan" "$cli" surface --stats "$data/csv-1.csv"
check "csv-2: UTF-16 decoded, an index column beside x and height" expect_exit 2 \
  "under the header row 'index,x in µm,y in µm' (line 1): $line_scan (positions and heights, beside an index column" \
  "$cli" surface --stats "$data/csv-2.csv"
check "csv-3: UTF-16 decoded" expect_exit 2 "under the header row 'x in µm,y in µm' (line 1): $line_scan" \
  "$cli" surface --stats "$data/csv-3.csv"
check "xy-2: a row of units and a count" expect_exit 2 \
  "under a row of units 'µm µm' (line 1), a lone number, 23 (line 2): $line_scan" "$cli" surface --stats "$data/xy-2.txt"
check "Dektak CSV export named" expect_exit 2 \
  "under a Bruker Dektak profilometer's CSV export of a stylus profile ('Scan Parameters', line 1)" \
  "$cli" surface --stats "$data/dektak-1-head.csv"
check "HFM: x, height and a validity column" expect_exit 2 \
  "a row of units '[mm];[mm];[1/0]' (line 2): $line_scan (positions and heights, beside a validity column 'valid')" \
  "$cli" surface --stats "$data/hfm-1-head.hfm"
check "Mitutoyo spreadsheet: a line scan in columns E and F" expect_exit 2 \
  "a Mitutoyo SurfTest export: its fullest sheet, xl/worksheets/sheet2.xml, holds numbers in 2 columns (E, F) of 960 rows: $line_scan" \
  "$cli" surface --stats "$data/mitutoyo_mock.xlsx"

# Warnings and records a researcher needs (finding D17, D14).
printf '# Width: 6\n1 2 3\n4 5 6\n7 8 9\n' >"$dir/unnamed.txt"
check "a unitless spacing of 2: heights in its unnamed unit, not in delta" bash -c "'$cli' surface --stats '$dir/unnamed.txt' | grep -q \"heights          in the spacing's unit\""
printf '1 2 3 4\nnan 5 6 7\n8 nan 9 1\n2 3 nan 4\n' >"$dir/holes.txt"
check "--fill inventing 19% of a surface is said" expect_exit 0 "--fill invented 18.8% of the surface (3 of 16 points)" \
  "$cli" surface --stats "$dir/holes.txt" --fill
"$cli" surface --n 64 --slope 1.5 --seed 4 --out "$dir/steep.npy" >/dev/null
"$cli" indent "$dir/steep.npy" --approach 4 --out "$dir/steep" >"$dir/steep.out" 2>&1
check "h'rms beyond small slopes is said" grep -q "h'rms = 1.5: slopes steeper than 45 degrees" "$dir/steep.out"
check "... and beyond the cone's flank" grep -q "is 8.51 times the cone flank's slope cot(alpha) = 0.176" "$dir/steep.out"
check "run.json states the pressure unit" grep -q '"pressure": "the unit of --e-star"' "$dir/steep/run.json"
check "run.json keeps no radius for a cone" bash -c "! grep -q '\"radius\"' '$dir/steep/run.json'"

if "$cli" formats | grep -q "not in this build"; then
  echo "indentmap-gwyddion-read not built: the instrument formats are not checked"
  finish
  exit $?
fi
check "OPDx of a profile: Gwyddion's curves named a line scan" expect_exit 2 \
  "a line scan (a 1-D profile), not a map: Gwyddion's module 'dektakvca' reads it as 1 curve in 1 graph, the longest of 3001 points" \
  "$cli" surface --stats "$data/opdx-3.opdx"
check "formats lists Gwyddion's Nanoscope module" bash -c "'$cli' formats | grep -q '^  nanoscope '"

# Gwyddion 2.62's numbers: xres x yres, xreal / xres, gwy_data_field_get_rms of the default channel.
stats "$data/di-3.di" >"$dir/di3" 2>&1
check "Nanoscope: grid and spacing" grep -q 'grid             256 x 256, delta = 3.90625e-08 m' "$dir/di3"
check "Nanoscope: the first channel in a length unit" grep -q "channel 0 'ZSensor' of 4" "$dir/di3"
check "Nanoscope: h_rms as Gwyddion's" stated "$dir/di3" h_rms 2.26425e-07
stats "$data/di-3.di" --channel Height >"$dir/di3h" 2>&1
check "Nanoscope: --channel by title" stated "$dir/di3h" h_rms 2.64003e-07
check "Nanoscope: a channel that is not heights is refused, naming the channels" expect_exit 2 \
  "channel 2 'Phase' holds values in 'deg', not heights (a length); its channels: 0 'ZSensor' [m]" \
  "$cli" surface --stats "$data/di-3.di" --channel 2
check "Nanoscope: a channel not there" expect_exit 2 "no channel has the index or title 'Friction'" \
  "$cli" surface --stats "$data/di-3.di" --channel Friction
# The same scan through Gwyddion's text export and through the instrument file: one surface.
"$cli" surface --stats "$data/matrix-3.txt" >"$dir/m3" 2>&1
"$cli" surface --stats "$data/di-3.di" >"$dir/di3p" 2>&1
check "Gwyddion's export of the ZSensor channel gives the Nanoscope file's slopes" \
  bash -c "diff <(grep \"^h'rms\" '$dir/m3') <(grep \"^h'rms\" '$dir/di3p')"
check "... and its h_rms (µm against m)" bash -c "grep -qx 'h_rms            0.0352229' '$dir/m3' && grep -qx 'h_rms            3.52229e-08' '$dir/di3p'"
# Without its `# Value units:` line (finding D8b) the export's heights are taken in the Width's unit, µm, and
# said so on stderr, naming the file and the unit; --height-unit states theirs, and nothing is said.
grep -v '^# Value units:' "$data/matrix-3.txt" >"$dir/no-value-units.txt"
"$cli" surface --stats "$dir/no-value-units.txt" >"$dir/nvu" 2>"$dir/nvu.err"
check "no Value units: read (exit 0)" test $? -eq 0
check "... warned, naming the file and the unit taken" grep -qF \
  "warning: $dir/no-value-units.txt: no '# Value units:' line: its heights are taken in µm, the lateral unit" "$dir/nvu.err"
check "... heights taken as µm unconverted: h_rms 1e6 times too small" grep -qx 'h_rms            3.52229e-08' "$dir/nvu"
"$cli" surface --stats "$dir/no-value-units.txt" --height-unit m >"$dir/nvu-m" 2>"$dir/nvu-m.err"
check "--height-unit m: converted as with the line" grep -qx 'h_rms            0.0352229' "$dir/nvu-m"
check "... and no warning" bash -c "! grep -q warning '$dir/nvu-m.err' && ! grep -q warning '$dir/m3'"
stats "$data/stp-1.stp" >"$dir/stp" 2>&1
check "WSxM: grid and spacing" grep -q 'grid             256 x 256, delta = 2.34375e-09 m' "$dir/stp"
check "WSxM: h_rms as Gwyddion's" stated "$dir/stp" h_rms 1.65416e-09
stats "$data/al3d-1.al3d" >"$dir/al3d" 2>&1
check "Alicona: grid and spacing" grep -q 'grid             200 x 296, delta = 4.38027e-07 m' "$dir/al3d"
# Gwyddion's rms is one-pass: heights 1e4 times their rms lose it about 3e-6 (two-pass: 7.688266e-06).
check "Alicona: h_rms as Gwyddion's (to its one-pass rounding)" stated "$dir/al3d" h_rms 7.68829e-06 1e-5
stats "$data/10x10-one_channel_without_name.ibw" >"$dir/ibw" 2>&1
check "Igor wave without units: read as a bare matrix" grep -q 'grid             10 x 10, delta = 1 *$' "$dir/ibw"
check "Igor wave: h_rms as Gwyddion's" stated "$dir/ibw" h_rms 0.480049
head -c 300000 "$data/di-3.di" >"$dir/cut.di"
check "a truncated Nanoscope file is refused by its module's reason" expect_exit 2 \
  "cut.di: Gwyddion's file modules cannot read it: File is truncated" "$cli" surface --stats "$dir/cut.di"
printf 'GARBAGE\0\1\2\3 not a surface' >"$dir/junk.bin"
check "a binary file no module reads" expect_exit 2 "junk.bin: a binary file no reader here opens: none of Gwyddion's" \
  "$cli" surface --stats "$dir/junk.bin"
"$cli" indent "$data/stp-1.stp" --channel Topography --crop 96,96,64,64 --approach 1e-9:4e-9:2 --out "$dir/run" \
  >"$dir/indent" 2>&1
check "indent solves on a WSxM scan's channel" grep -q '^2,' "$dir/run/history.csv"
check "... and run.json names the module and channel" grep -q "\"values\": \"Gwyddion 'wsxmfile': channel 0 'Topography' of 1\"" "$dir/run/run.json"
# A scene over an instrument file: its channel key, the file's own h'rms in the table and run.json.
printf '[scene]\nname = wsxm\noutput = wsxm\n[surfaces]\nfile = %s\nchannel = 0\nalign = median\n[loading]\nload_star = 100\n[output]\ntable = yes\n' \
  "$data/stp-1.stp" >"$dir/wsxm.ini"
"$cli" run --quiet "$dir/wsxm.ini" >/dev/null 2>"$dir/wsxm.err"
slope=$(stats "$data/stp-1.stp" --channel Topography --align median | awk '/^h.rms fd/ { print $3 }')
check "a scene over a WSxM scan: its table's slope is the file's h'rms ($slope)" \
  test "$(sed -n 2p "$dir/wsxm/table1.csv" | cut -d, -f1)" = "$slope"
check "... and run.json records the channel" grep -q '"channel": "0"' "$dir/wsxm/run.json"
check "... and the rows' alignment" grep -q '"align": "median"' "$dir/wsxm/run.json"
check "surface --stats states the alignment" bash -c "'$cli' surface --stats '$data/stp-1.stp' --align line | grep -q 'rows aligned (line)'"

# refused_with PHRASE OUTPUT: surface --stats printed PHRASE and no grid.
refused_with() { grep -qF -- "$1" "$2" && ! grep -q '^grid' "$2"; }

# The shared folder's 61 files: read (grid given) or refused with the phrase that says why.
shared=${IM_TEST_SURFACES:-$here/../../shared/test-data/surfaces}
if [ ! -d "$shared" ]; then
  echo "no $shared: the 61 shared instrument files are not checked"
  finish
  exit $?
fi
while read -r file outcome rest; do
  [ -z "$file" ] && continue
  "$cli" surface --stats "$shared/$file" >"$dir/one" 2>&1
  if [ "$outcome" = read ]; then
    check "$file: read $rest" grep -q "^grid             $rest" "$dir/one"
  else
    check "$file: refused ($rest)" refused_with "$rest" "$dir/one"
  fi
done <"$here/data/instrument_outcomes.txt"
finish
