#!/usr/bin/env bash
# FFTW wisdom kept in the user's cache (docs/solver.md): written to $XDG_CACHE_HOME/indentmap/fftw-wisdom
# by default and reused by the next run (the same file, the same answers); a damaged file gives a notice
# and the run goes on (and mends it); --no-wisdom and IM_FFTW_WISDOM="" keep none. Every run here has
# XDG_CACHE_HOME in a temporary folder: the real ~/.cache is never touched.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
export OMP_NUM_THREADS=1
unset IM_FFTW_WISDOM # ctest turns wisdom off for every test; this one is about it
export HOME="$dir/home" XDG_CACHE_HOME="$dir/cache"
cd "$dir" || exit 1
wisdom=$dir/cache/indentmap/fftw-wisdom

"$cli" surface --n 48 --seed 2 --out s.npy >/dev/null || exit 1
export steps=0.1:1:10 # the cache is the default from 10 steps on
indent() { "$cli" indent s.npy --approach $steps --out "$@" >/dev/null; }
answers() { cut -d, -f1-10 "$1/history.csv"; } # all but the timings
is_wisdom() { [ -s "$1" ] && head -c 6 "$1" | grep -q '(fftw-'; }
measured() { grep -q '"fftw_measure": true' "$1/run.json" && grep -q '"fftw_wisdom": true' "$1/run.json"; }
unmeasured() { grep -q '"fftw_measure": false' "$1/run.json" && grep -q '"fftw_wisdom": false' "$1/run.json"; }

# the default: the cache's file is written, and the plans are measured
check "default: wisdom written to \$XDG_CACHE_HOME/indentmap" bash -c "$(declare -f indent is_wisdom); cli='$cli'; indent o1 && is_wisdom '$wisdom'"
check "default: the run's plans are measured" measured o1
check "fewer than 10 steps: no wisdom by default" bash -c "'$cli' indent s.npy --approach 0.5 --out short >/dev/null && grep -q '\"fftw_wisdom\": false' short/run.json"
cp "$wisdom" first.wisdom
# the second run imports it: nothing new to measure (the file is the same), the same plans (the same answers)
check "second run: succeeds" indent o2
check "second run: the same wisdom, nothing measured anew" cmp -s <(sort first.wisdom) <(sort "$wisdom") # (FFTW's order varies)
check "second run: the same answers as the first" cmp -s <(answers o1) <(answers o2)
# without XDG_CACHE_HOME, ~/.cache (here a temporary HOME)
check "no XDG_CACHE_HOME: ~/.cache/indentmap" bash -c "$(declare -f indent is_wisdom); cli='$cli'; unset XDG_CACHE_HOME; indent o3 && is_wisdom '$dir/home/.cache/indentmap/fftw-wisdom'"

# a damaged file: FFTW rejects it; notice, the run succeeds, and the file is wisdom again
head -c 200 first.wisdom >"$wisdom"
check "truncated wisdom: a notice" expect_exit 0 "FFTW rejects it" "$cli" indent s.npy --approach $steps --out o4
check "truncated wisdom: replaced by whole wisdom" is_wisdom "$wisdom"
printf 'not wisdom at all\n' >"$wisdom"
check "foreign file in the cache: a notice" expect_exit 0 "not FFTW wisdom" "$cli" indent s.npy --approach $steps --out o5
check "foreign file in the cache: replaced by wisdom" is_wisdom "$wisdom"

# the off switches: no file is written, nothing is measured
rm -rf "$dir/cache"
check "--no-wisdom: succeeds" indent o6 --no-wisdom
check "--no-wisdom: no file" test ! -e "$wisdom"
check "--no-wisdom: estimated plans" unmeasured o6
check "IM_FFTW_WISDOM=\"\": succeeds" env IM_FFTW_WISDOM= "$cli" indent s.npy --approach $steps --out o7
check "IM_FFTW_WISDOM=\"\": no file" test ! -e "$wisdom"
check "IM_FFTW_WISDOM=\"\": estimated plans" unmeasured o7
check "IM_FFTW_WISDOM=FILE: that file instead" bash -c "IM_FFTW_WISDOM='$dir/mine.wisdom' '$cli' indent s.npy --approach 0.4 --out o8 >/dev/null && test ! -e '$wisdom' && head -c 6 '$dir/mine.wisdom' | grep -q '(fftw-'"

# a scene: the cache is used too, and --no-wisdom switches it off
printf '[scene]\noutput = sc\n[surfaces]\nfile = s.npy\n[loading]\nsteps = 0.4, 0.8\n[output]\nplots = fig5\n' >scene.ini
check "run --no-wisdom: no file" bash -c "'$cli' run scene.ini --quiet --no-wisdom >/dev/null && test ! -e '$wisdom'"
rm -rf sc
check "run: wisdom written to the cache" bash -c "'$cli' run scene.ini --quiet >/dev/null && head -c 6 '$wisdom' | grep -q '(fftw-'"

# --resume keeps a scene's results only while their plans can be had: wisdom kept, they are read back;
# wisdom removed (it is then measured anew) or plans estimated instead, everything is solved again with
# a notice, and the outputs are then a fresh run's with the same wisdom, byte for byte.
resume() { "$cli" run --resume scene.ini "$@" >/dev/null 2>resume.err; }
check "resume, the same wisdom: succeeds" resume
check "resume, the same wisdom: read back" grep -q "0 solved, 1 read back" resume.err
check "resume, the same wisdom: no notice" bash -c "! grep -q 'other FFTW plans' resume.err"
rm "$wisdom"
check "resume, wisdom removed: succeeds" resume
check "resume, wisdom removed: a notice" grep -q "sc/fftw-plans.txt: the kept results were solved with other FFTW plans than this run's (the wisdom file no longer holds every plan" resume.err
check "resume, wisdom removed: solved again" grep -q "1 solved, 0 read back" resume.err
sed 's/^output = sc$/output = fresh/' scene.ini >fresh.ini
"$cli" run --quiet fresh.ini >/dev/null
for f in fresh/histories/*.csv; do
  check "resume, wisdom removed: $(basename "$f") as a fresh run's" cmp -s <(history_rows "$f") <(history_rows "sc/histories/$(basename "$f")")
done
check "resume, estimated plans after measured: succeeds" resume --no-wisdom
check "resume, estimated plans after measured: a notice" grep -q "they were measured with FFTW wisdom, and this run estimates its plans" resume.err
check "resume, estimated plans after measured: solved again" grep -q "1 solved, 0 read back" resume.err
finish
