#!/bin/bash
# indentmap indent: outputs, exit codes, and that the steps solved before a failure are kept.
set -u
BIN="$1"
DIR=$(mktemp -d)
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# A smooth cone: history columns, one row per step, run.json, fields; N* = n_p within 1% (Love).
"$BIN" indent --smooth --n 96 --approach 1:6:3 --out "$DIR/ok" --fields >/dev/null || fail "smooth run exited $?"
head -1 "$DIR/ok/history.csv" | grep -q '^step,approach,load,load_star,contact_patches,area_ratio,mean_pressure,max_pressure,iterations,residual,seconds' \
    || fail "history.csv header: $(head -1 "$DIR/ok/history.csv")"
[ "$(wc -l < "$DIR/ok/history.csv")" -eq 4 ] || fail "expected 3 rows"
awk -F, 'NR == 4 { d = $4 / $5 - 1; if (d < -0.01 || d > 0.01) exit 1 }' "$DIR/ok/history.csv" || fail "N* != n_p at the last step"
for key in '"version"' '"window"' '"threads"' '"tol"' '"steps_completed": 3' '"source": "smooth"'; do
    grep -q "$key" "$DIR/ok/run.json" || fail "run.json lacks $key"
done
for f in force gap displacement; do [ -s "$DIR/ok/${f}_0003.npy" ] || fail "missing ${f}_0003.npy"; done

# Contact reaching the surface's edge at step 3: exit 1, steps 1-2 kept.
"$BIN" indent --smooth --n 48 --approach 2,4,8 --out "$DIR/edge" >/dev/null 2>"$DIR/edge.err"
[ $? -eq 1 ] || fail "edge contact should exit 1"
grep -q edge "$DIR/edge.err" || fail "edge message: $(cat "$DIR/edge.err")"
[ "$(wc -l < "$DIR/edge/history.csv")" -eq 3 ] || fail "edge: the two solved steps should be kept"
grep -q '"steps_completed": 2' "$DIR/edge/run.json" || fail "edge: run.json steps_completed"

# No convergence within the cap: exit 1, the converged first step kept.
"$BIN" indent --smooth --n 64 --approach 0,2 --max-iter 2 --out "$DIR/cap" >/dev/null 2>"$DIR/cap.err"
[ $? -eq 1 ] || fail "no convergence should exit 1"
grep -q cap "$DIR/cap.err" || fail "cap message: $(cat "$DIR/cap.err")"
[ "$(wc -l < "$DIR/cap/history.csv")" -eq 2 ] || fail "cap: the converged step should be kept"

# Bad input: exit 2 with a message naming the problem.
"$BIN" indent --smooth --n 64 --alpha 90 --approach 1 --out "$DIR/bad" 2>"$DIR/bad.err"
[ $? -eq 2 ] && grep -q alpha "$DIR/bad.err" || fail "alpha = 90 should exit 2 naming alpha"
printf '0 0 0\n0 nan 0\n0 0 0\n' > "$DIR/nan.txt"
"$BIN" indent "$DIR/nan.txt" --approach 0.1 --out "$DIR/nan" 2>/dev/null
[ $? -eq 2 ] || fail "a NaN height should exit 2"
"$BIN" indent --smooth --n 64 --out "$DIR/none" 2>/dev/null
[ $? -eq 2 ] || fail "missing --approach/--load should exit 2"
echo ok
