#!/usr/bin/env bash
# indent --adhesion-zone (issue 27; docs/solver.md, "Across Tabor's mu"): the Maugis-Dugdale sphere at Tabor's
# mu = 10 on L = 8 patches per reduced radius (R = 8 L, tests/test_adhesion.c's sphere; its Dugdale zone 0.022
# patches), retracted to D = -0.5 L^2 / R, pulls off within 0.1 pi w R of Maugis-Dugdale with the zone widened to
# a patch (test_adhesion --mu 10 --L 8 --zone 1: 0.075) and over 1 pi w R off without (1.37: the edge sticks);
# run.json states the law solved and the law asked. A zone that already spans P patches changes no bit of the
# history; P <= 0, P without adhesion and P with the exponential law are refused naming the option.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export IM_FFTW_WISDOM=
source "$(dirname "$0")/lib.sh"

# w and delta_c of Tabor's mu = 10 (lambda = 1.157 mu) on a sphere of radius R = 8 L, L = 8: sphere_case_make's
read -r work range < <(/usr/bin/python3 -c '
import math
k, L, lam = 4 / 3, 8, 10 * 1.157
R = 8 * L
w = k * L ** 3 / (math.pi * R * R)
stress = lam / 2 * (math.pi * w * k * k / R) ** (1 / 3)
print(repr(w), repr(w / stress))')
sphere=(--smooth --n 64 --punch sphere --radius 64 --adhesion-work "$work" --adhesion-range "$range" --tol 1e-8
  --approach 0.25:1.5:6,1.4:-0.5:20)

# pull_off_error RUN WIDENED WORK RADIUS: |most tensile load - Maugis-Dugdale's pull-off| / (pi w R), from run.json's "adhesion"
# block (its theory is the law asked's), after checking what the block says of the zone: WIDENED 1 (the law solved
# spans one patch at the same work, Tabor's mu below the asked 10), 0 (the law as asked), none (no "zone").
pull_off_error() {
  /usr/bin/python3 - "$@" <<'PY'
import json, math, sys
law = json.load(open(sys.argv[1] + "/run.json"))["adhesion"]
widened, work, radius = sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
zone = law.get("zone")
assert law["work"] == work, law
if widened == "none":
    assert zone is None, zone
else:
    asked = zone["asked"]
    assert zone["widened"] == (widened == "1") and asked["work"] == work, zone
    if widened == "1":
        assert abs(law["zone_length_patches"] - 1) < 1e-12 and law["range"] > asked["range"], law
        assert abs(asked["tabor_mu"] - 10) < 1e-9 and law["tabor_mu"] < 2, law
    else:
        assert all(law[key] == asked[key] for key in asked), law
print(abs(law["most_tensile_load"] - law["theory"]["pull_off_force"]) / (math.pi * work * radius))
PY
}

"$cli" indent "${sphere[@]}" --adhesion-zone 1 --out "$dir/widened" >"$dir/widened.out" || exit 1
"$cli" indent "${sphere[@]}" --out "$dir/plain" >"$dir/plain.out" || exit 1
widened=$(pull_off_error "$dir/widened" 1 "$work" 64)
plain=$(pull_off_error "$dir/plain" none "$work" 64)
echo "mu = 10, L = 8: pull-off error ${widened:-?} pi w R widened to a patch, ${plain:-?} as asked"
check "widened zone: pull-off within 0.1 pi w R" awk -v e="$widened" 'BEGIN { exit !(e != "" && e < 0.1) }'
check "the law as asked sticks: over 1 pi w R" awk -v e="$plain" 'BEGIN { exit !(e != "" && e > 1) }'
check "stdout states the law solved" grep -q "adhesion zone widened from 0.02.* to 1 patches at the same work: range.*Tabor mu 1\..* (asked 10)" "$dir/widened.out"
check "no unresolved-zone warning once widened" bash -c "! grep -q 'below one patch' '$dir/widened.out'"

# A zone already wider than P patches (l = pi 0.36 / 0.4 = 2.8 patches): the same history, to the bit.
small=(--smooth --n 32 --punch sphere --radius 20 --adhesion-work 0.05 --adhesion-range 0.6 --approach 0.5,1,-0.2)
"$cli" indent "${small[@]}" --out "$dir/as-given" >/dev/null &&
  "$cli" indent "${small[@]}" --adhesion-zone 2 --out "$dir/spanned" >"$dir/spanned.out"
check "a zone already spanning P: the same history" diff <(history_rows "$dir/as-given/history.csv") \
  <(history_rows "$dir/spanned/history.csv")
check "a zone already spanning P: said so" grep -q "already spans --adhesion-zone 2: the law as given" "$dir/spanned.out"
check "a zone already spanning P: run.json says not widened" pull_off_error "$dir/spanned" 0 0.05 20

# Nonsense, refused naming the option
check "P = 0 refused" expect_exit 2 "--adhesion-zone = 0: expected" "$cli" indent "${small[@]}" --adhesion-zone 0 --out "$dir/x"
check "P < 0 refused" expect_exit 2 "--adhesion-zone = -1: expected" "$cli" indent "${small[@]}" --adhesion-zone -1 --out "$dir/x"
check "P without adhesion refused" expect_exit 2 "--adhesion-zone widens the zone of --adhesion-work" \
  "$cli" indent --smooth --n 32 --punch sphere --radius 20 --approach 0.5 --adhesion-zone 1 --out "$dir/x"
check "P with the exponential law refused" expect_exit 2 "--adhesion-zone widens the Maugis-Dugdale law's zone" \
  "$cli" indent "${small[@]}" --adhesion-law exponential --adhesion-zone 1 --out "$dir/x"
finish
