#!/usr/bin/env bash
# A named pipe as the surface file: with no program writing to it, the first SIGTERM ends `indent` and
# `run` (they used to stay blocked in open() until a second signal), naming the file; a format that
# must be read as a file (NetCDF) refuses a pipe at once; a pipe that is written to is read as before.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
export OMP_NUM_THREADS=1
cd "$dir" || exit 1

mkfifo waiting.npy waiting.nc written.npy
cat >fifo.ini <<'INI'
[scene]
name = fifo
output = out
[surfaces]
file = waiting.npy
[punch]
shape = cone
alpha = 80
[loading]
steps = 0.5:1:2
[output]
table = yes
INI

# ends_at_one_sigterm NAME COMMAND...: SIGTERM after 2 s ends COMMAND with exit 143 and the message
# naming the pipe (a second signal, 5 s later, would end it with 137).
ends_at_one_sigterm() {
  local name=$1; shift
  timeout --preserve-status -k 5 -s TERM 2 "$@" >/dev/null 2>"$name.err"
  local got=$?
  check "$name: one SIGTERM ends it (exit $got)" test "$got" -eq 143
  check "$name: the message names the pipe" grep -q "waiting.npy is a pipe no program has written to: waiting for one interrupted by signal 15" "$name.err"
}
ends_at_one_sigterm indent "$cli" indent waiting.npy --approach 1 --out o
ends_at_one_sigterm run "$cli" run fifo.ini

check "NetCDF: a pipe refused at once" expect_exit 2 "waiting.nc is a pipe: expected a regular file" \
  timeout -k 5 3 "$cli" surface --stats waiting.nc

"$cli" surface --n 32 --seed 4 --out s.npy >/dev/null
cp s.npy.json written.npy.json # the units, as beside the file
"$cli" surface --stats s.npy >alone.txt
(sleep 1; cat s.npy >written.npy) &
timeout -k 5 20 "$cli" surface --stats written.npy >piped.txt
check "a pipe that is written to: read as the file" cmp -s alone.txt piped.txt
wait
finish
