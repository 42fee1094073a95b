#!/usr/bin/env bash
# `indentmap indent` and scenes are two front ends of one library (issue 14): a step list or a
# punch name refused by one is refused by the other with the same message (after the option or
# key's name), their histories have one column line, and their run records one set of common
# fields and one default tolerance. (The parsers and the reader themselves: tests/test_front.c.)
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
. "$(dirname "$0")/lib.sh"

"$cli" surface --n 32 --slope 0.08 --seed 1 --out "$dir/s.npy" >/dev/null
scene() { # $1: [punch] and [loading] lines
  printf '[scene]\nname = f\noutput = sout\n[surfaces]\nn = 32\nslopes = 0.08\nseeds = 1\n%b[output]\nplots = fig5\n' "$1" >"$dir/f.ini"
}
# indent's message after "indentmap: OPTION " and the scene's after "f.ini:LINE: KEY = " or "KEY "
indent_says() { "$cli" indent "$dir/s.npy" "$1" "$2" --out "$dir/o" 2>&1 >/dev/null | head -1 | sed "s/^indentmap: $1 //"; }
scene_says() { "$cli" run --quiet "$dir/f.ini" 2>&1 >/dev/null | head -1 | sed "s/^indentmap: .*f\.ini:[0-9]*: $1//"; }

for steps in 1:2:5000 1:2 1,,2 1,abc -1,2 1:2:0; do
  scene "[loading]\nsteps = $steps\n"
  a=$(indent_says --approach "$steps") b=$(scene_says "steps ")
  check "steps '$steps': one message ($a | $b)" test -n "$a" -a "$a" = "$b"
done
# The limit, 4096 steps, passes the parser of both: each then refuses the run for what it is
# (indent: a punch axis off the surface; a scene: steps whose contact leaves the surface).
check "indent: 4096 steps parsed" expect_exit 2 "the punch's axis lies outside" \
  "$cli" indent "$dir/s.npy" --approach 0:1:4096 --x 1e9 --y 1e9 --out "$dir/o"
scene "[loading]\nsteps = 0:1e6:4096\n"
check "scene: 4096 steps parsed" bash -c "\"$cli\" run --quiet \"$dir/f.ini\" 2>&1 | grep -v 'count' | grep -q 'f.ini'"

scene "[punch]\nshape = pyramid\n"
a=$(indent_says --punch pyramid) b=$(scene_says "shape = ")
check "punch 'pyramid': one message ($a | $b)" test -n "$a" -a "$a" = "$b"

# One history schema: the column line of indent's history.csv is the scene's (after its "# ..." line).
scene "[loading]\nsteps = 0.5:2:3\n"
"$cli" run --quiet "$dir/f.ini" >/dev/null 2>&1
check "scene runs" test -s "$dir/sout/histories/member_00_1.csv"
"$cli" indent "$dir/s.npy" --approach 0.5:2:3 --out "$dir/indent" >/dev/null 2>&1
check "one column line" test "$(head -1 "$dir/indent/history.csv")" = "$(sed -n 2p "$dir/sout/histories/member_00_1.csv")"
# the same surface (seed 1) solved by both: the same solution columns, step to area_ratio (n_p
# exactly, the rest to rounding: the scene solves on one thread, indent on all)
same_solution() { awk -F, 'NR == FNR { for (c = 1; c <= 6; ++c) v[FNR, c] = $c; next }
  { for (c = 1; c <= 6; ++c) { d = $c - v[FNR, c]; if (d < 0) d = -d
      if ((c == 1 || c == 5) ? d != 0 : d > 1e-12 * ($c < 0 ? -$c : $c)) bad = 1 } }
  END { exit bad || FNR != 4 }' "$1" <(tail -n +2 "$2"); }
check "the same solution on the same surface" same_solution "$dir/indent/history.csv" "$dir/sout/histories/member_00_1.csv"

json_quality() { python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["solver"]["quality"])' "$1"; }
# One run record: the same common fields and one default tolerance.
common() { python3 -c 'import json, sys
r = json.load(open(sys.argv[1]))
print(sorted(k for k in ("program", "version", "input", "solver") if k in r), sorted(r["solver"]), r["solver"]["quality"],
      r["solver"]["tol"], r["solver"]["tol_from"], r["input"]["kind"])' "$1" | sed 's/indentmap run\|scene\|surface//g'; }
check "run.json: one set of common fields, one default" test "$(common "$dir/indent/run.json" | sed 's/, .fftw_measure.\|, .plan_seconds.//g')" = \
  "$(common "$dir/sout/run.json")"
check "run.json: the default is the standard preset" test "$(json_quality "$dir/indent/run.json")" = standard -a \
  "$(json_quality "$dir/sout/run.json")" = standard
finish
