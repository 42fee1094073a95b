#!/usr/bin/env bash
# --resume never reuses what no longer matches, and a damaged output is made again, not fatal
# (issue 32; the cases of ../shared/findings/reliability.md, defects 2, 5, 7 and 16, row 144): each
# case runs a small scene (64 x 64, two slopes x three seeds, table, fig7, panels, frames), damages
# or edits it, resumes, and compares with a fresh run of the scene as resumed (--no-wisdom: FFTW's
# estimated plans, so that two runs agree to the bit). Exit 77 (skipped) without an OpenGL context.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
require_renderer "$cli"

# scene FILE OUTPUT [KEY = VALUE...]: the scene of the probe (its sc7/ref.ini, 6 frames), edited.
scene() {
  local file=$1 out=$2
  shift 2
  cat >"$file" <<INI
[scene]
name = ref
output = $out
[surfaces]
n = 64
hurst = 0.8
lambda_s = 4
slopes = 0.04, 0.16
seeds = 1:3
[punch]
shape = cone
alpha = 80
[loading]
load_star = 600
control = load
steps = 100:600:4
[output]
table = yes
plots = fig7
contact_panels = yes
frames = yes
frame_count = 6
INI
  local line # an edit of a key the scene has, or a key added to [output]
  for line in "$@"; do
    if grep -q "^${line%% =*} = " "$file"; then sed -i "s/^${line%% =*} = .*/$line/" "$file"; else echo "$line" >>"$file"; fi
  done
}

run() { "$cli" run --quiet --no-wisdom "$@" >/dev/null 2>>"$dir/log"; }

# fresh NAME [EDITS...]: a fresh run of the scene (with the edits) into $dir/NAME.
fresh() {
  local name=$1
  shift
  scene "$dir/$name.ini" "$dir/$name" "$@"
  run "$dir/$name.ini"
}

# resumed NAME [EDITS...]: a copy of the reference run resumed with the edits; exit status in $resumed.
resumed() {
  local name=$1
  shift
  rm -rf "$dir/$name"
  cp -r "$dir/ref" "$dir/$name"
  [ -n "${damage:-}" ] && (cd "$dir/$name" && eval "$damage")
  scene "$dir/$name.ini" "$dir/$name" "$@"
  : >"$dir/log"
  run --resume "$dir/$name.ini"
  resumed=$?
}

same_results() { cmp "$dir/$1/table1.csv" "$dir/$2/table1.csv" && cmp "$dir/$1/results.csv" "$dir/$2/results.csv"; }
notice() { grep -qF -- "$1" "$dir/log" || { echo "no notice '$1' in: $(cat "$dir/log")"; return 1; }; }

fresh ref
check "reference run" test -f "$dir/ref/table1.csv"

# defect 2: a changed digit in a kept member, a flipped byte in a kept panel force
damage="sed -i '2s/,0\.76166/,0.96166/' table/member_01_2.csv" resumed d2_member
check "2 member: exit 0" test "$resumed" -eq 0
check "2 member: named" notice "member_01_2.csv is damaged (its row does not match its checksum"
check "2 member: table as fresh" same_results d2_member ref
damage="printf A | dd of=panels/force_00.npy bs=1 seek=3000 conv=notrunc 2>/dev/null" resumed d2_panel
check "2 panel: named" notice "force_00.npy is damaged (its values do not match the checksum"
check "2 panel: force as fresh" cmp "$dir/d2_panel/panels/force_00.npy" "$dir/ref/panels/force_00.npy"

# defect 16: frames_slope edited: the old framed panel is not the table's state a fresh run takes
fresh f16 "frames_slope = 0.04"
damage="" resumed d16 "frames_slope = 0.04"
check "16 frames_slope: named" notice "force_01.npy was made from other inputs"
check "16 frames_slope: results as fresh" same_results d16 f16
check "16 frames_slope: force as fresh" cmp "$dir/d16/panels/force_01.npy" "$dir/f16/panels/force_01.npy"

# defect 5: fewer frames, fewer seeds: what the scene no longer makes is removed
damage="" resumed d5_frames "frame_count = 3"
check "5 frames: stale frames removed" test ! -e "$dir/d5_frames/frames/contact_0003.png" -a \
  ! -e "$dir/d5_frames/frames/height_0005.png" -a -e "$dir/d5_frames/frames/contact_0002.png"
check "5 frames: named" notice "that this scene no longer makes"
damage="" resumed d5_seeds "seeds = 1:2"
check "5 seeds: dropped members removed" test ! -e "$dir/d5_seeds/table/member_00_3.csv" -a \
  ! -e "$dir/d5_seeds/histories/member_01_3.csv" -a -e "$dir/d5_seeds/table/member_01_2.csv"
# defect 5: scene B (table only, slope 0.08) run into A's finished folder, without --resume
rm -rf "$dir/d5_b"
cp -r "$dir/ref" "$dir/d5_b"
scene "$dir/b.ini" "$dir/d5_b" "slopes = 0.08" "plots = fig2" "contact_panels = no" "frames = no"
run "$dir/b.ini"
check "5 scene B: exit 0" test $? -eq 0
check "5 scene B: A's outputs removed" test ! -e "$dir/d5_b/fig7.png" -a ! -e "$dir/d5_b/contact_panels.png" -a \
  ! -e "$dir/d5_b/frames" -a ! -e "$dir/d5_b/panels" -a ! -e "$dir/d5_b/histories/member_01_1.csv"
check "5 scene B: its own table" test -f "$dir/d5_b/table1.csv" -a -f "$dir/d5_b/fig2.png"

# defect 7 and row 144: random bytes in a kept output: made again, exit 0, with a notice
for f in table/member_00_3.csv table/member_01_2.csv fig7.png fig7.pdf contact_panels.png frames/contact_0002.png \
         index.html table1.csv table1.md panels/force_01.npy run.json histories/member_00_1.csv; do
  name=d7_$(echo "$f" | tr '/.' '__')
  damage="{ printf 'x\0'; head -c 300 /dev/urandom; } > $f" resumed "$name"
  check "7 $f: exit 0" test "$resumed" -eq 0
  check "7 $f: made again" test -s "$dir/$name/$f"
  check "7 $f: table as fresh" same_results "$name" ref
done
check "7 fig7.png is a PNG again" bash -c "head -c 4 '$dir/d7_fig7_png/fig7.png' | grep -q PNG"
check "7 run.json is JSON again" bash -c "head -c 1 '$dir/d7_run_json/run.json' | grep -q '{'"

# inputs stay protected: a damaged surface file is still an error
head -c 300 /dev/urandom >"$dir/bad.npy"
printf '[scene]\nname = in\noutput = %s\n[surfaces]\nfile = %s\n[punch]\nshape = cone\nalpha = 80\n[loading]\nload_star = 60\n[output]\ntable = yes\n' \
  "$dir/in" "$dir/bad.npy" >"$dir/in.ini"
check "damaged input: an error" bash -c "! '$cli' run --quiet '$dir/in.ini' 2>/dev/null"

finish
