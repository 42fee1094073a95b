#!/usr/bin/env bash
# A scene's [adhesion] (issue 27): a smooth sphere at Maugis's lambda = 1 (R = 64, w = 0.05305,
# delta_c = 0.6366, the reduced radius 8 patches, as cli_indent's) approached from w = -1 and pulled back to
# -1.5: its history pulls, its least load is within 3% of Maugis-Dugdale's 1.6007 pi w R = 17.07
# (theory.h, im_theory_md_sphere_pull_off; test_theory_adhesion), and it equals `indent`'s of the same
# settings. --resume reads it back; another work of adhesion, or none, is solved again (the key). law =
# exponential is solved with that law, which is part of the key. The refusals name the key and what is expected.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"

scene() { # scene FILE ADHESION-LINES [OUTPUT-LINES [STEPS [FOLDER]]]
    printf '[scene]\nname = sticky\noutput = %s/%s\n[surfaces]\nn = 96\nslopes = 0\nseeds = 1\n[punch]\nshape = sphere\nradius = 64\n%s\n[loading]\ncontrol = displacement\nsteps = %s\n[output]\n%s\n' \
        "$dir" "${5:-res}" "$2" "${4:--1:2:16, 1.9:-1.5:35}" "${3:-plots = fig5, fig6}" > "$1"
}
sticky='[adhesion]
work = 0.05305
range = 0.6366
law = maugis-dugdale'
scene "$dir/sticky.ini" "$sticky" ""
check "the adhesive scene runs" "$cli" run "$dir/sticky.ini" 2> "$dir/run.err" > /dev/null
history=$dir/res/histories/member_00_1.csv
pull_off() { python3 - "$1" <<'PY'
import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
print(-min(float(r["load"]) for r in rows))
PY
}
check "the history pulls, its pull-off within 3% of Maugis-Dugdale's 17.07" \
    python3 -c "import sys; p = float(sys.argv[1]); sys.exit(not abs(p / 17.07 - 1) < 0.03)" "$(pull_off "$history")"
"$cli" indent --smooth --n 96 --punch sphere --radius 64 --adhesion-work 0.05305 --adhesion-range 0.6366 \
    --approach -1:2:16,1.9:-1.5:35 --out "$dir/indent" > /dev/null 2>&1
check "the scene's history is indent's" python3 - "$history" "$dir/indent/history.csv" <<'PY'
import csv, sys
def loads(path):
    return [float(r["load"]) for r in csv.DictReader(l for l in open(path) if not l.startswith("#"))]
a, b = loads(sys.argv[1]), loads(sys.argv[2])
sys.exit(not (len(a) == len(b) == 51 and max(abs(x - y) for x, y in zip(a, b)) <= 1e-9 * max(map(abs, b))))
PY
check "run.json states the law" python3 -c "import json, sys; a = json.load(open(sys.argv[1]))['adhesion']; \
sys.exit(not (a['law'] == 'Maugis-Dugdale' and a['work'] == 0.05305 and a['range'] == 0.6366))" "$dir/res/run.json"
check "--resume reads the adhesive history back" expect_exit 0 "0 solved, 1 read back" "$cli" run --resume "$dir/sticky.ini"
scene "$dir/stronger.ini" "${sticky/0.05305/0.06}" ""
check "another work is solved again" expect_exit 0 "made from other inputs" "$cli" run --resume "$dir/stronger.ini"
scene "$dir/plain.ini" "" "" "0.1:2:16" plain
"$cli" run "$dir/plain.ini" > /dev/null 2>&1
scene "$dir/pulling.ini" "$sticky" "" "0.1:2:16" plain
check "adhesion is not reused from a plain scene" expect_exit 0 "made from other inputs" \
    "$cli" run --resume "$dir/pulling.ini"
# law = exponential: solved with it (run.json names it, as `indent --adhesion-law exponential`'s history), and
# part of the key: the Maugis-Dugdale law of the same work and range is solved again.
exponential='[adhesion]
work = 0.05305
range = 0.2
law = exponential'
scene "$dir/exp.ini" "$exponential" "" "-0.5:1:4, 0.5:-0.5:3" exp
check "the exponential scene runs" "$cli" run "$dir/exp.ini" 2> "$dir/exp.err" > /dev/null
check "run.json states the exponential law" python3 -c "import json, sys; a = json.load(open(sys.argv[1]))['adhesion']; \
sys.exit(not (a['law'] == 'exponential' and a['range'] == 0.2))" "$dir/exp/run.json"
"$cli" indent --smooth --n 96 --punch sphere --radius 64 --adhesion-work 0.05305 --adhesion-range 0.2 \
    --adhesion-law exponential --approach -0.5:1:4,0.5:-0.5:3 --out "$dir/expindent" > /dev/null 2>&1
check "the exponential scene's history is indent's" python3 - "$dir/exp/histories/member_00_1.csv" \
    "$dir/expindent/history.csv" <<'PY'
import csv, sys
def loads(path):
    return [float(r["load"]) for r in csv.DictReader(l for l in open(path) if not l.startswith("#"))]
a, b = loads(sys.argv[1]), loads(sys.argv[2])
sys.exit(not (len(a) == len(b) == 7 and min(b) < 0 and max(abs(x - y) for x, y in zip(a, b)) <= 1e-9 * max(map(abs, b))))
PY
scene "$dir/expmd.ini" "${exponential/exponential/maugis-dugdale}" "" "-0.5:1:4, 0.5:-0.5:3" exp
check "another law is solved again" expect_exit 0 "made from other inputs" "$cli" run --resume "$dir/expmd.ini"

# zone = 4 (indent --adhesion-zone 4): l = 3.0 patches widened to 4, the same history as indent's, not the law's as given
scene "$dir/zone.ini" "$sticky"$'\nzone = 4' "" "0.5, 1, -0.5" zone
check "a scene with zone runs" "$cli" run "$dir/zone.ini" > /dev/null 2> "$dir/zone.err"
for zone in 4 none; do
  "$cli" indent --smooth --n 96 --punch sphere --radius 64 --adhesion-work 0.05305 --adhesion-range 0.6366 \
      $([ $zone = none ] || echo --adhesion-zone $zone) --approach 0.5,1,-0.5 --out "$dir/indent-$zone" > /dev/null 2>&1
done
check "the zone's history is indent --adhesion-zone's, not the law's as given" python3 - \
    "$dir/zone/histories/member_00_1.csv" "$dir/indent-4/history.csv" "$dir/indent-none/history.csv" <<'PY'
import csv, sys
def loads(path):
    return [float(r["load"]) for r in csv.DictReader(l for l in open(path) if not l.startswith("#"))]
a, b, given = (loads(path) for path in sys.argv[1:])
sys.exit(not (len(a) == len(b) == len(given) == 3 and max(abs(x - y) for x, y in zip(a, b)) <= 1e-9 * max(map(abs, b))
              and a != given))
PY
check "run.json states the zone" python3 -c "import json, sys; sys.exit(json.load(open(sys.argv[1]))['adhesion']['zone'] != 4)" \
    "$dir/zone/run.json"

# The refusals, each naming the key at fault and what is expected.
refuse() { # NAME ADHESION-LINES EXTRA-LINES PHRASE
    scene "$dir/bad.ini" "$2" "$3"
    check "$1" expect_exit 2 "$4" "$cli" run "$dir/bad.ini"
}
refuse "another law" "${sticky/maugis-dugdale/lennard-jones}" "" "law = 'lennard-jones': expected maugis-dugdale (a constant stress w / range up to the gap range) or exponential"
refuse "work without range" '[adhesion]
work = 0.1' "" "[adhesion] work and range go together"
refuse "range without work" '[adhesion]
range = 0.1' "" "[adhesion] work and range go together"
refuse "a negative work" '[adhesion]
work = -1
range = 1' "" "work = '-1': expected a number in"
refuse "a zone of 0 patches" "$sticky"$'\nzone = 0' "" "zone = '0': expected a number in"
refuse "a zone without work and range" $'[adhesion]\nzone = 1' "" "[adhesion] zone widens the zone of the law's work and range"
refuse "a zone of the exponential law" "${sticky/maugis-dugdale/exponential}"$'\nzone = 1' "" \
    "[adhesion] zone widens the Maugis-Dugdale law's zone: expected law = maugis-dugdale"
refuse "panels under load control" "$sticky" "contact_panels = yes" "contact_panels, frames, table or distributions"
refuse "periodic flat panels" "$sticky" "plots = flat_k" "plots = flat_k: its flat panels are solved at mean pressures, which an adhesive cell does not take"
refuse "log-axis figures" "$sticky" "plots = fig7" "plots = fig7 or sphere"
scene "$dir/bad.ini" "" ""
check "negative steps without adhesion (indent's message)" expect_exit 2 "'-1:2:16' is not a range first:last:count (three numbers >= 0)" \
    "$cli" run "$dir/bad.ini"

# With [material] hardness (yielding below the sphere's elastic peak pressure): indent --hardness's history,
# the plastic depth kept on the way back. A scene solves a member on one thread, and so does indent here: the
# capped solves' sums depend on the thread count (to the solve's tolerance).
scene "$dir/hard.ini" "$sticky"$'\n[material]\nhardness = 0.06' "" "-1:2:7, 1.5:-1.5:7" hard
check "the adhesive scene with a hardness runs" "$cli" run "$dir/hard.ini" > /dev/null 2> "$dir/hard.err"
OMP_NUM_THREADS=1 "$cli" indent --smooth --n 96 --punch sphere --radius 64 --adhesion-work 0.05305 --adhesion-range 0.6366 \
    --hardness 0.06 --approach -1:2:7,1.5:-1.5:7 --out "$dir/hardindent" > /dev/null 2>&1
check "its history is indent --hardness --adhesion-work's, flattened and pulled" python3 - \
    "$dir/hard/histories/member_00_1.csv" "$dir/hardindent/history.csv" <<'PY'
import csv, sys
def rows(path):
    return [(float(r["approach"]), float(r["load"]), float(r["plastic_depth"]))
            for r in csv.DictReader(l for l in open(path) if not l.startswith("#"))]
a, b = rows(sys.argv[1]), rows(sys.argv[2])
close = all(abs(x - y) <= 1e-9 * max(abs(y), 1) for p, q in zip(a, b) for x, y in zip(p, q))
sys.exit(not (len(a) == len(b) == 14 and close and b[-1][2] > 0.5 and min(r[1] for r in b) < 0))
PY

# Load control: the steps are loads (indent --load's; a pulled contact has no N*), the history indent's. A
# load below the pull-off force under load control (the smooth sphere's -17.13, the rough one's -15.90) ends
# its member with the library's message and the step; the other members' histories are kept, as for a
# member whose contact reached the edge.
loads="0:40:5, 30:-15:4"
scene "$dir/load.ini" "$sticky" "" "$loads" load
sed -i 's/control = displacement/control = load/' "$dir/load.ini"
check "the load-controlled scene runs" "$cli" run "$dir/load.ini" > /dev/null 2> "$dir/load.err"
"$cli" indent --smooth --n 96 --punch sphere --radius 64 --adhesion-work 0.05305 --adhesion-range 0.6366 \
    --load "${loads// /}" --out "$dir/loadindent" > /dev/null 2>&1
check "the load-controlled scene's history is indent --load's, pulled below 0" python3 - \
    "$dir/load/histories/member_00_1.csv" "$dir/loadindent/history.csv" <<'PY'
import csv, sys
def rows(path):
    return [(float(r["approach"]), float(r["load"]))
            for r in csv.DictReader(l for l in open(path) if not l.startswith("#"))]
a, b = rows(sys.argv[1]), rows(sys.argv[2])
close = all(abs(x - y) <= 1e-9 * max(abs(y), 1) for p, q in zip(a, b) for x, y in zip(p, q))
sys.exit(not (len(a) == len(b) == 9 and close and abs(b[-1][1] + 15) < 1e-4))
PY
sed 's/slopes = 0$/slopes = 0, 0.05/; s/-15:4$/-15:4, -16.5/; s|/load$|/beyond|' "$dir/load.ini" > "$dir/beyond.ini"
check "a load beyond the pull-off ends its member with the library's message and the step" expect_exit 2 \
    "family 1, seed 1: step 10 of 10 (load -16.5): load -16.5: below the least load the contact held on retraction" \
    "$cli" run "$dir/beyond.ini"
check "the member that held every load is kept, the other is not written" python3 -c "import os, sys; \
sys.exit(not (os.path.exists(sys.argv[1] + '/member_00_1.csv') and not os.path.exists(sys.argv[1] + '/member_01_1.csv')))" \
    "$dir/beyond/histories"
finish
