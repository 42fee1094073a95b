#!/usr/bin/env bash
# End-to-end: a reduced scene (64 x 64, a smooth and a rough family) through parse, plan, solve,
# render and write; then the files and their contents; then a damaged scene. Exit 77 (skipped)
# when no OpenGL context can be had, with the reason.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"

cat >"$dir/small.ini" <<INI
[scene]
name = small
output = $dir/out
[surfaces]
n = 64
hurst = 0.8
lambda_s = 4
slopes = 0, 0.08
seeds = 5:6
[punch]
shape = cone
alpha = 80
[loading]
load_star = 600
control = load
steps = 100:600:3
[solver]
tol = 1e-8
[output]
contact_panels = yes
frames = yes
frame_count = 3
animation = gif
table = yes
plots = fig1, fig2, fig3, fig5, fig6, fig7
INI

"$cli" run "$dir/small.ini" >"$dir/log" 2>&1
status=$?
if [ $status -ne 0 ] && ! grep -q "rendering with" "$dir/log"; then
  echo "SKIPPED: no OpenGL context: $(tail -1 "$dir/log")"
  exit 77
fi
check "scene runs" test $status -eq 0
for f in contact_panels.png contact_panels.pdf results.csv contact.gif panels/force_00.npy panels/force_01.npy \
         frames/contact_0000.png frames/contact_0002.png frames/height_0002.png fig1.png fig2.pdf fig3.png \
         table1.csv table1.md table/member_00_5.csv table/member_01_6.csv fig5.png fig6.pdf fig7.png fig7.csv \
         histories/member_01_6.csv; do
  check "wrote $f" test -s "$dir/out/$f"
done
check "no temporary files" bash -c "! find '$dir/out' -name '*.tmp.*' | grep -q ."
# The smooth family's n_p delta^2 against A_cone at N* = 600 (a coarse grid: within 3%), and the
# load_star column is the requested N*.
check "smooth area ratio near 1" awk -F, 'NR == 2 { exit !($7 > 0.97 && $7 < 1.03) }' "$dir/out/results.csv"
check "load_star is N*" awk -F, 'NR == 2 { exit !($5 > 599.99 && $5 < 600.01) }' "$dir/out/results.csv"
check "rough family has less contact" awk -F, 'NR == 2 { s = $6 } NR == 3 { exit !($6 < s) }' "$dir/out/results.csv"
check "png has the scene in a text chunk" grep -qa "small.ini" "$dir/out/contact_panels.png"

# Every column of the scene's tables has its unit in run.json (the page heads its tables with them).
check "run.json has a unit for every table column" /usr/bin/python3 -c "
import csv, json, sys
units = json.load(open('$dir/out/run.json'))['units']['columns']
for table in ('results.csv', 'table1.csv', 'fig7.csv', 'table/member_01_6.csv'):
    header = next(csv.reader(open('$dir/out/' + table)))
    missing = [c for c in header if c not in units]
    if missing:
        sys.exit(f'{table}: no unit for {missing}')
assert units['load'] == 'E* δ²' and units['height_rms_mean'] == 'δ' and units['height_rms'] == 'δ', units"
check "the page heads results.csv's load with its unit" grep -q '<th>load<br><span class="unit">(E\* δ²)</span></th>' "$dir/out/index.html"

# The table: the smooth family is solved once whatever the seeds, the rough one per seed.
check "table has two families" awk -F, 'NR == 2 { exit !($2 == 1) } NR == 3 { exit !($2 == 2) }' "$dir/out/table1.csv"
check "smooth solved once" test ! -e "$dir/out/table/member_00_6.csv"

# Histories in load control reach each N* step: the last row of a rough member is at N* = 600.
check "history reaches the last N*" awk -F, 'END { exit !($4 > 599.99 && $4 < 600.01) }' "$dir/out/histories/member_01_6.csv"

# Theory beside the history: eq. (12) at rho_c = cot(alpha) / h'rms in every row (the load does not
# enter it), and A_cone = N* delta^2. The columns are indent's history.csv's (one schema; cli_front_ends.sh).
check "history has the theory columns" bash -c "sed -n 2p '$dir/out/histories/member_01_6.csv' | \
  grep -qx 'step,approach,load,load_star,contact_patches,area_ratio,mean_pressure,max_pressure,iterations,residual,seconds,convolutions,load_smooth,area_smooth,area_ratio_constant,area_ratio_gamma,stiffness,e_star_sneddon,patches,patch_perimeter,yielding_patches,plastic_depth,plastic_work,residual_approach,tensile_force,adhesive_patches,repulsive_patches,mean_gap'"
eq12=$("$cli" theory --alpha 80 --slope 0.08 --format csv | awk -F, 'NR == 2 { print $4 }')
check "history's eq. (12) column" awk -F, -v e="$eq12" 'NR > 2 { d = $16 - e; if (d < -1e-9 || d > 1e-9 || $14 != $4) bad = 1 }
  END { exit bad }' "$dir/out/histories/member_01_6.csv"

# fig7.csv: the plotted mean of the rough family at its last N* (600) is the mean of its two
# surfaces' A/A_cone there, and eq. (12) the theory's.
check "fig7.csv's last mean is the surfaces' mean at N* = 600" awk -F, -v e="$eq12" '
  FNR == 1 { file++ } file <= 2 && FNR > 2 { last[file] = $6 }
  file == 3 && FNR > 1 { mean = $3; n_star = $2; eq = $6 }
  END { d = mean - (last[1] + last[2]) / 2; exit !(d * d < 1e-20 && n_star > 599.99 && (eq - e) ^ 2 < 1e-18) }' \
  "$dir/out/histories/member_01_5.csv" "$dir/out/histories/member_01_6.csv" "$dir/out/fig7.csv"

# Nothing solved twice: the table solves each surface at N* = 600; the histories' last step (N* =
# 600) is the table's; the panels are the table's (smooth) and the frames' last step (rough).
check "table solves its 3 surfaces" grep -q "table: 3 surfaces: 3 solved, 0 read back" "$dir/log"
check "histories take N* = 600 from the table" grep -q "histories: 3 steps at load_star taken from the table" "$dir/log"
check "no panel solved again" grep -q "panels: 2 surfaces: 0 solved, 0 read back, 2 reused" "$dir/log"
check "history's last step is the table's" cmp <(cut -d, -f5 "$dir/out/table/member_01_6.csv" | tail -1) \
  <(cut -d, -f3 "$dir/out/histories/member_01_6.csv" | tail -1)

# Resume reads the panels back instead of solving them.
"$cli" run --resume "$dir/small.ini" >"$dir/log2" 2>&1
check "resume succeeds" test $? -eq 0
check "resume reuses panels" grep -q "reusing" "$dir/log2"
check "resume reads the table back" grep -q "table: 3 surfaces: 0 solved, 3 read back" "$dir/log2"
check "resume solves no panel" grep -q "panels: 2 surfaces: 0 solved" "$dir/log2"

# [output] frames_clip = 5 (render --clip's): the frames drawn again with 5 % of their values cut at each end of
# their one range: the height frames' norm strictly inside the full one, the contact frames' top below the largest
# force, the colour bar's triangles (the figure's pixels differ); the key removed again before what follows.
norm_of() { grep -ao 'Norm.[a-z]* \[[^]]*\]' "$1" | cut -c6-; }
cp -r "$dir/out" "$dir/unclipped"
sed -i 's/^frame_count = 3$/frame_count = 3\nframes_clip = 5/' "$dir/small.ini"
"$cli" run --resume "$dir/small.ini" >"$dir/log_clip" 2>&1
check "frames_clip: resume succeeds" test $? -eq 0
inside() { python3 -c 'import re, sys  # FULL CLIPPED ENDS: CLIPPED strictly inside FULL at the ENDS (lo, hi, both)
full, cut = ([float(v) for v in re.findall(r"-?[0-9][-+0-9.e]*", text)] for text in sys.argv[1:3])
sys.exit(not ((cut[0] > full[0] or sys.argv[3] == "hi") and cut[1] < full[1]))' "$@"; }
check "frames_clip: the height frame's norm inside the full one" inside \
  "$(norm_of "$dir/unclipped/frames/height_0002.png")" "$(norm_of "$dir/out/frames/height_0002.png")" both
check "frames_clip: the contact frame's top below the largest force" inside \
  "$(norm_of "$dir/unclipped/frames/contact_0002.png")" "$(norm_of "$dir/out/frames/contact_0002.png")" hi
sed -i '/^frames_clip = 5$/d' "$dir/small.ini"
# [output] contact_panels_clip = 5: the contact panels' one force norm with its top 5 % cut, as frames_clip's
# (it took no clip: a needle asperity's force made every other patch one colour), its PNG stating the norm.
sed -i 's/^contact_panels = yes$/contact_panels = yes\ncontact_panels_clip = 5/' "$dir/small.ini"
"$cli" run --resume "$dir/small.ini" >"$dir/log_clip" 2>&1
check "contact_panels_clip: resume succeeds" test $? -eq 0
check "contact_panels_clip: the panels' top below the largest force" inside \
  "$(norm_of "$dir/unclipped/contact_panels.png")" "$(norm_of "$dir/out/contact_panels.png")" hi
sed -i '/^contact_panels_clip = 5$/d' "$dir/small.ini"

# An edited scene: --resume solves again what the change touches (with a notice) and ends with the
# results of a fresh run of the edited scene, not the old ones.
cp -r "$dir/out" "$dir/old"
sed -i 's/^slopes = 0, 0.08$/slopes = 0, 0.16/' "$dir/small.ini"
"$cli" run --resume "$dir/small.ini" >"$dir/log3" 2>&1
check "edited resume succeeds" test $? -eq 0
check "edited resume names a stale member" grep -q "member_01_6.csv was made from other inputs" "$dir/log3"
check "edited resume keeps the smooth member" grep -q "table: 3 surfaces: 2 solved, 1 read back" "$dir/log3"
sed "s|^output = .*|output = $dir/fresh|" "$dir/small.ini" >"$dir/fresh.ini"
"$cli" run "$dir/fresh.ini" >/dev/null 2>&1
for f in table1.csv results.csv panels/force_01.npy; do
  check "edited resume: $f as a fresh run" cmp "$dir/fresh/$f" "$dir/out/$f"
done
for f in histories/member_01_5.csv histories/member_01_6.csv; do
  check "edited resume: $f as a fresh run" cmp <(history_rows "$dir/fresh/$f") <(history_rows "$dir/out/$f")
done
check "edited resume: not the old table" bash -c "! cmp -s '$dir/old/table1.csv' '$dir/out/table1.csv'"

# The sphere's figure draws steps of at least 10 contact patches: loads that never reach them are
# refused, naming the resolution.
printf '[scene]\nname = tiny\noutput = %s\n[surfaces]\nn = 64\nslopes = 0.16\nseeds = 1\n[punch]\nshape = sphere\nradius = 60\n[loading]\ncontrol = load\nsteps = 1, 2, 3\n[output]\nplots = sphere\n' \
  "$dir/tiny" >"$dir/tiny.ini"
"$cli" run --quiet "$dir/tiny.ini" 2>"$dir/tiny.err"
check "a sphere figure below the grid's resolution is refused" test $? -eq 2
check "... naming the resolution" grep -qF "the surfaces of h'rms 0.16 reach 10 contact patches (the grid's resolution) at fewer than two" "$dir/tiny.err"

# A damaged scene names its file and line.
printf '[surfaces]\nn = 64\nslopes = 0, x\n' >"$dir/bad.ini"
"$cli" run "$dir/bad.ini" 2>"$dir/err"
check "damaged scene exits 2" test $? -eq 2
check "damaged scene names the line" grep -q "bad.ini:3: slopes" "$dir/err"
printf '[output]\nplots = fig4\n' >"$dir/plot.ini"
"$cli" run "$dir/plot.ini" 2>"$dir/err"
check "unknown plot refused" grep -q "plots: 'fig4' is not a figure" "$dir/err"
"$cli" run "$dir/none.ini" 2>"$dir/err"
check "missing scene exits 1" test $? -eq 1

finish
