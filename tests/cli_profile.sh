#!/bin/bash
# indentmap indent --punch profile --profile FILE: a sampled cone gives the cone's history (text table
# and .npy field), the run records the profile, bad files are refused naming file and line (exit 2
# for usage and a bad file, nothing written).
set -u
BIN="$1"
DIR=$(mktemp -d)
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v python3 >/dev/null || { echo "no python3: skipped"; exit 77; }

"$BIN" surface --n 64 --slope 0.05 --seed 7 --out "$DIR/s.npy" >/dev/null || fail "surface exited $?"
"$BIN" indent "$DIR/s.npy" --approach 0.5,1.5 --tol 1e-8 --out "$DIR/cone" >/dev/null || fail "cone run exited $?"

# An 80 degree cone, 5 samples to r = 40 (cot 80 = 0.17632698070846498), with a header and a comment.
python3 - "$DIR/cone.csv" <<'PY'
import math, sys
with open(sys.argv[1], "w") as f:
    f.write("r,z\n# an 80 degree cone\n")
    for i in range(5):
        r = 10.0 * i
        f.write(f"{r!r},{r / math.tan(math.radians(80))!r}\n")
PY
"$BIN" indent "$DIR/s.npy" --approach 0.5,1.5 --tol 1e-8 --punch profile --profile "$DIR/cone.csv" --out "$DIR/table" >/dev/null \
    || fail "profile run exited $?"
# the same contact sets (column 5) and the loads (column 3) to the solver tolerance
paste -d, "$DIR/cone/history.csv" "$DIR/table/history.csv" | awk -F, -v n="$(head -1 "$DIR/cone/history.csv" | awk -F, '{print NF}')" '
    NR > 1 { if ($5 != $(n + 5)) exit 1; d = $3 / $(n + 3) - 1; if (d > 1e-7 || d < -1e-7) exit 1 }' \
    || fail "a sampled cone differs from the cone: $(cut -d, -f3,5 "$DIR/cone/history.csv" "$DIR/table/history.csv" | tr '\n' ' ')"
grep -q '"kind": "profile"' "$DIR/table/run.json" || fail "run.json: kind"
grep -q "\"profile\": \"$DIR/cone.csv\"" "$DIR/table/run.json" || fail "run.json lacks the profile's path"
! grep -q '"alpha_degrees"' "$DIR/table/run.json" || fail "run.json gives a profile punch an angle"

# The cone sampled on the surface's grid (81 x 81, centre patch on the axis): a 2-D profile.
python3 - "$DIR/cone2d.npy" <<'PY'
import math, struct, sys
header = "{'descr': '<f8', 'fortran_order': False, 'shape': (81, 81), }"
header += " " * (63 - (10 + len(header)) % 64) + "\n"  # npy 1.0: the data starts on a 64-byte boundary
values = [math.hypot(ix - 40.0, iy - 40.0) / math.tan(math.radians(80)) for iy in range(81) for ix in range(81)]
with open(sys.argv[1], "wb") as f:
    f.write(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode("latin1"))
    f.write(struct.pack("<%dd" % len(values), *values))
PY
"$BIN" indent "$DIR/s.npy" --approach 0.5,1.5 --tol 1e-8 --punch profile --profile "$DIR/cone2d.npy" --out "$DIR/field" >/dev/null \
    || fail "2-D profile run exited $?"
paste -d, "$DIR/cone/history.csv" "$DIR/field/history.csv" | awk -F, -v n="$(head -1 "$DIR/cone/history.csv" | awk -F, '{print NF}')" '
    NR > 1 { if ($5 != $(n + 5)) exit 1; d = $3 / $(n + 3) - 1; if (d > 1e-8 || d < -1e-8) exit 1;
             if ($(n + 4) != "nan" || $(n + 6) != "nan") exit 1 }' \
    || fail "a 2-D cone differs from the cone (or has load_star/area_ratio): $(cut -d, -f3-6 "$DIR/field/history.csv" | tr '\n' ' ')"
grep -q '"kind": "profile-2d"' "$DIR/field/run.json" || fail "run.json: kind profile-2d"

# Refusals: usage, then bad files (exit 2: invalid input) naming the file and its line; no output folder.
"$BIN" indent "$DIR/s.npy" --approach 1 --punch profile --out "$DIR/x" >/dev/null 2>&1
[ $? -eq 2 ] || fail "--punch profile without --profile not refused with exit 2"
"$BIN" indent "$DIR/s.npy" --approach 1 --profile "$DIR/cone.csv" --out "$DIR/x" >/dev/null 2>&1
[ $? -eq 2 ] || fail "--profile without --punch profile not refused with exit 2"
printf 'r z\n0 0\n1 0.5\n2 0.4\n3 1\n' > "$DIR/down.txt"
message=$("$BIN" indent "$DIR/s.npy" --approach 1 --punch profile --profile "$DIR/down.txt" --out "$DIR/x" 2>&1 >/dev/null)
[ $? -eq 2 ] || fail "a decreasing profile: exit status (expected 2, invalid input)"
echo "$message" | grep -q "down.txt:4.*sample 2.*non-decreasing" || fail "a decreasing profile: message '$message'"
printf '0 0\n1 0.5\n2 x\n' > "$DIR/word.txt"
message=$("$BIN" indent "$DIR/s.npy" --approach 1 --punch profile --profile "$DIR/word.txt" --out "$DIR/x" 2>&1 >/dev/null)
echo "$message" | grep -q "word.txt:3" || fail "a bad line: message '$message'"
# a file with no sample (empty, or comments only) was refused with the library's "r is NULL: expected a pointer"
printf '# r z\n' > "$DIR/comments.txt"
message=$("$BIN" indent "$DIR/s.npy" --approach 1 --punch profile --profile "$DIR/comments.txt" --out "$DIR/x" 2>&1 >/dev/null)
[ $? -eq 2 ] || fail "a profile without samples: exit status (expected 2, invalid input)"
echo "$message" | grep -q "comments.txt: no profile sample: expected at least 3 lines 'r z' or 'r,z'" \
    || fail "a profile without samples: message '$message'"
message=$("$BIN" indent "$DIR/s.npy" --approach 1 --punch profile --profile "$DIR/none.txt" --out "$DIR/x" 2>&1 >/dev/null)
echo "$message" | grep -q "none.txt" || fail "a missing file: message '$message'"
[ ! -e "$DIR/x" ] || fail "a refused run made its output folder"

# A scene: [punch] shape = profile with profile = FILE relative to the scene's folder (run from
# elsewhere); the history equals the cone's; --resume reads it back, and solves again once the
# profile file changes (the samples are in the result's key).
mkdir -p "$DIR/scenes"
cp "$DIR/cone.csv" "$DIR/scenes/tip.csv"
write_scene() { # NAME SHAPE-LINES
    printf '[scene]\nname = %s\noutput = %s\n\n[surfaces]\nn = 64\nlambda_r = 64\nslopes = 0.05\nseeds = 1\n\n' \
        "$1" "$DIR/$1" > "$DIR/scenes/$1.ini"
    printf '[punch]\n%b\n\n[loading]\nsteps = 0.5, 1.5\n\n[output]\nplots = fig5\n' "$2" >> "$DIR/scenes/$1.ini"
}
write_scene tipped 'shape = profile\nprofile = tip.csv'
write_scene conical 'shape = cone'
(cd "$DIR" && "$BIN" run --quiet scenes/tipped.ini >/dev/null && "$BIN" run --quiet scenes/conical.ini >/dev/null) || fail "scenes exited $?"
paste -d, <(grep -v '^#' "$DIR/tipped/histories/member_00_1.csv") <(grep -v '^#' "$DIR/conical/histories/member_00_1.csv") |
    awk -F, -v n="$(head -1 "$DIR/cone/history.csv" | awk -F, '{print NF}')" '
        NR > 1 { if ($5 != $(n + 5)) exit 1; d = $3 / $(n + 3) - 1; if (d > 1e-7 || d < -1e-7) exit 1 }' \
    || fail "the scene's profile history differs from the cone's"
(cd "$DIR" && "$BIN" run --resume scenes/tipped.ini 2>"$DIR/kept.log" >/dev/null) || fail "--resume exited $?"
grep -q "0 solved, 1 read back" "$DIR/kept.log" || fail "--resume did not read the history back: $(cat "$DIR/kept.log")"
echo "80,14.1" >> "$DIR/scenes/tip.csv"
(cd "$DIR" && "$BIN" run --resume scenes/tipped.ini 2>"$DIR/changed.log" >/dev/null) || fail "--resume exited $?"
grep -q "made from other inputs" "$DIR/changed.log" && grep -q "1 solved, 0 read back" "$DIR/changed.log" \
    || fail "--resume kept a history of the old profile: $(cat "$DIR/changed.log")"
# The scene's run.json names the profile file (resolved against the scene's folder, as the run
# read it: here relative to the working directory, as the scene's path) and its kind.
grep -q '"kind": "profile"' "$DIR/tipped/run.json" && grep -q '"profile": "scenes/tip.csv"' "$DIR/tipped/run.json" \
    || fail "the scene's run.json does not record the profile: $(cat "$DIR/tipped/run.json")"

# A 2-D profile in a scene: displacement control solves it (load_star and area_ratio NaN) and
# --resume reads that history back; load control (steps are N*, which needs the smooth-contact
# area) and distributions (at load_star) are refused naming the key, nothing solved.
cp "$DIR/cone2d.npy" "$DIR/scenes/cone2d.npy"
write_scene field 'shape = profile\nprofile = cone2d.npy'
"$BIN" run --quiet "$DIR/scenes/field.ini" >/dev/null || fail "a 2-D profile scene exited $?"
"$BIN" run --resume "$DIR/scenes/field.ini" 2>"$DIR/field.log" >/dev/null || fail "2-D --resume exited $?"
grep -q "0 solved, 1 read back" "$DIR/field.log" || fail "--resume did not read a 2-D history back: $(cat "$DIR/field.log")"
sed 's/^\[loading\]$/[loading]\ncontrol = load\nload_star = 1.5/' "$DIR/scenes/field.ini" > "$DIR/scenes/loaded.ini"
sed -i "s|^output = .*|output = $DIR/loaded|" "$DIR/scenes/loaded.ini"
message=$("$BIN" run --quiet "$DIR/scenes/loaded.ini" 2>&1 >/dev/null)
[ $? -eq 2 ] && echo "$message" | grep -q "\[loading\] control = load.*2-D profile" \
    || fail "load control with a 2-D profile: '$message'"
[ ! -e "$DIR/loaded/histories" ] || fail "load control with a 2-D profile solved histories"
sed 's/^plots = fig5$/plots = fig5\ndistributions = yes/' "$DIR/scenes/field.ini" > "$DIR/scenes/spread.ini"
sed -i -e "s|^output = .*|output = $DIR/spread|" -e 's/^\[loading\]$/[loading]\nload_star = 1.5/' "$DIR/scenes/spread.ini"
message=$("$BIN" run --quiet "$DIR/scenes/spread.ini" 2>&1 >/dev/null)
[ $? -eq 2 ] && echo "$message" | grep -q "\[output\] distributions.*2-D profile" \
    || fail "distributions with a 2-D profile: '$message'"

# A profile path too long once resolved against the scene's folder (a scene path of 4000 bytes
# and more, within PATH_MAX): refused naming the key, not cut short.
write_scene overlong "shape = profile\nprofile = $(printf 'd/%.0s' $(seq 50))tip.csv"
long_scene="$DIR/scenes/$(printf './%.0s' $(seq 2000))overlong.ini"
message=$("$BIN" run --quiet "$long_scene" 2>&1 >/dev/null)
[ $? -eq 2 ] && echo "$message" | grep -q "^indentmap: \[punch\] profile: 'd/d/.*tip.csv' is .* bytes.*longer than 4095" || fail "an overlong profile path: '$message'"

write_scene lonely 'shape = profile'
message=$("$BIN" run --quiet "$DIR/scenes/lonely.ini" 2>&1 >/dev/null)
echo "$message" | grep -q "shape = profile and profile = FILE go together" || fail "a profile scene without a file: '$message'"
exit 0
