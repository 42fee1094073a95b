#!/usr/bin/env bash
# A disk that fills up during a run: the ensemble of tests/cli_interrupt.sh writes into a 2 MiB
# tmpfs (mounted in a private mount namespace; skipped, 77, where mounts are not allowed), which
# another file fills as soon as the first table member is on disk. The run must stop with a clear
# "No space left on device" error naming the file, exit 1, leave no temporary file and no lock;
# once space is freed, --resume must finish with the table of a run that was never disturbed.
# Also: `indentmap indent --fields` past a file-size limit (ulimit -f) fails cleanly, naming the
# step whose file failed; `render animate` onto a full disk names the frame and the reason.
set -u
cli=$1
if [ -z "${IM_PRIVATE_MOUNTS:-}" ]; then
  unshare -m true 2>/dev/null || { echo "SKIPPED: no private mount namespace (unshare -m)"; exit 77; }
  IM_PRIVATE_MOUNTS=1 exec unshare -m bash "$0" "$@"
fi
dir=$(mktemp -d)
trap 'kill "$pid" 2>/dev/null; umount "$dir/tiny" 2>/dev/null; rm -rf "$dir"' EXIT
pid=
source "$(dirname "$0")/lib.sh"
export OMP_NUM_THREADS=2
mkdir "$dir/tiny"
mount -t tmpfs -o size=2m tmpfs "$dir/tiny" 2>/dev/null || { echo "SKIPPED: cannot mount a tmpfs"; exit 77; }

scene() { ensemble_scene "$1" disk "$2"; }
scene "$dir/whole.ini" "$dir/whole"
scene "$dir/tiny.ini" "$dir/tiny/out"
"$cli" run --quiet "$dir/whole.ini" >/dev/null 2>&1
check "undisturbed run" test $? -eq 0

"$cli" run --quiet "$dir/tiny.ini" >/dev/null 2>"$dir/full.log" &
pid=$!
for _ in $(seq 1200); do compgen -G "$dir/tiny/out/table/member_*.csv" >/dev/null && break; sleep 0.01; done
dd if=/dev/zero of="$dir/tiny/filler" bs=64k 2>/dev/null
wait "$pid"
check "full disk: exit 1" test $? -eq 1
pid=
check "full disk: clear message" grep -q "write failed: No space left on device\|cannot open for writing: No space left on device" "$dir/full.log"
check "full disk: no temporary file" bash -c "! find '$dir/tiny' -name '*.tmp.*' | grep -q ."
check "full disk: no lock left" test ! -e "$dir/tiny/out/.lock"
check "full disk: kept members are whole" bash -c "for f in '$dir'/tiny/out/table/member_*.csv; do [ \$(wc -l <\"\$f\") -eq 2 ] || exit 1; done"
# The record written as the run started ("running") is not left behind when its end cannot be written on the
# full disk, and the message says so (the scene's record once kept "running" without a word).
check "full disk: no run.json left saying running" bash -c "! grep -qs '\"running\"' '$dir/tiny/out/run.json'"
check "full disk: the record not written is said" grep -q "run.json was not written either" "$dir/full.log"

rm "$dir/tiny/filler"
"$cli" run --quiet --resume "$dir/tiny.ini" >/dev/null 2>"$dir/resume.log"
check "resume after freeing space" test $? -eq 0
check "table1.csv as undisturbed" cmp "$dir/whole/table1.csv" "$dir/tiny/out/table1.csv"
for f in "$dir"/whole/histories/*.csv; do
  check "$(basename "$f") as undisturbed" cmp -s <(history_rows "$f") <(history_rows "$dir/tiny/out/histories/$(basename "$f")")
done

# indent's disk estimate leaves the file-size limit out: its field files fail there, with EFBIG, cleanly.
(ulimit -f 100; "$cli" indent --smooth --n 256 --approach 1:5:3 --fields --out "$dir/indent" >/dev/null 2>"$dir/indent.log"
 echo $? >"$dir/indent.status")
check "file-size limit: exit 1" test "$(cat "$dir/indent.status")" -eq 1
check "file-size limit: message" grep -q "force_0001.npy: write failed: File too large" "$dir/indent.log"
check "file-size limit: no temporary file" bash -c "! find '$dir/indent' -name '*.tmp.*' | grep -q ."
check "file-size limit: the failing step is named (step 1, not 2)" grep -q "step 1 of 3 (approach 1; no step before it was solved)" "$dir/indent.log"

# render animate onto a full disk: the frame named, with errno's reason (not libpng's bare "Write Error")
"$cli" indent --smooth --n 64 --approach 1:2:2 --fields --out "$dir/fields" >/dev/null || exit 1
dd if=/dev/zero of="$dir/tiny/filler" bs=64k 2>/dev/null
"$cli" render animate "$dir"/fields/force_000{1,2}.npy --frames "$dir/tiny/frames" >/dev/null 2>"$dir/animate.log"
check "animate, full disk: exit 1" test $? -eq 1
check "animate, full disk: the frame and the reason" \
  grep -q "frames/contact_0000.png: write failed: No space left on device" "$dir/animate.log"
check "animate, full disk: no libpng message" bash -c "! grep -q libpng '$dir/animate.log'"
check "animate, full disk: no temporary file" bash -c "! find '$dir/tiny' -name '*.tmp.*' | grep -q ."

# indent --fields whose step files would not fit on the disk: refused before any step, with the estimate,
# writing nothing (it solved and wrote steps until the disk was full: at 4096^2, 384 MiB a step, hours
# in). The estimate is an upper bound of what a step writes: the first step's files of the same run on
# a disk with room (printed to 0.01 MiB), and within 10% of it.
rm -rf "$dir/tiny/filler" "$dir/tiny/frames" "$dir/tiny/out"
"$cli" surface --n 128 --seed 1 --out "$dir/s128.npy" >/dev/null
"$cli" indent "$dir/s128.npy" --approach 0.5:6:40 --fields --out "$dir/tiny/indent" >"$dir/indent_est.out" \
  2>"$dir/indent_est.log"
check "indent, too little disk: exit 1" test $? -eq 1
check "indent, too little disk: the estimate and the free disk named" grep -q \
  "^indentmap: --fields: the 40 steps' files of the 128 x 128 surface need about [0-9.]* MiB of disk ([0-9.]* MiB a step) but $dir/tiny/indent has only 2.0 MiB free; refused before any step was solved" \
  "$dir/indent_est.log"
check "indent, too little disk: no step solved, nothing written" \
  bash -c "test ! -s '$dir/indent_est.out' && test ! -e '$dir/tiny/indent'"
"$cli" indent "$dir/s128.npy" --approach 0.5 --fields --out "$dir/one_step" >/dev/null 2>&1
written=$(cat "$dir"/one_step/*_0001.npy* | wc -c)
per_step=$(sed -n 's/.*MiB of disk (\([0-9.]*\) MiB a step).*/\1/p' "$dir/indent_est.log")
check "indent, too little disk: a step's estimate ($per_step MiB) >= what a step writes ($written bytes)" \
  awk -v e="$per_step" -v w="$written" 'BEGIN { m = w / 1048576; exit !(m > 0 && e + 0.005 >= m && e - 0.005 < 1.1 * m) }'

# indent --fields onto a disk that fills mid-run (reliability finding 13), the estimate skipped: the step
# and the history are named, and so is the record that could not be written after them (run.json was
# gone, unsaid).
IM_NO_SPACE_CHECK=1 "$cli" indent "$dir/s128.npy" --approach 0.5:6:40 --fields --out "$dir/tiny/indent" \
  >/dev/null 2>"$dir/indent_full.log"
check "indent, full disk: exit 1" test $? -eq 1
check "indent, full disk: the step and the history named" grep -Eq "(steps before are|step before is) in .*history.csv" "$dir/indent_full.log"
# A run.json left is the finished one, never the start record ("running", written as the steps start).
check "indent, full disk: a run.json not written is said, none left saying running" \
  bash -c "if test -e '$dir/tiny/indent/run.json'; then ! grep -q '\"running\"' '$dir/tiny/indent/run.json'; else grep -q 'run.json was not written either' '$dir/indent_full.log'; fi"

# render's vector figures onto a full disk (reliability row 154): the reason, as for PNG (an SVG said
# only cairo's "error while writing to output stream").
rm -rf "$dir/tiny/indent"
dd if=/dev/zero of="$dir/tiny/filler" bs=4k 2>/dev/null
for format in pdf svg; do
  "$cli" render contact "$dir/fields/force_0002.npy" --out "$dir/tiny/r.$format" >/dev/null 2>"$dir/render.log"
  check "render .$format, full disk: exit 1" test $? -eq 1
  check "render .$format, full disk: the file and the reason" grep -q "r.$format: write failed: No space left on device" "$dir/render.log"
done

finish
