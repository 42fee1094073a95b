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

# Seeds beyond JSON's signed integers (2^63 and 2^64 - 1) are recorded as the decimal typed, which --seed takes
# back by hand to the same surface; indent's run.json records it so too.
for seed in 9223372036854775808 18446744073709551615; do
  "$cli" surface --n 16 --seed "$seed" --out "$dir/big.npy" >/dev/null
  check "seed $seed: the sidecar's decimal" grep -q "\"seed\": $seed\$" "$dir/big.npy.json"
  recorded=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["generator"]["seed"])' "$dir/big.npy.json")
  check "seed $seed: --seed takes it back" "$cli" surface --n 16 --seed "$recorded" --out "$dir/again.npy"
  check "seed $seed: the same surface" cmp "$dir/big.npy" "$dir/again.npy"
done
"$cli" indent "$dir/big.npy" --periodic --pressure 0.01 --out "$dir/big_run" >/dev/null 2>&1
check "indent's run.json records the seed" grep -q '^  "seed": 18446744073709551615,$' "$dir/big_run/run.json"

# The same seed gives the same bytes for any thread count.
OMP_NUM_THREADS=1 "$cli" surface --n 96 --seed 9 --out "$dir/one.npy" >/dev/null
OMP_NUM_THREADS=2 "$cli" surface --n 96 --seed 9 --out "$dir/two.npy" >/dev/null
check "thread-count determinism" cmp -s "$dir/one.npy" "$dir/two.npy"

# Measuring files, good and bad.
check "stats of a written file" bash -c "'$cli' surface --stats '$dir/s.npy' | grep -q 'h_rms'"
# ... a file this program generated is measured as made (its sidecar records the generator): its requested
# h'rms, as indent and scenes take it (redteam3 R6: the plane and Hann taper of measured data gave 0.0728 for
# 0.08); a preparation asked for, or the same heights without the sidecar, are measured as data
check "a generated file measured as made" bash -c "'$cli' surface --stats '$dir/s.npy' | grep -q \"h'rms spectral   0.05 \""
cp "$dir/s.npy" "$dir/bare.npy"
check "without its sidecar, as measured data" bash -c "'$cli' surface --stats '$dir/bare.npy' | grep -q 'preparation      plane removed; .* Hann-tapered'"
check "a preparation asked for is kept" bash -c "'$cli' surface --stats '$dir/s.npy' --detrend plane | grep -q 'Hann-tapered'"
printf '# Width: 3 um\n1 2 3\n4 five 6\n' >"$dir/bad.txt"
check "text matrix line number" expect_exit 2 "bad.txt:3: 'five' is not a number" "$cli" surface --stats "$dir/bad.txt"
head -c 100 "$dir/s.npy" >"$dir/cut.npy"
check "truncated npy" expect_exit 2 "truncated" "$cli" surface --stats "$dir/cut.npy"
check "missing file" expect_exit 1 "cannot open" "$cli" surface --stats "$dir/none.npy"
check "unwritable output" expect_exit 1 "/no/such/dir/s.npy" "$cli" surface --n 32 --out /no/such/dir/s.npy

# Bad surface files: exit 2 with a message naming the file and what is wrong. npy FILE DESCR ORDER
# SHAPE COUNT [LAST]: a .npy of COUNT zero float64 values (the last one replaced by the 8 bytes of
# LAST, e.g. a NaN), built byte by byte.
npy() {
  local dict="{'descr': '$2', 'fortran_order': $3, 'shape': $4, }"
  local pad=$(( (64 - (10 + ${#dict} + 1) % 64) % 64 ))
  local length=$(( ${#dict} + 1 + pad )) zeros=$5
  [ -z "${6:-}" ] || zeros=$(( $5 - 1 ))
  {
    printf '\x93NUMPY\x01\x00'
    printf "\\x$(printf %02x $((length & 255)))\\x$(printf %02x $((length >> 8)))"
    printf '%s%*s\n' "$dict" "$pad" ''
    head -c $(( zeros * 8 )) /dev/zero
    if [ -n "${6:-}" ]; then printf "$6"; fi
  } >"$1"
}
npy "$dir/good.npy" '<f8' False '(2, 3)' 6
check "hand-built npy is read" bash -c "'$cli' surface --stats '$dir/good.npy' | grep -q 'grid             3 x 2'"
npy "$dir/complex.npy" '<c16' False '(2, 3)' 12
check "unsupported dtype" expect_exit 2 "complex.npy: dtype '<c16' is not supported" "$cli" surface --stats "$dir/complex.npy"
npy "$dir/int.npy" '<i8' True '(2, 3)' 6
check "int64 in Fortran order is read, the conversion stated" bash -c "'$cli' surface --stats '$dir/int.npy' | grep -q \"values           '<i8' (int64) converted to float64; Fortran order transposed to C order\""
npy "$dir/nan.npy" '<f8' False '(2, 3)' 6 '\x00\x00\x00\x00\x00\x00\xf8\x7f'
check "NaN height" expect_exit 2 "nan.npy: value nan at (x=2, y=1)" "$cli" surface --stats "$dir/nan.npy"
npy "$dir/short.npy" '<f8' False '(3, 3)' 8
check "shape larger than the data" expect_exit 2 "short.npy: truncated data: the header (shape (3, 3) of <f8) needs 72 bytes" \
  "$cli" surface --stats "$dir/short.npy"
npy "$dir/long.npy" '<f8' False '(2, 2)' 5
check "shape smaller than the data" expect_exit 2 "long.npy: more data than the header (shape (2, 2) of <f8)" \
  "$cli" surface --stats "$dir/long.npy"
"$cli" surface --n 16 --seed 2 --out "$dir/s16.txt" >/dev/null
head -n 14 "$dir/s16.txt" >"$dir/cut16.txt"   # 3 header lines and 11 of the 16 rows
check "text matrix shorter than its header" expect_exit 2 \
  "cut16.txt:1: the header states 16 columns x 16 rows, but the file has 16 columns x 11 rows" \
  "$cli" surface --stats "$dir/cut16.txt"

# An output never replaces the measured file: exit 2 naming both paths, the input byte-identical.
cp "$dir/s.npy" "$dir/s.orig"
check "--psd onto the input" expect_exit 2 "--psd $dir/s.npy would overwrite the input file $dir/s.npy" \
  "$cli" surface --stats "$dir/s.npy" --psd "$dir/s.npy"
check "--histograms onto the input by another path" expect_exit 2 "would overwrite the input file $dir/s.npy" \
  "$cli" surface --stats "$dir/s.npy" --histograms "$dir/../$(basename "$dir")/./s.npy"
ln -s "$dir/s.npy" "$dir/link.npy"
check "--png onto a symlink to the input" expect_exit 2 "--png $dir/link.npy would overwrite the input file $dir/s.npy" \
  "$cli" surface --stats "$dir/s.npy" --png "$dir/link.npy"
check "--out onto the input" expect_exit 2 "--out $dir/s.npy would overwrite" \
  "$cli" surface --stats "$dir/s.npy" --out "$dir/s.npy"
check "input unchanged" cmp -s "$dir/s.npy" "$dir/s.orig"
check "no temporary files left" bash -c "! ls '$dir' | grep -q tmp"

# Units (issue 13): --delta, --unit and --height-unit set what a .npy cannot state.
check "--stats honours --delta and --unit" bash -c "'$cli' surface --stats '$dir/s.npy' --delta 5e-8 --unit m | grep -q 'grid             64 x 64, delta = 5e-08 m'"
check "--height-unit converts to --unit" bash -c "'$cli' surface --stats '$dir/s.npy' --delta 1 --unit um --height-unit nm --detrend none --window none | grep -q 'h.rms spectral   5e-05 '"
check "unknown unit" expect_exit 2 "--unit 'parsec': expected a length unit" "$cli" surface --stats "$dir/s.npy" --unit parsec
check "heights in a unit, spacing in none" expect_exit 2 "--height-unit = 'nm' gives the heights a unit" \
  "$cli" surface --stats "$dir/s.npy" --height-unit nm
printf '# Width: 3 um\n# Height: 6 um\n1 2 3\n4 5 6\n7 8 9\n' >"$dir/rect.txt"
check "non-square pixels refused" expect_exit 2 "rect.txt: Width / columns and Height / rows: non-square pixels" \
  "$cli" surface --stats "$dir/rect.txt"
check "the refusal names the spacings, the tolerance and the option" expect_exit 2 \
  "x spacing 1 and y spacing 2 um differ by 0.667 of their mean, beyond the 0.002 (the extents' printed digits) that rounding explains: resample them onto square pixels (--resample-square;" \
  "$cli" surface --stats "$dir/rect.txt"

# Square pixels (issue 25): spacings within 2^-16 of each other read as square (their mean, the
# difference stated; extents printed with 6 digits, which leave less open than 2^-16; "3 um" above leaves
# the most a header may, 0.002); beyond, --resample-square resamples onto the finer spacing (1 x 2 um: 3 x 5 of 1 um).
check "--resample-square" bash -c "'$cli' surface --stats '$dir/rect.txt' --resample-square | grep -q 'grid             3 x 5, delta = 1 '"
check "--resample-square is stated" bash -c "'$cli' surface --stats '$dir/rect.txt' --resample-square | grep -q 'pixels           3 x 3 of 1 x 2 .*m, resampled (bilinear) onto square pixels of 1 .*m'"
check "--resample-square keeps the values" bash -c "'$cli' surface --stats '$dir/rect.txt' --resample-square --detrend none --window none | grep -q 'mean             5$'"
check "--resample-square on generation refused" expect_exit 2 "use them with --stats" "$cli" surface --n 16 --resample-square
printf '# Width: 3.00000 um\n# Height: 3.00003 um\n1 2 3\n4 5 6\n7 8 9\n' >"$dir/near.txt"
check "near-square pixels read as square" bash -c "'$cli' surface --stats '$dir/near.txt' | grep -q 'grid             3 x 3, delta = 1.00001 '"
check "near-square pixels stated" bash -c "'$cli' surface --stats '$dir/near.txt' | grep -q 'pixels           x spacing 1 and y spacing 1.00001 .*m differ by 1e-05 of their mean, within the 1.53e-05 that rounding explains: read as square, of their mean'"
check "square pixels say nothing" bash -c "! '$cli' surface --stats '$dir/s.npy' | grep -q '^pixels'"

# Preparation (issue 13): missing points refused with their position or filled; crop; the statement.
printf '1 2 3 4\n5 nan 6 7\n8 9 1 2\n' >"$dir/hole.txt"
check "missing point refused" expect_exit 2 "hole.txt: value nan at (x=1, y=1): a missing point" "$cli" surface --stats "$dir/hole.txt"
check "--fill fills it" bash -c "'$cli' surface --stats '$dir/hole.txt' --fill --detrend none --window none | grep -q 'height range     \[1, 9\]'"
check "--fill is stated" bash -c "'$cli' surface --stats '$dir/hole.txt' --fill | grep -q '1 missing points filled'"
check "stats state the preparation" bash -c "'$cli' surface --stats '$dir/bare.npy' | grep -q 'preparation      plane removed; spectral quantities and PSD of the Hann-tapered surface'"
check "--crop" bash -c "'$cli' surface --stats '$dir/s.npy' --crop 8,4,32,16 | grep -q 'grid             32 x 16'"
check "--crop outside" expect_exit 2 "--crop: crop 40,0,32,16: expected X0,Y0,NX,NY" "$cli" surface --stats "$dir/s.npy" --crop 40,0,32,16
check "--window on generation refused" expect_exit 2 "use them with --stats" "$cli" surface --n 16 --window hann

finish
