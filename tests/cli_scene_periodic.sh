#!/usr/bin/env bash
# A scene's [punch] periodic (issue 26): a generated 64 x 64 cell under a rigid flat at six mean pressures,
# read as a scene's surface file and by `indent --periodic --pressure`: the scene's history is indent's and
# its k_fit.csv row is indent's run.json "k_fit", both exactly (one thread each, the same helpers); --resume
# reads the history back and draws the same k; a sphere repeated with the cell under a hardness, loaded and
# unloaded, is indent's too; so are mean gaps (control = mean_gap) and an adhesive cell's mean pressures. A ramp (not periodic) is warned about; what needs a half-space is refused,
# naming the key. Then an indentation/member_FF_SEED.csv per member of a hardness history that goes up and
# down, equal to indent's indentation.csv, and the example scene scenes/periodic.ini.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
export OMP_NUM_THREADS=1 # a scene solves each member on one thread: so does indent here, for equal bits

"$cli" surface --n 64 --slope 0.08 --seed 3 --out "$dir/cell.npy" > /dev/null
scene() { # scene FILE SURFACE PUNCH-LINES LOADING-LINES [OTHER-LINES [OUTPUT]]
    printf '[scene]\nname = cell\noutput = %s\n[surfaces]\nfile = %s\n[punch]\nperiodic = yes\n%s\n[loading]\n%s\n%s\n' \
        "${6:-res}" "$2" "$3" "$4" "${5:-}" > "$1"
}
rows() { tail -n +2 "$1" | cut -d, -f1-10,12-; } # a history's rows but the solve times
scene "$dir/flat.ini" cell.npy "" "steps = 0.002:0.03:6"
check "the periodic scene runs" "$cli" run "$dir/flat.ini" 2> "$dir/run.err" > /dev/null
check "a periodic surface is not warned about" [ -z "$(grep -i warn "$dir/run.err")" ]
"$cli" indent "$dir/cell.npy" --periodic --pressure 0.002:0.03:6 --out "$dir/indent" > /dev/null
check "the scene's history is indent --periodic's" \
    cmp <(rows "$dir/res/histories/member_00_0.csv" | tail -n +2) <(rows "$dir/indent/history.csv")
k_fit_matches() { python3 - "$1" "$2" <<'PY'
import csv, json, math, sys
row = next(csv.DictReader(open(sys.argv[1])))
fit = json.load(open(sys.argv[2]))["k_fit"]
pairs = [(row["k"], fit["k"]), (row["k_error"], fit["k_error"]), (row["rms_residual"], fit["rms_residual"]),
         (row["k_linear"], fit["k_linear"]), (row["slope_rms"], fit["slope_rms"]),
         (row["points"], fit["points"]), (row["linear_points"], fit["linear_points"]),
         (row["pressure_ratio_min"], fit["pressure_ratio_range"][0]),
         (row["pressure_ratio_max"], fit["pressure_ratio_range"][1]),
         (row["area_fraction_min"], fit["area_fraction_range"][0]),
         (row["area_fraction_max"], fit["area_fraction_range"][1])]
sys.exit(not all(float(a) == float(b) for a, b in pairs) or not 1.5 < fit["k"] < 2.5)
PY
}
check "k_fit.csv is indent's k fit" k_fit_matches "$dir/res/k_fit.csv" "$dir/indent/run.json"
check "run.json states the periodic mode" python3 -c "import json, sys; p = json.load(open(sys.argv[1]))['periodic']; \
sys.exit(not (p['punch'] == 'rigid flat on the whole cell' and p['k_fit'] == 'k_fit.csv'))" "$dir/res/run.json"
cp "$dir/res/k_fit.csv" "$dir/k_fit.csv"
check "--resume reads the periodic history back" expect_exit 0 "0 solved, 1 read back" "$cli" run --resume "$dir/flat.ini"
check "and draws the same k" cmp "$dir/k_fit.csv" "$dir/res/k_fit.csv"
# With its contact maps too: the k fit reads the history the maps take over (it crashed, issue 28).
scene "$dir/flat_maps.ini" cell.npy "" "steps = 0.002:0.03:6" $'[output]\ncontact_panels = yes' flat_maps
check "the rigid flat with contact maps runs" "$cli" run --no-wisdom "$dir/flat_maps.ini" > /dev/null 2>&1
check "its k_fit.csv is the one without maps" cmp "$dir/k_fit.csv" "$dir/flat_maps/k_fit.csv"
check "and its maps are drawn" [ -s "$dir/flat_maps/panels/family_00/contact_0005.png" ]
scene "$dir/more.ini" cell.npy "" "steps = 0.002:0.03:7"
check "other pressures are solved again" expect_exit 0 "made from other inputs" "$cli" run --resume "$dir/more.ini"

# Mean gaps (control = mean_gap): indent --periodic --mean-gap's history, with a hardness, falling and rising.
scene "$dir/gap.ini" cell.npy "" $'control = mean_gap\nsteps = 0.4:0.2:3, 0.3' $'[material]\nhardness = 0.05' gap
check "a mean-gap scene runs" "$cli" run "$dir/gap.ini" > /dev/null 2>&1
"$cli" indent "$dir/cell.npy" --periodic --hardness 0.05 --mean-gap 0.4:0.2:3,0.3 --out "$dir/indent_gap" > /dev/null
check "its history is indent --mean-gap's" \
    cmp <(rows "$dir/gap/histories/member_00_0.csv" | tail -n +2) <(rows "$dir/indent_gap/history.csv")
check "the mean gaps are the steps" awk -F, '/^#/ || /^step/ { next } { split("0.4 0.3 0.2 0.3", g, " "); d = $28 / g[++k] - 1
    if (d > 1e-6 || -d > 1e-6) bad = 1 } END { exit bad || k != 4 }' "$dir/gap/histories/member_00_0.csv"

# An adhesive cell (issue 27) under mean gaps falling and rising: indent --periodic --mean-gap --adhesion-work's
# history, pulling where the cell is out of contact; each step's contact map drawn (tension on its own colour
# bar); no k (eq. (2) is the repulsive flat's).
sticky=$'[adhesion]\nwork = 0.001\nrange = 0.5'
scene "$dir/sticky.ini" cell.npy "" $'control = mean_gap\nsteps = 1.5, 1, 0.5, 1, 1.5' \
    "$sticky"$'\n[output]\ncontact_panels = yes' sticky
check "an adhesive cell's scene runs" "$cli" run "$dir/sticky.ini" > /dev/null 2>&1
"$cli" indent "$dir/cell.npy" --periodic --mean-gap 1.5,1,0.5,1,1.5 --adhesion-work 0.001 --adhesion-range 0.5 \
    --out "$dir/indent_sticky" > "$dir/indent_sticky.out"
# its loop's jumps lie between the steps, and at mean gap 1 the retraction's zone is one patch short of the
# approach's: the trapezoids' -0.0003 is theirs, not a work lost
check "its loop's work is stated as not resolved, within its error" awk '
    match($0, /work lost not resolved by the steps: [-0-9.e]+ within the trapezoids. error \+- [0-9.e]+/) {
        split(substr($0, RSTART, RLENGTH), w, " "); work = w[8]; error = w[14]; found = 1 }
    END { exit !(found && (work < 0 ? -work : work) <= error && error > 0) }' "$dir/indent_sticky.out"
check "its history is indent --periodic --mean-gap --adhesion-work's" \
    cmp <(rows "$dir/sticky/histories/member_00_0.csv" | tail -n +2) <(rows "$dir/indent_sticky/history.csv")
check "the cell pulls out of contact" awk -F, '/^[0-9]/ && $3 < 0 && $5 == 0 { pulled = 1 } END { exit !pulled }' \
    "$dir/sticky/histories/member_00_0.csv"
check "each step's contact map is drawn" [ -s "$dir/sticky/panels/family_00/contact_0004.png" ]
check "no k for an adhesive cell" [ ! -e "$dir/sticky/k_fit.csv" ]
# The adhesive cell at mean pressures (load control), into tension: indent --periodic --pressure's history.
scene "$dir/sticky_p.ini" cell.npy "" "steps = 0.004, 0.001, -0.0005" $'[adhesion]\nwork = 0.002\nrange = 0.5' \
    sticky_p
check "an adhesive cell's scene runs at mean pressures" "$cli" run "$dir/sticky_p.ini" > /dev/null 2>&1
"$cli" indent "$dir/cell.npy" --periodic --pressure 0.004,0.001,-0.0005 --adhesion-work 0.002 --adhesion-range 0.5 \
    --out "$dir/indent_sticky_p" > /dev/null 2>&1
check "its history is indent --periodic --pressure --adhesion-work's" \
    cmp <(rows "$dir/sticky_p/histories/member_00_0.csv" | tail -n +2) <(rows "$dir/indent_sticky_p/history.csv")
# With a hardness too, under mean gaps: indent --periodic --mean-gap --hardness --adhesion-work's history.
scene "$dir/sticky_h.ini" cell.npy "" $'control = mean_gap\nsteps = 0.4, 0.2, 0.3' \
    $'[adhesion]\nwork = 0.002\nrange = 0.5\n[material]\nhardness = 0.05' sticky_h
check "an adhesive cell's scene runs with a hardness" "$cli" run "$dir/sticky_h.ini" > /dev/null 2>&1
"$cli" indent "$dir/cell.npy" --periodic --mean-gap 0.4,0.2,0.3 --hardness 0.05 --adhesion-work 0.002 \
    --adhesion-range 0.5 --out "$dir/indent_sticky_h" > /dev/null 2>&1
check "its history is indent --periodic --mean-gap --hardness --adhesion-work's" \
    cmp <(rows "$dir/sticky_h/histories/member_00_0.csv" | tail -n +2) <(rows "$dir/indent_sticky_h/history.csv")

# A sphere repeated with the cell, with a hardness, loaded and unloaded: indent's history; no k (a cap).
scene "$dir/sphere.ini" cell.npy $'shape = sphere\nradius = 20' "steps = 0.01:0.05:3, 0.03:0.01:2" \
    $'[material]\nhardness = 0.4' sphere
check "a repeated sphere with a hardness runs" "$cli" run "$dir/sphere.ini" > /dev/null 2>&1
"$cli" indent "$dir/cell.npy" --periodic --punch sphere --radius 20 --hardness 0.4 \
    --pressure 0.01:0.05:3,0.03:0.01:2 --out "$dir/indent_sphere" > /dev/null
check "its history is indent's, plastic flow and all" \
    cmp <(rows "$dir/sphere/histories/member_00_0.csv" | tail -n +2) <(rows "$dir/indent_sphere/history.csv")
check "the history yields" awk -F, 'NR > 2 && $21 > 0 { y = 1 } END { exit !y }' "$dir/sphere/histories/member_00_0.csv"
check "no k with a hardness" [ ! -e "$dir/sphere/k_fit.csv" ]

# Contact panels and distributions of a periodic cell, loaded and unloaded with a hardness: every step's fields
# are indent --fields' (plastic depth too) and its distributions indent --distributions', bit for bit; the drawn
# maps are indent --frames' size; the patch histogram sums to the history's contact count.
scene "$dir/maps.ini" cell.npy "" "steps = 0.002:0.03:3, 0.01" \
    $'[material]\nhardness = 0.3\n[output]\ncontact_panels = yes\ndistributions = yes' maps
check "a periodic scene with panels and distributions runs" "$cli" run --no-wisdom "$dir/maps.ini" > /dev/null 2>&1
"$cli" indent "$dir/cell.npy" --periodic --hardness 0.3 --pressure 0.002:0.03:3,0.01 --fields --frames \
    --distributions --out "$dir/indent_maps" > /dev/null 2>&1
same_files() { # FOLDER PATTERN RENAME(sed): every indent file matching PATTERN equals the scene's
    local n=0 f
    for f in "$dir/indent_maps"/$2; do
        cmp -s "$f" "$1/$(basename "$f" | sed "$3")" || return 1
        n=$((n + 1))
    done
    [ "$n" -gt 0 ]
}
check "its fields are indent --fields', every step" same_files "$dir/maps/panels/family_00" "*_000[1-4].npy*" ""
check "with the plastic depth" [ -s "$dir/maps/panels/family_00/plastic_0004.npy" ]
check "its distributions are indent --distributions'" \
    same_files "$dir/maps/distributions" "distributions_000[1-4]_*.csv" "s/^distributions_/family_00_/"
png_size() { python3 -c "import struct, sys; print(*struct.unpack('>II', open(sys.argv[1], 'rb').read()[16:24]))" "$1"; }
check "each step's contact map is drawn, indent --frames' size" bash -c "for i in 0 1 2 3; do
    [ \"\$($(declare -f png_size); png_size '$dir/maps/panels/family_00/contact_000'\$i.png)\" = \
      \"\$($(declare -f png_size); png_size '$dir/indent_maps/frames/contact_000'\$i.png)\" ] || exit 1; done"
patch_sums() { python3 - "$dir/maps" <<'PY'
import csv, sys
rows = [line.split(",") for line in open(sys.argv[1] + "/histories/member_00_0.csv") if line[0].isdigit()]
ok = len(rows) == 4
for step, row in enumerate(rows, 1):
    base = "%s/distributions/family_00_%04d" % (sys.argv[1], step)
    bins = list(csv.DictReader(open(base + "_patches.csv")))
    listed = list(csv.DictReader(open(base + "_patch_list.csv")))
    gaps = sum(int(r["cells"]) for r in csv.DictReader(open(base + "_gaps.csv")))
    ok &= sum(int(b["cells"]) for b in bins) == int(row[4]) == sum(int(p["cells"]) for p in listed)
    ok &= sum(int(b["patches"]) for b in bins) == len(listed) == int(row[18])
    ok &= gaps + int(row[4]) == 64 * 64
sys.exit(not ok)
PY
}
check "the distributions sum to each step's contact count and patches" patch_sums
check "outputs.txt lists the maps" grep -qx "panels/family_00/contact_0003.png" "$dir/maps/outputs.txt"
check "--resume solves the mapped surface again" expect_exit 0 "1 solved, 0 read back" \
    "$cli" run --resume --no-wisdom "$dir/maps.ini"
check "the same fields" same_files "$dir/maps/panels/family_00" "*_000[1-4].npy*" ""
scene "$dir/maps.ini" cell.npy "" "steps = 0.002:0.03:3" $'[material]\nhardness = 0.3\n[output]\ncontact_panels = yes' maps
check "fewer steps" "$cli" run --no-wisdom "$dir/maps.ini" > /dev/null 2>&1
check "remove the maps and distributions no longer made" \
    [ ! -e "$dir/maps/panels/family_00/force_0004.npy" -a ! -e "$dir/maps/distributions/family_00_0001_gaps.csv" ]

# A ramp is not periodic: the warning of indent, naming the file.
python3 -c "
with open('$dir/ramp.txt', 'w') as f:
    f.writelines(' '.join('%g' % (0.1 * x) for x in range(32)) + '\n' for y in range(32))"
scene "$dir/ramp.ini" ramp.txt "" "steps = 0.01" "" ramp
check "a ramp is warned about" expect_exit 0 "ramp.txt: the surface of family 0, seed 0 is not periodic" \
    "$cli" run "$dir/ramp.ini"

# The refusals, each naming the key at fault.
refuse() { # NAME PUNCH-LINES LOADING-LINES OTHER-LINES PHRASE
    scene "$dir/bad.ini" cell.npy "$2" "$3" "$4" bad
    check "$1" expect_exit 2 "$5" "$cli" run "$dir/bad.ini"
}
refuse "load control" "" $'control = load\nsteps = 0.01' "" "bad.ini:10: [loading] control beside [punch] periodic"
refuse "load_star" "" $'load_star = 100\nsteps = 0.01' "" "[loading] load_star beside [punch] periodic"
refuse "the table" "" "steps = 0.01" $'[output]\ntable = yes' "[output] table beside [punch] periodic"
refuse "frames" "" "steps = 0.01" $'[output]\ncontact_panels = no\nframes = yes' \
    "[output] frames beside [punch] periodic: the frames are a history of their own up to load_star N*; a periodic scene draws the contact map of every step"
refuse "Love's theory" "" "steps = 0.01" $'[output]\nplots = fig6' "plots = fig6 beside [punch] periodic"
refuse "the smooth contact circle" "" "steps = 0.01" $'[output]\nplots = fig1' "plots = fig1 beside [punch] periodic"
refuse "an angle without a shape" "alpha = 70" "steps = 0.01" "" "[punch] alpha beside periodic without shape"
refuse "no steps" "" "" "" "[punch] periodic needs [loading] steps"
refuse "unloading without a hardness" "" "steps = 0.02, 0.01" "" "steps must increase"
refuse "mean gaps that rise without a hardness" "" $'control = mean_gap\nsteps = 0.2, 0.3' "" "steps must decrease"
# (refused before solving: it was refused at its step, after those before it were solved)
refuse "a mean gap of 0" "" $'control = mean_gap\nsteps = 0.4, 0' "" \
    "bad.ini:11: steps: step 2 is the mean gap 0: expected mean gaps > 0 (at 0 the cell is in full contact)"
printf '[scene]\nname = hs\noutput = hs\n[surfaces]\nfile = cell.npy\n[punch]\nshape = cone\n[loading]\ncontrol = mean_gap\nsteps = 0.5\n' \
    > "$dir/hs.ini"
check "mean gaps on the half-space" expect_exit 2 "control = mean_gap needs [punch] periodic" "$cli" run "$dir/hs.ini"

# An indentation analysis per member of a hardness history that goes up and down: indent's indentation.csv.
printf '[scene]\nname = cycle\noutput = cycle\n[surfaces]\nfile = cell.npy\n[punch]\nshape = cone\nalpha = 80\n[material]\nhardness = 0.3\n[loading]\ncontrol = displacement\nsteps = 1:4:4, 3:1:3\n[output]\nplots = fig5\n' \
    > "$dir/cycle.ini"
check "a cycle with a hardness runs" expect_exit 0 "the indentation analysis of 1 surface in" "$cli" run "$dir/cycle.ini"
"$cli" indent "$dir/cell.npy" --hardness 0.3 --approach 1:4:4,3:1:3 --out "$dir/indent_cycle" > /dev/null
check "the member's indentation.csv is indent's" \
    cmp "$dir/cycle/indentation/member_00_0.csv" "$dir/indent_cycle/indentation.csv"
check "outputs.txt lists it" grep -qx "indentation/member_00_0.csv" "$dir/cycle/outputs.txt"
printf 'x\0y' > "$dir/cycle/indentation/member_00_0.csv"
check "--resume makes a damaged one again" expect_exit 0 "holds binary" "$cli" run --resume "$dir/cycle.ini"
check "as it was" cmp "$dir/cycle/indentation/member_00_0.csv" "$dir/indent_cycle/indentation.csv"
# ... and a fit past the touch (w = 0 withdrawn) says why S is NaN and what to do, in indent's words (findings R3)
sed -i 's/1:4:4, 3:1:3/1:4:4, 2, 0/' "$dir/cycle.ini"
note="the unloading from step 4: S, and h_c, A_p, H_IT and E_r after it, are NaN: the stiffness fit's third point (step 6) is past the touch"
check "a scene says why S is NaN" expect_exit 0 "histories: indentation/member_00_0.csv: $note" "$cli" run "$dir/cycle.ini"
check "as indent says it" bash -c "'$cli' indent '$dir/cell.npy' --hardness 0.3 --approach 1:4:4,2,0 | grep -qF \"indentation analysis: $note\""
sed -i 's/1:4:4, 2, 0/1:4:4/' "$dir/cycle.ini"
check "a history that only loads removes it" expect_exit 0 "indentation/member_00_0.csv" "$cli" run "$dir/cycle.ini"
check "removed" [ ! -e "$dir/cycle/indentation/member_00_0.csv" ]

# The example scene.
check "scenes/periodic.ini runs" bash -c "cd '$dir' && '$cli' run '$(cd "$(dirname "$0")/.." && pwd)/scenes/periodic.ini' > /dev/null 2>&1"
check "with k near eq. (2)'s 2 on its four surfaces" python3 -c "import csv, sys; r = list(csv.DictReader(open(sys.argv[1]))); \
sys.exit(not (len(r) == 4 and all(1.6 < float(x['k']) < 2.3 and float(x['k_error']) < 0.05 for x in r)))" \
    "$dir/output/periodic/k_fit.csv"
finish
