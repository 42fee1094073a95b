#!/usr/bin/env bash
# Reading is bounded and checked (issue 12): devices, directories and pipes as inputs, NUL bytes,
# byte-order marks, overlong lines, memory limits while reading, SIGINT during a read, and scene
# files that are empty, repeat a key or a section, or hold empty list items. Each case must end
# promptly with a message naming the file (and line) and a non-zero exit.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
export OMP_NUM_THREADS=1

printf '0 1 0 1\n1 0 1 0\n0 1 0 1\n1 0 1 0\n' >"$dir/s.txt"

# Inputs that are not regular files: refused at once (before: /dev/zero grew memory without end).
check "surface /dev/zero" expect_exit 2 "/dev/zero is a character device" \
  timeout -k 2 5 "$cli" indent /dev/zero --approach 1 --out "$dir/o1"
check "surface directory" expect_exit 2 "$dir is a directory" "$cli" surface --stats "$dir"
check "--wisdom /dev/zero" expect_exit 2 "wisdom file /dev/zero: /dev/zero is not a regular file" \
  timeout -k 2 5 "$cli" indent "$dir/s.txt" --approach 0.1 --wisdom /dev/zero --out "$dir/o2"
cat >"$dir/zero.ini" <<INI
[scene]
name = zero
output = out_zero
[surfaces]
file = /dev/zero
[loading]
load_star = 10
[output]
table = yes
INI
check "scene file = /dev/zero" expect_exit 2 "/dev/zero is a character device" \
  timeout -k 2 5 "$cli" run --quiet "$dir/zero.ini"

# Text: a NUL byte ends nothing silently; a byte-order mark is skipped at the start, shown elsewhere.
printf '0 1\x00 5\n1 0\n' >"$dir/nul.txt"
check "NUL byte" expect_exit 2 "nul.txt:1: a NUL byte at column 4" "$cli" surface --stats "$dir/nul.txt"
printf '\xef\xbb\xbf0 1 2 3\n1 0 2 3\n3 4 5 6\n' >"$dir/bom.txt"
check "leading BOM skipped" "$cli" surface --stats "$dir/bom.txt"
printf '0 1\n\xef\xbb\xbf1 0\n' >"$dir/bom2.txt"
check "BOM shown" expect_exit 2 "bom2.txt:2: '\\xef\\xbb\\xbf1' is not a number" "$cli" surface --stats "$dir/bom2.txt"
# A line of more values than any grid side names the file and the line.
awk 'BEGIN { for (i = 0; i < 70000; ++i) printf "1 "; print "" }' >"$dir/wide.txt"
check "overlong row" expect_exit 2 "wide.txt:1: more than 65536 values on one line" \
  "$cli" surface --stats "$dir/wide.txt"

# Memory runs out while reading a pipe: the reason, not "no data rows" (getline's ENOMEM was EOF).
row=$(seq -s ' ' 1 4000)
yes "$row" | IM_MEMORY_LIMIT_MIB=20 timeout -s KILL 60 "$cli" surface --stats /dev/stdin >/dev/null 2>"$dir/mem.err"
check "memory limit while reading: exit 2" test "${PIPESTATUS[1]}" -eq 2
check "memory limit while reading: message" grep -q "/dev/stdin:[0-9]*: room for [0-9]* values needs about" "$dir/mem.err"

# SIGINT while a long pipe is read ends the program promptly with the interrupted status (130).
# (the 60 s SIGKILL only ends a program that ignores SIGINT, as one did, whose memory then grew)
(yes "$row" | timeout -s KILL 60 "$cli" indent /dev/stdin --approach 1 --out "$dir/o3" 2>"$dir/int.err"
 echo "${PIPESTATUS[1]}" >"$dir/int.status") &
sleep 1
pid=$(pgrep -n -x -f "$cli indent /dev/stdin --approach 1 --out $dir/o3")
start=$SECONDS
kill -INT "$pid"
wait
check "SIGINT during a read: exit 130" test "$(cat "$dir/int.status")" -eq 130
check "SIGINT during a read: prompt" test $((SECONDS - start)) -le 5
check "SIGINT during a read: message" grep -q "/dev/stdin:[0-9]*: reading interrupted by signal 2" "$dir/int.err"
check "SIGINT: first signal acknowledged" grep -q "stopping at the next safe point" "$dir/int.err"

# .npy of another rank: the shape without the header's padding.
npy() { # npy FILE SHAPE: a <f8 .npy header with that shape, no data
  local dict="{'descr': '<f8', 'fortran_order': False, 'shape': $2, }"
  local pad=$((128 - 10 - ${#dict} - 1))
  { printf '\x93NUMPY\x01\x00\x76\x00'; printf '%s%*s\n' "$dict" "$pad" ''; } >"$1"
}
npy "$dir/one.npy" "(4,)"
check "1-D .npy message" expect_exit 2 "one.npy: shape (4,): expected a 2-D shape" "$cli" surface --stats "$dir/one.npy"
check "1-D .npy: no header junk" bash -c "! grep -q '}' '$dir/err'"

# Scenes: an empty file asks for nothing; a key or a section given twice; empty list items.
scene_refused() { # scene_refused NAME PATTERN TEXT
  printf '%b' "$3" >"$dir/$1.ini"
  check "scene $1" expect_exit 2 "$2" "$cli" run --quiet "$dir/$1.ini"
}
scene_refused empty "empty.ini: no settings" ""
scene_refused dupkey "dupkey.ini:3: [surfaces] n is given twice (first on line 2)" "[surfaces]\nn = 64\nn = 32\n"
scene_refused dupsection "dupsection.ini:4: [surfaces] is opened twice (first on line 1)" \
  "[surfaces]\nn = 64\n[output]\n[surfaces]\nm = 32\n"
scene_refused noslopes "noslopes.ini:2: slopes = '': expected a list v1, v2, ..." "[surfaces]\nslopes =\n"
scene_refused emptyitem "emptyitem.ini:2: slopes = '0.1,,0.2': an empty item" "[surfaces]\nslopes = 0.1,,0.2\n"
check "scene /dev/null" expect_exit 2 "/dev/null is a character device" "$cli" run --quiet /dev/null

# Hexadecimal numbers (strtod's C99 "0x10" = 16, "0x1p3" = 8) were read (T11): refused wherever a number is
# read from text, naming the option or the file and line; decimals with exponents still read.
check "--alpha 0x10" expect_exit 2 "--alpha: '0x10' is not a finite number" \
  "$cli" indent --smooth --n 32 --approach 2 --alpha 0x10
check "a step list's 0x1" expect_exit 2 "--approach '0x1,2': '0x1' is not a number" \
  "$cli" indent --smooth --n 32 --approach 0x1,2
check "--window tukey:0x0.8" expect_exit 2 "--window 'tukey:0x0.8': expected none" \
  "$cli" surface --stats "$dir/s.txt" --window tukey:0x0.8
printf '1 2 3\n4 0x1p3 6\n7 8 9\n' >"$dir/hex.txt"
check "a text matrix's 0x1p3" expect_exit 2 "hex.txt:2: '0x1p3' is not a number" "$cli" surface --stats "$dir/hex.txt"
printf '1 2 3\n4 -0X8 6\n7 8 9\n' >"$dir/hexneg.txt"
check "... signed, upper case" expect_exit 2 "hexneg.txt:2: '-0X8' is not a number" "$cli" surface --stats "$dir/hexneg.txt"
printf 'x,y,z\n0,0,1\n1,0,0x2\n0,1,3\n1,1,4\n' >"$dir/hexpoints.csv"
check "an x,y,z file's 0x2" expect_exit 2 "hexpoints.csv:3:" "$cli" surface --stats "$dir/hexpoints.csv"
printf '0 0\n1 0x1\n' >"$dir/hexprofile.txt"
check "a profile's 0x1" expect_exit 2 "hexprofile.txt:2: '1 0x1': expected two numbers" \
  "$cli" indent --smooth --n 32 --punch profile --profile "$dir/hexprofile.txt" --approach 1
scene_refused hexslope "hexslope.ini:2: slopes = '0x0.1': '0x0.1' is not a number" "[surfaces]\nslopes = 0x0.1\n"
printf '1e0 2.5E-1 -0.0 +3\n0 1 2 3\n4 5 6 7\n8 9 10 11\n' >"$dir/decimal.txt"
check "decimal numbers with exponents and signs still read" "$cli" surface --stats "$dir/decimal.txt"

# --resume reads back only whole histories: one cut short and one holding a NaN are solved again
# with a notice (before: accepted, and the figures drawn from them).
cat >"$dir/h.ini" <<INI
[scene]
name = h
output = h_out
[surfaces]
n = 32
slopes = 0.08
seeds = 1:3
[punch]
shape = cone
[loading]
control = displacement
steps = 0.5:3:6
[output]
plots = fig5
INI
"$cli" run "$dir/h.ini" >/dev/null 2>&1
cp -r "$dir/h_out/histories" "$dir/whole"
kept=$dir/h_out/histories
head -n 4 "$dir/whole/member_00_1.csv" >"$kept/member_00_1.csv"
sed -i '5s/^\(\([^,]*,\)\{5\}\)[^,]*/\1nan/' "$kept/member_00_2.csv"  # its A/A_cone
sed -i '4s/^2,1,/2,9,/' "$kept/member_00_3.csv" # an edit (approach 1 -> 9) that leaves a whole row: only the checksum sees it
"$cli" run --resume "$dir/h.ini" >/dev/null 2>"$dir/resume.err"
check "resume: exit 0" test $? -eq 0
check "resume: cut history named" grep -q "member_00_1.csv is damaged (2 rows where its header says 6" "$dir/resume.err"
check "resume: NaN named" grep -q "member_00_2.csv is damaged (row 3 holds a value that is not finite" "$dir/resume.err"
check "resume: edit named" grep -q "member_00_3.csv is damaged (its rows do not match the checksum" "$dir/resume.err"
check "resume: three solved again" grep -q "histories: 3 surfaces: 3 solved, 0 read back" "$dir/resume.err"
"$cli" run --resume "$dir/h.ini" >/dev/null 2>"$dir/resume2.err"
check "resume: whole histories read back" grep -q "histories: 3 surfaces: 0 solved, 3 read back" "$dir/resume2.err"
for f in "$dir"/whole/*.csv; do
  check "resume: $(basename "$f") whole again" cmp <(history_rows "$f") <(history_rows "$kept/$(basename "$f")")
done
finish
