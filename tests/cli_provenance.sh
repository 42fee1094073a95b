#!/usr/bin/env bash
# Provenance (issue 31): a scene run's run.json carries the scene's contents as parsed and its inputs'
# SHA-256, so that `run --from-record` makes the run again after its scene file was edited, and refuses
# when an input changed or the record is of another version; its figures carry the contents too.
# The scene is scenes/fig4.ini reduced to 64 x 64 (N* = 580, the paper's contact radius relative to the
# box; 3 frames): fig4 itself takes 8 s, and many times that under the sanitizers. Exit 77 (skipped)
# when no OpenGL context can be had.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
export IM_FFTW_WISDOM="$dir/wisdom" # never the user's cache

sed -e 's/^n = 512/n = 64/' -e 's/^lambda_r = 512/lambda_r = 64/' -e 's/^load_star = 37000 .*/load_star = 580/' \
    -e 's/^frame_count = 12/frame_count = 3/' "$(dirname "$0")/../scenes/fig4.ini" >"$dir/fig4.ini"
"$cli" run --quiet --no-wisdom "$dir/fig4.ini" --out "$dir/a" >"$dir/log" 2>&1
status=$?
if [ $status -ne 0 ] && grep -q "OpenGL\|EGL\|OSMesa" "$dir/log"; then
  echo "SKIPPED: no OpenGL context: $(tail -1 "$dir/log")"
  exit 77
fi
check "reduced fig4 runs into --out" test $status -eq 0 -a -s "$dir/a/results.csv"

# The record holds every key the file set, as parsed (comments dropped), and the file's absolute path.
record_value() { python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); print(eval(sys.argv[2]))' "$@"; }
check "record has [punch] alpha" test "$(record_value "$dir/a/run.json" 'd["scene_contents"]["sections"]["punch"]["alpha"]')" = 80
check "record has load_star without its comment" \
  test "$(record_value "$dir/a/run.json" 'd["scene_contents"]["sections"]["loading"]["load_star"]')" = 580
check "record names the scene file" \
  test "$(record_value "$dir/a/run.json" 'd["scene_contents"]["scene_file"]')" = "$(realpath "$dir/fig4.ini")"
check "a generated scene has no input files" test "$(record_value "$dir/a/run.json" 'len(d["inputs"])')" = 0

# The figures carry the contents: a text chunk of the PNGs, the PDF's Subject.
check "panels PNG holds the contents" grep -qa "alpha = 80" "$dir/a/contact_panels.png"
check "frame PNG holds the contents" grep -qa "slopes = 0, 0.01, 0.02, 0.04, 0.08, 0.16" "$dir/a/frames/contact_0000.png"
pdf_subject() { python3 -c 'import re, sys
hexes = re.search(rb"/Subject <FEFF([0-9A-F]*)>", open(sys.argv[1], "rb").read()).group(1)
print(bytes.fromhex(hexes.decode()).decode("utf-16-be"))' "$1"; }
check "panels PDF holds the contents" bash -c "$(declare -f pdf_subject); pdf_subject '$dir/a/contact_panels.pdf' | grep -x 'alpha = 80' >/dev/null"

# Every figure a scene writes carries the record: fig1, fig2, fig3, fig5-7, the panels, the contact
# density, the distributions and every frame (contact, height, 3-D), PNG and PDF alike (figure_texts.py
# reads their text chunks and information dictionaries).
version=$("$cli" --version | cut -d' ' -f2)
cat >"$dir/every.ini" <<'INI'
[scene]
name = every
[surfaces]
n = 64
hurst = 0.8
lambda_s = 4
lambda_r = 64
slopes = 0, 0.08
seeds = 1, 2
[punch]
alpha = 80
[loading]
control = load
load_star = 580
steps = 100:580:4
[output]
table = yes
contact_panels = yes
frames = yes
frames3d = yes
frame3d_width = 320
frame3d_height = 180
frame_count = 2
distributions = yes
plots = fig1, fig2, fig3, fig5, fig6, fig7, density
INI
"$cli" run --quiet --no-wisdom "$dir/every.ini" --out "$dir/every" >/dev/null 2>&1
check "every figure of a scene carries its contents, version and inputs" python3 "$(dirname "$0")/figure_texts.py" \
  "$dir/every" "Scene contents=alpha = 80" "Scene contents=plots = fig1, fig2, fig3, fig5, fig6, fig7, density" \
  "Software=indentmap $version" "Source=$dir/every.ini" "Inputs=none"

# Edited afterwards, the scene file solves something else; its record still makes the same results.
sed -i 's/^alpha = 80/alpha = 70/' "$dir/fig4.ini"
"$cli" run --quiet --no-wisdom "$dir/fig4.ini" --out "$dir/edited" >/dev/null 2>&1
check "the edited scene's results differ" bash -c "! cmp -s '$dir/a/results.csv' '$dir/edited/results.csv'"
"$cli" run --quiet --from-record "$dir/a/run.json" --out "$dir/b" >"$dir/log" 2>&1
check "--from-record runs" test $? -eq 0
check "--from-record remakes results.csv byte for byte" cmp "$dir/a/results.csv" "$dir/b/results.csv"
check "--from-record remakes the panels' forces" cmp "$dir/a/panels/force_05.npy" "$dir/b/panels/force_05.npy"
check "the new record names the one it came from" test "$(record_value "$dir/b/run.json" 'd["from_record"]')" = "$dir/a/run.json"
check "plans estimated as recorded" test "$(record_value "$dir/b/run.json" 'd["solver"]["fftw_wisdom"]')" = False
check "the new record has the same contents" \
  test "$(record_value "$dir/b/run.json" 'd["scene_contents"]')" = "$(record_value "$dir/a/run.json" 'd["scene_contents"]')"

# Refused, exit 2, naming the file: another version, a record without contents, not a record.
sed 's/"version": "[^"]*"/"version": "0.0.9"/' "$dir/a/run.json" >"$dir/old_version.json"
check "another version refused" expect_exit 2 "old_version.json: made by indentmap 0.0.9" \
  "$cli" run --from-record "$dir/old_version.json" --out "$dir/c"
python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); del d["scene_contents"]; json.dump(d, open(sys.argv[2], "w"))' \
  "$dir/a/run.json" "$dir/bare.json"
check "a record without contents refused" expect_exit 2 "bare.json: no scene_contents" \
  "$cli" run --from-record "$dir/bare.json" --out "$dir/c"
check "a scene file is not a record" expect_exit 2 "fig4.ini:1:" "$cli" run --from-record "$dir/fig4.ini" --out "$dir/c"
check "a record and a scene refused together" expect_exit 2 "usage" \
  "$cli" run --from-record "$dir/a/run.json" "$dir/fig4.ini"

# A scene over a surface file: its SHA-256 is recorded and checked.
"$cli" surface --n 64 --slope 0.16 --seed 2 --out "$dir/s.npy" >/dev/null
printf '[scene]\nname = files\n[surfaces]\nfile = s.npy\n[loading]\nload_star = 580\n[output]\ntable = yes\nplots = fig2\n' \
  >"$dir/files.ini"
"$cli" run --quiet --no-wisdom "$dir/files.ini" --out "$dir/f" >/dev/null 2>&1
check "the surface file's SHA-256 is recorded" \
  test "$(record_value "$dir/f/run.json" 'd["inputs"][0]["sha256"]')" = "$(sha256sum "$dir/s.npy" | cut -d' ' -f1)"
"$cli" run --quiet --from-record "$dir/f/run.json" --out "$dir/g" >/dev/null 2>&1
check "a scene over a file is made again" cmp "$dir/f/table1.csv" "$dir/g/table1.csv"
check "a scene's figures carry its input's SHA-256" python3 "$(dirname "$0")/figure_texts.py" "$dir/f" \
  "Inputs=$(sha256sum "$dir/s.npy" | cut -d' ' -f1)  $dir/s.npy"
"$cli" surface --n 64 --slope 0.16 --seed 3 --out "$dir/s.npy" >/dev/null
check "a changed input refused, naming it" expect_exit 2 "s.npy: [surfaces] file has changed since the run" \
  "$cli" run --from-record "$dir/f/run.json" --out "$dir/h"
check "nothing written for a refused record" test ! -e "$dir/h"

# indent records its input files' SHA-256 as a scene does: the surface's and --profile's are sha256sum's.
"$cli" surface --n 32 --slope 0.1 --seed 4 --out "$dir/s32.npy" >/dev/null
printf '0 0\n20 3.5\n40 7\n' >"$dir/profile.txt"
"$cli" indent "$dir/s32.npy" --punch profile --profile "$dir/profile.txt" --load 20 --out "$dir/ind" >/dev/null 2>&1
check "indent runs with a surface and a profile" test -s "$dir/ind/run.json"
check "indent's inputs: the surface's SHA-256" test "$(record_value "$dir/ind/run.json" \
  '[i["sha256"] for i in d["inputs"] if i["key"] == "surface"][0]')" = "$(sha256sum "$dir/s32.npy" | cut -d' ' -f1)"
check "indent's inputs: the profile's SHA-256" test "$(record_value "$dir/ind/run.json" \
  '[i["sha256"] for i in d["inputs"] if i["key"] == "--profile"][0]')" = "$(sha256sum "$dir/profile.txt" | cut -d' ' -f1)"
check "indent's inputs: the surface's absolute path" test "$(record_value "$dir/ind/run.json" 'd["inputs"][0]["path"]')" = "$dir/s32.npy"

# indent --from-record: the run made again from its record's arguments (paths absolute, --out apart), the
# tables byte for byte but for the solve times (history.csv's column 11, seconds), the fields too.
"$cli" indent "$dir/s32.npy" --punch profile --profile "$dir/profile.txt" --load 5:20:4 --fields --distributions \
  --out "$dir/ind2" >/dev/null 2>&1
check "indent records its arguments" test "$(record_value "$dir/ind2/run.json" '" ".join(d["arguments"])')" = \
  "--punch profile --profile $dir/profile.txt --load 5:20:4 --fields --distributions $dir/s32.npy"
(cd "$dir" && "$cli" indent --from-record ind2/run.json --out again >/dev/null 2>&1)
# indent's figures (the history, the unloading analysis, the frames) carry its command line
"$cli" indent "$dir/s32.npy" --approach 0.5,1,1.5,1,0.5 --frames --punch profile --profile "$dir/profile.txt" \
  --out "$dir/ind3" >/dev/null 2>&1
check "indent draws its history, analysis and frames" \
  test -s "$dir/ind3/history.pdf" -a -s "$dir/ind3/load_displacement.png" -a -s "$dir/ind3/frames/contact_0004.png"
check "indent --from-record runs" test $? -eq 0 -a -s "$dir/again/history.csv"
check "indent --from-record remakes history.csv but its solve times" \
  cmp <(cut -d, -f11 --complement "$dir/ind2/history.csv") <(cut -d, -f11 --complement "$dir/again/history.csv")
check "indent --from-record remakes the distribution tables" \
  bash -c "for f in '$dir'/ind2/distributions_*.csv; do cmp \"\$f\" '$dir/again/'\"\${f##*/}\" || exit 1; done"
check "indent --from-record remakes the fields" cmp "$dir/ind2/force_0004.npy" "$dir/again/force_0004.npy"
check "indent's new record names the one it came from" \
  test "$(record_value "$dir/again/run.json" 'd["from_record"]')" = ind2/run.json
check "every figure of indent carries its command, version and inputs" python3 "$(dirname "$0")/figure_texts.py" \
  "$dir/ind3" "Command=indentmap indent --approach 0.5,1,1.5,1,0.5 --frames --punch profile --profile $dir/profile.txt" \
  "Software=indentmap $version" "Inputs=$(sha256sum "$dir/s32.npy" | cut -d' ' -f1)  $dir/s32.npy"
check "indent's new record has the same arguments" \
  test "$(record_value "$dir/again/run.json" 'd["arguments"]')" = "$(record_value "$dir/ind2/run.json" 'd["arguments"]')"
check "indent --from-record takes no other options" expect_exit 2 "give only --out, --wisdom or --no-wisdom" \
  "$cli" indent --from-record "$dir/ind2/run.json" --load 3 --out "$dir/i3"
check "indent --from-record refuses a scene's record" expect_exit 2 "expected the record of an indent run" \
  "$cli" indent --from-record "$dir/a/run.json" --out "$dir/i3"
sed 's/"version": "[^"]*"/"version": "0.0.9"/' "$dir/ind2/run.json" >"$dir/indent_old.json"
check "indent --from-record refuses another version" expect_exit 2 "indent_old.json: made by indentmap 0.0.9" \
  "$cli" indent --from-record "$dir/indent_old.json" --out "$dir/i3"
old_sum=$(sha256sum "$dir/profile.txt" | cut -d' ' -f1)
printf '0 0\n20 3.5\n40 7.5\n' >"$dir/profile.txt"
new_sum=$(sha256sum "$dir/profile.txt" | cut -d' ' -f1)
check "indent --from-record refuses a changed input, naming it and both checksums" expect_exit 2 \
  "$dir/profile.txt: --profile has changed since the run: its SHA-256 is $new_sum, the record $dir/ind2/run.json says $old_sum" \
  "$cli" indent --from-record "$dir/ind2/run.json" --out "$dir/i3"
check "nothing written for a refused indent record" test ! -e "$dir/i3"


# render's figures carry the command line as given, where it ran and their inputs' SHA-256 (they carried
# the input's path only): contact panels (PNG, PDF), a height map with --contact, the animation's frames
# and the 3-D view; the recorded command, run again where it ran, remakes the figure byte for byte.
here=$(cd "$dir" && pwd -P)
sum_of() { echo "$(sha256sum "$1" | cut -d' ' -f1)  $here/$2"; }
mkdir -p "$dir/r"
(cd "$dir" && "$cli" render contact ind2/force_0004.npy ind2/force_0002.npy --titles "N = 20,N = 10" \
  --out "r/contact map.png" && "$cli" render contact ind2/force_0004.npy --out r/contact.pdf &&
  "$cli" render height s32.npy --contact ind2/force_0004.npy --out r/height.png &&
  "$cli" render animate ind2/force_0002.npy ind2/force_0004.npy --frames r/frames &&
  "$cli" render view3d s32.npy --force ind2/force_0004.npy --width 160 --height 120 --out r/view3d.png) \
  >"$dir/render.log" 2>&1
check "render draws contact, height, animation frames and the 3-D view" test $? -eq 0
texts() { python3 "$(dirname "$0")/figure_texts.py" "$@"; }
check "render contact records its command, where it ran and both inputs" texts "$dir/r/contact map.png" \
  "Command=indentmap render contact ind2/force_0004.npy ind2/force_0002.npy --titles 'N = 20,N = 10' --out 'r/contact map.png'" \
  "Directory=$here" "Software=indentmap $version" "Inputs=$(sum_of "$dir/ind2/force_0004.npy" ind2/force_0004.npy)" \
  "Inputs=$(sum_of "$dir/ind2/force_0002.npy" ind2/force_0002.npy)"
check "as PDF" texts "$dir/r/contact.pdf" "Command=indentmap render contact ind2/force_0004.npy --out r/contact.pdf" \
  "Directory=$here" "Inputs=$(sum_of "$dir/ind2/force_0004.npy" ind2/force_0004.npy)"
check "render height records the surface and --contact" texts "$dir/r/height.png" \
  "Command=indentmap render height s32.npy --contact ind2/force_0004.npy --out r/height.png" \
  "Inputs=$(sum_of "$dir/s32.npy" s32.npy)" "Inputs=$(sum_of "$dir/ind2/force_0004.npy" ind2/force_0004.npy)"
check "every frame of render animate records the command and every input" texts "$dir/r/frames" \
  "Command=indentmap render animate ind2/force_0002.npy ind2/force_0004.npy --frames r/frames" \
  "Inputs=$(sum_of "$dir/ind2/force_0002.npy" ind2/force_0002.npy)" \
  "Inputs=$(sum_of "$dir/ind2/force_0004.npy" ind2/force_0004.npy)"
check "render view3d records its command and inputs" texts "$dir/r/view3d.png" \
  "Command=indentmap render view3d s32.npy --force ind2/force_0004.npy --width 160 --height 120 --out r/view3d.png" \
  "Directory=$here" "Inputs=$(sum_of "$dir/s32.npy" s32.npy)"
remake() { python3 -c 'import sys; sys.path.insert(0, sys.argv[1]); from figure_texts import png_texts
t = png_texts(sys.argv[2]); print(t["Directory"]); print(t["Command"])' "$(dirname "$0")" "$1"; }
for figure in "contact map.png" view3d.png; do
  { read -r where; read -r command; } < <(remake "$dir/r/$figure")
  mv "$dir/r/$figure" "$dir/first.png"
  check "$figure made again from its record" bash -c "cd '$where' && eval '\"$cli\"'\"\${1#indentmap}\" >/dev/null 2>&1 &&
    cmp '$dir/first.png' 'r/$figure'" _ "$command"
done

finish
