#!/usr/bin/env bash
# indentmap mpi-indent's figures (MPI builds with an OpenGL context; skipped, exit 77, elsewhere): the history
# figure, the Oliver-Pharr figure and --frames' contact maps, drawn on rank 0 by indent's writers, against
# indent --full --frames' on a 64 x 48 rough surface over 3 ranks: every PNG's header and pixels (its IDAT
# inflated) the same, its texts the same but for Command (the command line); the force_NNNN.npy the frames are
# drawn from, with their sidecars; a periodic cell's too. Refused: --frames without --out or without a history.
#   cli_mpi_figures.sh PATH_TO_INDENTMAP
set -uo pipefail
cli=$1
source "$(dirname "$0")/lib.sh"
require_renderer "$cli"
source "$(dirname "$0")/mpi/cli_history.sh"

"$cli" surface --n 64 --m 48 --seed 3 --out "$work/p.npy" > /dev/null || fail "surface"
awk 'BEGIN { for (i = 0; i <= 40; ++i) print i, i * i / 40 }' > "$work/profile.txt"

# same_pixels A B: the PNGs' IHDR and inflated IDAT are equal and their texts differ in Command only
same_pixels() {
  python3 -c 'import struct, sys, zlib
def read(path):
    data, pos, chunks = open(path, "rb").read(), 8, {"IDAT": b""}
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body, kind = data[pos + 8:pos + 8 + length], kind.decode()
        if kind == "tEXt":
            key, value = body.split(b"\0", 1)
            chunks["text " + key.decode()] = value
        else:
            chunks[kind] = chunks.get(kind, b"") + body
        pos += 12 + length
    chunks["IDAT"] = zlib.decompress(chunks["IDAT"])
    return chunks
a, b = read(sys.argv[1]), read(sys.argv[2])
differ = sorted(k for k in set(a) | set(b) if a.get(k) != b.get(k) and k not in ("text Command", "IEND"))
if differ or a.get("text Command") == b.get("text Command"):
    sys.exit("differ: %s" % (differ or "nothing, not even the Command"))' "$1" "$2"
}

# figures NAME FILES ARGUMENTS...: indent --full --frames ARGUMENTS and mpi-indent --frames ARGUMENTS on 3 ranks
# draw FILES (and history.pdf, the frames of every step) alike
figures() {
  local name=$1 files=$2 steps
  shift 2
  "$cli" indent "$work/p.npy" --full --frames "$@" --tol 1e-8 --out "$work/$name.serial" > /dev/null \
    2> "$work/$name.err" || fail "$name: indent: $(cat "$work/$name.err")"
  timeout 600 "$mpiexec" -n 3 --oversubscribe "$cli" mpi-indent --surface "$work/p.npy" --frames "$@" --tol 1e-8 \
    --out "$work/$name.3" > /dev/null 2> "$work/$name.3.err" ||
    fail "$name: mpi-indent (exit $?, 124: timed out): $(cat "$work/$name.3.err")"
  steps=$(($(wc -l < "$work/$name.serial/history.csv") - 1))
  [ "$(ls "$work/$name.3/frames")" = "$(ls "$work/$name.serial/frames")" ] && [ "$steps" -ge 3 ] ||
    fail "$name: the frames are not indent's: $(ls "$work/$name.3/frames")"
  for file in $files $(cd "$work/$name.serial" && ls frames/*.png); do
    same_pixels "$work/$name.serial/$file" "$work/$name.3/$file" > "$work/$name.diff" 2>&1 ||
      fail "$name: $file is not indent's: $(cat "$work/$name.diff")"
  done
  for step in $(seq -f %04g 1 "$steps"); do
    [ -s "$work/$name.3/force_$step.npy" ] && [ -s "$work/$name.3/force_$step.npy.json" ] ||
      fail "$name: no force_$step.npy and its sidecar"
  done
  [ -s "$work/$name.3/history.pdf" ] || fail "$name: no history.pdf"
}

figures profile "history.png load_displacement.png" --approach 0.5,1.5,3,1.5,0.5 --punch profile \
  --profile "$work/profile.txt"
figures cell "history.png" --periodic --pressure 0.01,0.03,0.05

refused frames_alone "--frames needs --out DIR" --approach 1,2 --frames
refused frames_one_step "--frames draws a history's steps" --approach 1 --frames --out "$work/one"
echo "mpi-indent's figures and frames are indent's, pixel for pixel, on 3 ranks"
