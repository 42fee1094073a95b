#!/usr/bin/env bash
# Limits checked before any work: memory and disk estimates against the machine (a grid no machine
# holds; a file-size limit; a 1 MiB tmpfs when mounts are allowed), scene consistency (N* whose
# smooth contact leaves the surface), paths relative to the scene file, and output folders that
# would hold an input. Each refusal must name what it refuses and create no output folder.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"

# scene NAME N LOAD_STAR [more [output] lines]: a table scene writing to out_NAME.
scene() {
  local name=$1 n=$2 load_star=$3 extra=${4:-}
  cat >"$dir/$name.ini" <<INI
[scene]
name = $name
output = out_$name
[surfaces]
n = $n
slopes = 0.08
seeds = 1:2
[punch]
shape = cone
[loading]
load_star = $load_star
[output]
table = yes
$extra
INI
}
refused() { # refused NAME EXIT PATTERN: runs the scene, expects the exit status and message, no output
  "$cli" run --quiet "$dir/$1.ini" >/dev/null 2>"$dir/$1.err"
  local status=$?
  check "$1: exit $2" test $status -eq "$2"
  check "$1: message" grep -q "$3" "$dir/$1.err"
  check "$1: no output folder" test ! -e "$dir/out_$1"
}

# Memory: a 65536 x 65536 grid's solver plan alone is about 800 GB.
scene memory 65536 1000
refused memory 2 "memory.ini: this scene needs about [0-9.]* MiB of memory (.* 65536 x 65536 grid"

# Disk, per file: the panels' figure of a 512 x 512 family against a 1 MiB file-size limit.
scene fsize 512 1000 "contact_panels = yes"
(ulimit -f 1024; "$cli" run --quiet "$dir/fsize.ini" >/dev/null 2>"$dir/fsize.err"; echo $? >"$dir/fsize.status")
check "file-size limit: exit 1" test "$(cat "$dir/fsize.status")" -eq 1
check "file-size limit: message" grep -q "contact_panels.png would be about [0-9.]* MiB but the file-size limit (ulimit -f) is 1.0 MiB" "$dir/fsize.err"
check "file-size limit: no output folder" test ! -e "$dir/out_fsize"

# Disk, in all: frames of a 256 x 256 history into a 1 MiB file system (needs mount rights).
scene disk 256 1000 "frames = yes"
mkdir "$dir/tiny"
if unshare -m true 2>/dev/null && unshare -m sh -c "mount -t tmpfs -o size=1m tmpfs '$dir/tiny'" 2>/dev/null; then
  sed -i "s|^output = .*|output = $dir/tiny/out|" "$dir/disk.ini"
  unshare -m sh -c "mount -t tmpfs -o size=1m tmpfs '$dir/tiny' && '$cli' run --quiet '$dir/disk.ini' 2>'$dir/disk.err'; echo \$? >'$dir/disk.status'"
  check "disk: exit 1" test "$(cat "$dir/disk.status")" -eq 1
  check "disk: message" grep -q "the outputs need about [0-9.]* MiB of disk (the largest, .*) but $dir/tiny has only 1.0 MiB free" "$dir/disk.err"
  # The estimate is an honest upper bound (it was 16.4 MiB for the 1.3 MiB of this scene, refused on a
  # 20 MB disk), and IM_NO_SPACE_CHECK=1 overrides it: a scene of table, fig7, panels and 16 frames.
  cat >"$dir/fits.ini" <<INI
[scene]
name = fits
output = $dir/tiny/out
[surfaces]
n = 128
slopes = 0.04, 0.16
seeds = 1:4
[punch]
shape = cone
alpha = 80
[loading]
load_star = 2400
control = load
steps = 300:2400:8
[output]
table = yes
plots = fig7
contact_panels = yes
frames = yes
frame_count = 16
INI
  in_tmpfs() { # in_tmpfs SIZE COMMAND: COMMAND with a fresh tmpfs of SIZE at $dir/tiny
    unshare -m sh -c "mount -t tmpfs -o size=$1 tmpfs '$dir/tiny' && $2"
  }
  in_tmpfs 8m "'$cli' run --quiet '$dir/fits.ini' 2>'$dir/fits.err' && du -sb '$dir/tiny/out' | cut -f1 >'$dir/fits.bytes'"
  check "disk: the scene fits 8 MiB" test -s "$dir/fits.bytes"
  in_tmpfs 1m "'$cli' run --quiet '$dir/fits.ini' 2>'$dir/estimate.err'"
  estimate=$(sed -n 's/.*the outputs need about \([0-9.]*\) MiB of disk.*/\1/p' "$dir/estimate.err")
  check "disk: the estimate ($estimate MiB) is at least what the scene writes" \
    awk -v e="$estimate" -v b="$(cat "$dir/fits.bytes")" 'BEGIN { exit !(e != "" && e * 1048576 >= b) }'
  check "disk: the estimate is at most 4x what the scene writes" \
    awk -v e="$estimate" -v b="$(cat "$dir/fits.bytes")" 'BEGIN { exit !(e != "" && e * 1048576 <= 4 * b) }'
  check "disk: the refusal names the override" grep -q "IM_NO_SPACE_CHECK=1 runs anyway" "$dir/estimate.err"
  in_tmpfs 3m "'$cli' run --quiet '$dir/fits.ini' 2>'$dir/small.err'; echo \$? >'$dir/small.status'"
  check "disk: under the estimate: refused" test "$(cat "$dir/small.status")" -eq 1
  in_tmpfs 3m "IM_NO_SPACE_CHECK=1 '$cli' run --quiet '$dir/fits.ini' 2>'$dir/override.err'; echo \$? >'$dir/override.status'"
  check "disk: IM_NO_SPACE_CHECK=1: runs where the outputs fit" test "$(cat "$dir/override.status")" -eq 0
  [ "$(cat "$dir/override.status")" -eq 0 ] || sed 's/^/  stderr: /' "$dir/override.err"
else
  echo "note: cannot mount a tmpfs here: the free-space check is not exercised"
fi

# Consistency: at N* = 4000 the smooth contact radius (35.7 patches) exceeds half of 64.
scene wide 64 4000
refused wide 2 "wide.ini: \[loading\] load_star = 4000: the smooth contact radius sqrt(N\*/pi) = 35.7 patches reaches the edge of the 64 x 64 surface"
scene steps 64 600 "plots = fig5"
sed -i 's/^\[loading\]$/[loading]\ncontrol = load\nsteps = 100:5000:3/' "$dir/steps.ini"
refused steps 2 "\[loading\] steps (largest) = 5000"

# Outputs never hold inputs: the scene's own folder, or the folder of its surface file.
scene here 64 600
sed -i "s|^output = .*|output = .|" "$dir/here.ini"
"$cli" run --quiet "$dir/here.ini" >/dev/null 2>"$dir/here.err"
check "output holding the scene: exit 2" test $? -eq 2
check "output holding the scene: message" grep -q "output = $dir/. would hold the scene file" "$dir/here.err"
mkdir "$dir/inputs"
"$cli" surface --n 64 --slope 0.08 --seed 3 --out "$dir/inputs/rough.npy" >/dev/null
cat >"$dir/file.ini" <<INI
[scene]
name = file
output = inputs
[surfaces]
file = inputs/rough.npy
[loading]
load_star = 600
[output]
table = yes
INI
"$cli" run --quiet "$dir/file.ini" >/dev/null 2>"$dir/file.err"
check "output holding the surface file: exit 2" test $? -eq 2
check "output holding the surface file: message" grep -q "would hold the surface file $dir/inputs/rough.npy" "$dir/file.err"
cmp -s <("$cli" surface --n 64 --slope 0.08 --seed 3 --out "$dir/again.npy" >/dev/null; cat "$dir/again.npy") "$dir/inputs/rough.npy"
check "surface file untouched" test $? -eq 0

# Paths relative to the scene file, whatever the working directory.
sed -i "s|^output = .*|output = results|" "$dir/file.ini"
(cd / && "$cli" run --quiet "$dir/file.ini" >/dev/null 2>"$dir/relative.err")
check "relative paths: runs from /" test $? -eq 0
check "relative paths: output beside the scene" test -s "$dir/results/table1.csv"
# the table's mean h_rms is the file's (issue 13; its h'rms is the spectral target 0.08, the default's too)
h_rms=$("$cli" surface --stats "$dir/inputs/rough.npy" --detrend none --window none | awk '/^h_rms / { print $2 }')
check "relative paths: the surface file was read" grep -q "^0.08,1,$h_rms," "$dir/results/table1.csv"

# cpu_scene NAME SURFACES LOADING OUTPUT: a scene on the CPU engine writing to out_NAME, its sections' lines
# given ('\n' between them)
cpu_scene() {
  printf '[scene]\nname = %s\noutput = out_%s\n[surfaces]\n%b\n[loading]\n%b\n[solver]\ndevice = cpu\n[output]\n%b\n' \
    "$1" "$1" "$2" "$3" "$4" >"$dir/$1.ini"
}
# A history stepping in boxes of its window (displacement control, CPU) holds each box's plans beside the
# window's: the estimate counts them. The run's peak resident memory beyond a tiny scene's (the program
# and its libraries, which the estimate leaves out) stays within the estimate (102 MiB against 75.3 MiB
# counted before the boxes were, 206 MiB now); one thread, so one solve.
boxes() { cpu_scene "$1" "n = $2\nslopes = 0\nseeds = 1" "steps = $3" "plots = fig5"; }
peak_kib() {
  OMP_NUM_THREADS=1 python3 -c 'import resource, subprocess, sys
subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)' "$@"
}
# framed NAME N LOAD_STAR: a frame history on a synthesized file (so that the estimate knows the window, a
# small one at a small load) that draws each frame's displacement on the whole grid: its convolution's plan
# (im_indentation_fields_full) beside the window's solver. Before it was counted, 1024^2 held 168 MiB
# beyond a tiny frame history against 143 MiB counted.
framed() {
  "$cli" surface --n "$2" --slope 0.08 --seed 1 --out "$dir/$1.npy" >/dev/null 2>&1
  cpu_scene "$1" "n = $2\nfile = $1.npy" "control = load\nload_star = $3" "frames = yes\nframe_count = 2"
}
boxes tiny 64 1:2:2
boxes steps 512 30:52:2
framed tiny_frames 64 300
framed frames 1024 3000
estimate_of() { # the scene's memory estimate in MiB, from its refusal under a limit below it
  OMP_NUM_THREADS=1 IM_MEMORY_LIMIT_MIB=$2 "$cli" run --quiet "$dir/$1.ini" 2>&1 |
    sed -n 's/.*this scene needs about \([0-9.]*\) MiB of memory.*/\1/p'
}
estimate=$(estimate_of steps 1)
frames_estimate=$(estimate_of frames 20) # 20 MiB: the 8 MiB file is read before the scene's estimate
if ldd "$cli" 2>/dev/null | grep -q "libasan"; then
  # AddressSanitizer's shadow memory and quarantine are resident too (329 MiB held against 206 counted):
  # the peak says nothing about the program's own memory there; the estimates must still be stated.
  check "steps in boxes: an estimate is stated (peak not compared on a sanitizer build)" test -n "$estimate"
  check "frames: an estimate is stated (peak not compared on a sanitizer build)" test -n "$frames_estimate"
else
  held=$(( $(peak_kib "$cli" run --quiet "$dir/steps.ini") - $(peak_kib "$cli" run --quiet "$dir/tiny.ini") ))
  echo "steps in boxes: estimated $estimate MiB, held $((held / 1024)) MiB beyond a tiny scene"
  check "steps in boxes: the estimate holds the run's peak" awk -v e="$estimate" -v h="$held" 'BEGIN { exit !(e > 0 && h / 1024 <= e) }'
  # beyond a tiny frame history: the renderer's own resident memory (Mesa, LLVM) is the program's
  held=$(( $(peak_kib "$cli" run --quiet "$dir/frames.ini") - $(peak_kib "$cli" run --quiet "$dir/tiny_frames.ini") ))
  echo "frames: estimated $frames_estimate MiB, held $((held / 1024)) MiB beyond a tiny frame history"
  check "frames: the estimate holds the run's peak" \
    awk -v e="$frames_estimate" -v h="$held" 'BEGIN { exit !(e > 0 && h / 1024 <= e) }'
fi

finish
