#!/usr/bin/env bash
# Temporary files of atomic writes: short names (a legal 250-byte final name works), removed when
# SIGTERM or SIGHUP (or SIGINT) ends `surface` or `render` mid-write, and removed by `run --resume` when a
# killed run left them in its output folder.
set -u
cli=$1
dir=$(mktemp -d)
trap 'kill "$pid" 2>/dev/null; rm -rf "$dir"' EXIT
pid=
source "$(dirname "$0")/lib.sh"
export OMP_NUM_THREADS=1
cd "$dir" || exit 1

long=$(printf 'a%.0s' $(seq 246)).npy # 250 bytes; its sidecar .json makes 255, the limit
check "a 250-byte file name" bash -c "'$cli' surface --n 16 --out '$long' >/dev/null"
check "... and its 255-byte sidecar" test -s "$long.json"

temporaries() { find "$1" -name '*.tmp.*' | grep -q .; }

# interrupt SIGNAL STATUS FOLDER COMMAND...: sends SIGNAL as soon as COMMAND's temporary file
# appears in FOLDER; the command must end with STATUS and leave no temporary file.
interrupt() {
  local signal=$1 status=$2 folder=$3; shift 3
  "$@" >/dev/null 2>&1 &
  pid=$!
  for _ in $(seq 3000); do temporaries "$folder" && break; sleep 0.005; done
  kill -"$signal" "$pid"
  wait "$pid"
  local got=$?
  pid=
  [ "$got" -eq "$status" ] || { echo "exit $got, expected $status"; return 1; }
  ! temporaries "$folder"
}

mkdir big
check "surface --png: SIGTERM mid-write leaves no temporary file" \
  interrupt TERM 143 big "$cli" surface --n 2048 --png big/h.png
"$cli" surface --n 512 --out h.npy >/dev/null
# (not SIGINT: a non-interactive shell starts background jobs with SIGINT ignored)
check "render --raw: SIGHUP mid-write leaves no temporary file" \
  interrupt HUP 129 big "$cli" render height h.npy --raw --scale 8 --out big/h.png

# run --resume: temporary files a killed run left (this version's and the older PATH.tmp.PID) go
cat >scene.ini <<INI
[scene]
name = t
output = res
[surfaces]
n = 32
seeds = 1:2
[loading]
control = displacement
steps = 0.5, 1
[output]
plots = fig5
INI
"$cli" run --quiet scene.ini >/dev/null 2>&1 || exit 1
touch res/.im.tmp.99999.7 res/histories/member_00_1.csv.tmp.4242 res/notes.tmp.txt
check "run --resume removes stale temporary files" expect_exit 0 "removed 2 temporary files" \
  "$cli" run --resume scene.ini
check "... every one" bash -c "! find res -name '*.tmp.[0-9]*' | grep -q ."
check "... and nothing else" test -e res/notes.tmp.txt
finish
