#!/usr/bin/env bash
# What is computed is checked before it is drawn (issue 12): no history step dropped without a
# word (the pre-flight check refuses steps whose smooth contact leaves the surface, for every punch
# and control; a history that still reaches the edge fails with the step), and messages for inputs
# that were accepted silently or explained wrongly.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
export OMP_NUM_THREADS=1

history_scene() { # history_scene NAME N SHAPE CONTROL STEPS PLOT [SLOPE]
  cat >"$dir/$1.ini" <<INI
[scene]
name = $1
output = out_$1
[surfaces]
n = $2
slopes = ${7:-0.08}
seeds = 1:2
[punch]
shape = $3
$([ "$3" = cone ] || echo "radius = 500")
[loading]
control = $4
steps = $5
[output]
plots = $6
INI
}
refused_before_work() { # refused_before_work NAME PATTERN
  check "$1: refused" expect_exit 2 "$2" "$cli" run --quiet "$dir/$1.ini"
  check "$1: no output folder" test ! -e "$dir/out_$1"
}

# The sphere scene's loads on a grid too small (before: it stopped at the edge, exit 0, and drew a
# plot that ends before the crossover it exists to show).
history_scene sphere 64 sphere load "1, 10, 100, 1000, 10000" sphere 0.16
refused_before_work sphere "sphere.ini: [loading] steps (largest) = 10000: the smooth contact radius sqrt(N*/pi) = 56.4 patches reaches the edge of the 64 x 64 surface"
# Displacement control: the punch's a(w), for a cone and a sphere.
history_scene cone_w 32 cone displacement "1, 2, 60" fig5
refused_before_work cone_w "cone_w.ini: [loading] steps (largest approach) = 60: the smooth contact radius a(w) of the punch"
history_scene sphere_w 32 sphere displacement "0.1, 0.2, 0.6" fig6
refused_before_work sphere_w "sphere_w.ini: [loading] steps (largest approach) = 0.6: the smooth contact radius a(w) of the punch = 17.3 patches"
# A flat punch of radius 31.5 on 64 x 64 reaches the edge patches' centres 31 from the centred axis (patch
# 32's centre): refused before work, as the solver refuses its first step (before: `run --check` passed it).
history_scene flat_w 64 flat displacement "0.1" fig6
sed -i 's/^radius = 500$/radius = 31.5/' "$dir/flat_w.ini"
refused_before_work flat_w "flat_w.ini: [loading] steps (largest approach) = 0.1: the smooth contact radius a(w) of the punch = 31.5 patches reaches the edge of the 64 x 64 surface (expected a radius < 31 patches"
check "flat_w: run --check refuses it too" expect_exit 2 "expected a radius < 31 patches" "$cli" run --check "$dir/flat_w.ini"
# Fig. 7 over one step (before: the solve ran, then the figure failed with "x[1] = inf").
history_scene one_step 32 cone load "300" fig7
refused_before_work one_step "one_step.ini:15: plots = fig7 needs at least two [loading] steps (1 given)"
# Steps that pass the smooth check but whose rough contact reaches the edge: the run fails and says
# which step, instead of drawing the histories cut short.
history_scene edge 32 cone load "100:700:4" fig7 0.5
check "history at the edge fails" expect_exit 1 "step 3 of 4 (N* 500; the scene asks for every step" \
  "$cli" run --quiet "$dir/edge.ini"
check "history at the edge: no figure" test ! -e "$dir/out_edge/fig7.png"

# render animate: an all-zero force field (approach 0) leaves the shared norm at 0 .. the largest
# force of the others (the statistics print 6 digits) (before: its fallback range widened every frame's norm to [0, 1]).
"$cli" surface --n 64 --slope 0.1 --seed 1 --out "$dir/s.npy" >/dev/null
"$cli" indent "$dir/s.npy" --approach 0:3:4 --fields --out "$dir/f" >"$dir/f.log"
"$cli" render animate "$dir"/f/force_000{1,2,3,4}.npy --frames "$dir/frames" --out "$dir/a.gif" >/dev/null
# indent --fields: u on the whole grid, positive everywhere under a positive load (before: 0 outside
# the solve window, so h - u showed a square step at its edge).
smallest=$("$cli" surface --stats "$dir/f/displacement_0004.npy" --detrend none | awk '$1 == "height" { sub(/\[/, "", $3); sub(/,/, "", $3); print $3 }')
check "displacement positive outside the window (smallest $smallest)" awk -v u="$smallest" 'BEGIN { exit !(u > 0) }'
window=$(grep -o "window \[[0-9]*, [0-9]*)" "$dir/f.log" | head -1)
check "the window is smaller than the grid ($window)" test -n "$window" -a "$window" != "window [0, 64)"
largest=$(for f in "$dir"/f/force_000[234].npy; do "$cli" surface --stats "$f" --detrend none | awk '$1 == "height" { sub(/\]/, "", $4); print $4 }'; done | sort -g | tail -1)
norm=$(grep -a -o "log \[[0-9.e+-]*, [0-9.e+-]*\]" "$dir/frames/contact_0000.png") # the default force norm
check "zero field: norm up to the largest force ($largest), not 1 ($norm)" \
  awk -v n="$norm" -v m="$largest" 'BEGIN { sub(/.*, /, "", n); sub(/\]/, "", n); exit !(m > 0 && (n - m) ^ 2 < 1e-10 * m * m) }'

# An address-space limit (ulimit -v): the estimate counts the threads' stacks and malloc arenas and
# the renderer, so a scene that cannot run is refused before any work (before: the check passed,
# the run failed mid-way and left frames/ behind). Not under AddressSanitizer (its shadow memory
# needs terabytes of address space).
cat >"$dir/frames.ini" <<INI
[scene]
name = frames
output = out_frames
[surfaces]
n = 64
slopes = 0.08
seeds = 1
[punch]
shape = cone
[loading]
load_star = 300
[output]
frames = yes
frame_count = 3
animation = gif
INI
if ldd "$cli" 2>/dev/null | grep -q libasan; then
  echo "note: AddressSanitizer build: the ulimit -v checks are skipped"
else
  (ulimit -v 450000; "$cli" run --quiet "$dir/frames.ini" >/dev/null 2>"$dir/as.err"; echo $? >"$dir/as.status")
  check "ulimit -v: refused (exit 2)" test "$(cat "$dir/as.status")" -eq 2
  check "ulimit -v: message" grep -q "frames.ini: this scene needs about [0-9.]* MiB of address space" "$dir/as.err"
  check "ulimit -v: no output folder" test ! -e "$dir/out_frames"
  (ulimit -v 1000000; "$cli" run --quiet "$dir/frames.ini" >/dev/null 2>"$dir/as2.err"; echo $? >"$dir/as2.status")
  check "ulimit -v: a limit that suffices runs the scene" test "$(cat "$dir/as2.status")" -eq 0
  check "ulimit -v: the frames' last step at load_star" test -f "$dir/out_frames/contact.gif"
fi

# Options accepted silently or explained wrongly before.
check "surface --n 2 names --n" expect_exit 2 "--n 2: the box's side is the default lambda_r" \
  "$cli" surface --n 2 --out "$dir/n2.npy"
check "--lambda-0 below lambda_r" expect_exit 2 "--lambda-0 10: expected >= lambda_r = 64" \
  "$cli" surface --n 64 --lambda-0 10 --out "$dir/l0.npy"
check "--approach 1:2" expect_exit 2 "--approach '1:2': '1:2' is not a range first:last:count (three numbers" \
  "$cli" indent "$dir/s.npy" --approach 1:2 --out "$dir/o_a"
check "--approach 1,,2" expect_exit 2 "--approach '1,,2'" "$cli" indent "$dir/s.npy" --approach 1,,2 --out "$dir/o_b"
check "--delta 1e300" expect_exit 2 "surface delta = 1e+300: expected 1e-150 <= delta <= 1e150" \
  "$cli" indent --smooth --n 32 --approach 1 --delta 1e300 --out "$dir/o_d"
awk 'BEGIN { for (y = 0; y < 8; ++y) { line = ""; for (x = 0; x < 8; ++x) line = line (x ? " " : "") ((x == 3 && y == 2) ? 1e308 : 0); print line } }' \
  > "$dir/huge_field.txt"
check "render height 1e308" expect_exit 2 "height map: height 1e+308 (1e+308 delta) at patch (3, 2): expected |h| <= 1e18 delta" \
  "$cli" render height "$dir/huge_field.txt" --out "$dir/huge.png"
# One huge height in a surface file (reliability row 18): named as the file holds it, before the
# plane is removed (which moved it to another point and value, or made every statistic NaN at 1e308).
# The reader itself takes such finite values (fuzz/corpus/npy/valid_v2_1x3.npy holds -1e300).
for huge in 1e160 1e308; do
  awk -v h="$huge" 'BEGIN { for (y = 0; y < 8; ++y) { line = ""; for (x = 0; x < 8; ++x) line = line (x ? " " : "") ((x == 3 && y == 2) ? h : x + y); print line } }' \
    >"$dir/huge_$huge.txt"
  check "surface --stats: a height $huge named with its file and point" expect_exit 2 \
    "huge_$huge.txt: surface before detrending: height ${huge/e/e+} at (x=3, y=2): expected |h| <= 1e+100" \
    "$cli" surface --stats "$dir/huge_$huge.txt"
  # indent's default, --detrend none, met it first in the statistics, which name no file
  check "indent: a height $huge named with its file and point" expect_exit 2 \
    "huge_$huge.txt: surface: height ${huge/e/e+} at (x=3, y=2): expected |h| <= 1e+100" \
    "$cli" indent "$dir/huge_$huge.txt" --approach 1 --out "$dir/o_huge"
done
check "--out ''" expect_exit 2 "--out '': expected a file or folder name" "$cli" indent "$dir/s.npy" --approach 1 --out ''
check "--psd ''" expect_exit 2 "--psd '': expected a file or folder name" "$cli" surface --n 16 --psd '' --out "$dir/p.npy"
check "--radius with a cone" expect_exit 2 "--radius applies to --punch sphere or flat" \
  "$cli" indent "$dir/s.npy" --approach 1 --radius 5 --out "$dir/o_c"
check "--x outside the surface" expect_exit 2 "--x 1000 --y 10: the punch's axis lies outside the 64 x 64 surface" \
  "$cli" indent "$dir/s.npy" --approach 1 --x 1000 --y 10 --out "$dir/o_x"
check "--titles surplus" expect_exit 2 "--titles 'a,b,c': 3 titles for 2 files" \
  "$cli" render contact "$dir/f/force_0004.npy" "$dir/f/force_0003.npy" --titles a,b,c --out "$dir/t.png"
check "info: bad IM_RENDER_BACKEND is bad input" expect_exit 2 "IM_RENDER_BACKEND" \
  env IM_RENDER_BACKEND=bogus "$cli" info
check "bad IM_MEMORY_LIMIT_MIB is bad input" expect_exit 2 "IM_MEMORY_LIMIT_MIB = 'lots': expected a number of MiB > 0" \
  env IM_MEMORY_LIMIT_MIB=lots "$cli" surface --stats "$dir/s.npy"
check "IM_MEMORY_LIMIT_MIB caps the memory" expect_exit 2 "needs about" \
  env IM_MEMORY_LIMIT_MIB=1 "$cli" surface --n 1024 --out "$dir/capped.npy"
printf '1e300 1e300 1e300 1e300\n1e300 1e300 1e300 1e300\n1e300 1e300 1e300 1e300\n' >"$dir/huge.txt"
# A flat punch's gap is +Inf where the punch can never touch: render reads fields with their NaN and
# Inf (drawn in the over colour), as it draws them, where a surface to solve on must be finite.
"$cli" indent "$dir/s.npy" --punch flat --radius 10 --approach 0.2 --fields --out "$dir/flat" >/dev/null
check "flat punch: its gap holds +Inf" bash -c "\"$cli\" surface --stats \"$dir/flat/gap_0001.npy\" 2>&1 | grep -q 'value inf'"
check "flat punch: render draws its gap" "$cli" render height "$dir/flat/gap_0001.npy" --out "$dir/gap.png"
check "... a real picture" test -s "$dir/gap.png"
check "... its colour bar names a gap, as its sidecar says" grep -aq "Quantity.*gap g / " "$dir/gap.png"
# (unprepared: removing the plane of this constant surface leaves it flat, a valid answer)
# A scene with a hardness may unload (issue 26): its member histories go up and down, nothing flows while
# unloading, and the load returns to 0 at the approach where the punch meets the impression it left.
cat >"$dir/unload.ini" <<INI
[scene]
name = unload
output = out_unload
[surfaces]
n = 64
slopes = 0.08
seeds = 1
[punch]
shape = cone
[material]
hardness = 0.05
[loading]
control = load
steps = 100:400:4, 300:0:4
[output]
plots = fig5
INI
check "a scene that unloads with a hardness" "$cli" run --quiet "$dir/unload.ini"
check "... its run.json states the theory's h'rms definition" grep -q '"definition": "spectral"' "$dir/out_unload/run.json"
check "... its history keeps the impression" awk -F, 'NR > 2 && !/^#/ { n++; w[n] = $2; N[n] = $3; work[n] = $23; r[n] = $24 }
  END { if (n != 8 || !(work[4] > 0) || work[8] != work[4] || N[8] != 0 || w[8] != r[8] || !(w[5] < w[4])) exit 1 }' \
  "$dir/out_unload/histories/member_00_1.csv"
check "huge heights: refused, not NaN statistics" expect_exit 2 "height 1e+300 at (x=0, y=0): expected |h| <= 1e+100" \
  "$cli" surface --stats "$dir/huge.txt" --detrend none
# a scene asking for no output solved nothing and exited 0, silently
printf '[scene]\noutput = %s\n[surfaces]\nn = 32\n[loading]\nsteps = 0.4\n' "$dir/nothing" >"$dir/nothing.ini"
check "no [output]: refused naming the file" expect_exit 2 "nothing.ini: no output asked for: expected an [output] section" \
  "$cli" run "$dir/nothing.ini"
printf '[output]\nplots =\ntable = no\n' >>"$dir/nothing.ini"
check "[output] asking for nothing: refused" expect_exit 2 "nothing.ini: no output asked for" "$cli" run "$dir/nothing.ini"
check "no output: no folder made" test ! -e "$dir/nothing"
# an option with a value given twice: the last won silently (T10); one rule for every command's options
check "--alpha twice: refused" expect_exit 2 "--alpha given twice ('70', then '85'): expected it once" \
  "$cli" indent --smooth --n 32 --approach 2 --alpha 70 --alpha 85
check "--approach twice: the same rule" expect_exit 2 "--approach given twice ('1', then '2')" \
  "$cli" indent --smooth --n 32 --approach 1 --approach 2
check "--quality twice: refused" expect_exit 2 "--quality given twice ('draft', then 'publication')" \
  "$cli" indent --smooth --n 32 --approach 1 --quality draft --quality publication
check "an abbreviation is the same option" expect_exit 2 "--alpha given twice ('70', then '85')" \
  "$cli" indent --smooth --n 32 --approach 2 --alp 70 --alpha=85
check "surface --out twice" expect_exit 2 "--out given twice ('$dir/a.npy', then '$dir/b.npy')" \
  "$cli" surface --n 32 --out "$dir/a.npy" --out "$dir/b.npy"
check "... nothing written" test ! -e "$dir/a.npy" -a ! -e "$dir/b.npy"
check "run --out twice" expect_exit 2 "--out given twice ('a', then 'b')" "$cli" run --out a --out b "$dir/unload.ini"
check "theory --slope twice" expect_exit 2 "--slope given twice" "$cli" theory --alpha 80 --slope 0.1 --slope 0.2
check "render --vmin twice" expect_exit 2 "--vmin given twice" "$cli" render contact x.npy --vmin 1 --vmin 2
check "a flag twice changes nothing" "$cli" indent --smooth --smooth --n 32 --approach 1
# [loading] steps in a scene that solves no history (a table at load_star) did nothing, silently: a
# study of loads so written got one load. Warned about, naming the key; not where histories use it.
printf '[scene]\noutput = %s\n[surfaces]\nn = 64\nslopes = 0.08\nseeds = 1:2\n[loading]\ncontrol = load\nload_star = 300\nsteps = 100:300:3\n[output]\ntable = yes\n' \
  "$dir/steps_unused" >"$dir/steps_unused.ini"
"$cli" run --check "$dir/steps_unused.ini" >/dev/null 2>"$dir/steps_unused.log"
check "steps without histories: the check passes" test $? -eq 0
check "steps without histories: warned, naming the key" grep -q "\[loading\] steps does nothing: the steps are the histories'" \
  "$dir/steps_unused.log"
sed 's/^table = yes/plots = fig7/' "$dir/steps_unused.ini" >"$dir/steps_used.ini"
"$cli" run --check "$dir/steps_used.ini" >/dev/null 2>"$dir/steps_used.log"
check "steps of fig7's histories: the check passes" test $? -eq 0
check "steps of fig7's histories: no warning" bash -c "! grep -q 'does nothing' '$dir/steps_used.log'"
finish
