#!/usr/bin/env bash
# Command-line tests of `indentmap render`: outputs, metadata, exit codes, atomic failures.
# Exits 77 (skipped) only when no OpenGL 3.3 core context can be created at all, and fails
# instead when IM_REQUIRE_GL=1; a renderer that opens a context and then fails always fails.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

source "$(dirname "$0")/lib.sh"
require_renderer "$cli"

# Without an EGL vendor library (glvnd) and with OSMesa excluded, no context exists: this very
# script skips, unless IM_REQUIRE_GL=1.
no_gl=(env -u IM_REQUIRE_GL __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json IM_RENDER_BACKEND=egl)
check "no context: info says so" bash -c "${no_gl[*]} '$cli' info | grep -q '^render backend: unavailable (no OpenGL 3.3 core context'"
check "no context: skipped" expect_exit 77 "SKIPPED: render backend: unavailable" "${no_gl[@]}" bash "$0" "$cli"
check "no context, IM_REQUIRE_GL=1: fails" expect_exit 1 "FAIL: IM_REQUIRE_GL=1" "${no_gl[@]}" IM_REQUIRE_GL=1 bash "$0" "$cli"
check "info --backend osmesa" bash -c "'$cli' info --backend osmesa | grep -q '^render backend: osmesa, libOSMesa'"
check "info --backend egl" bash -c "IM_RENDER_BACKEND=osmesa '$cli' info --backend egl | grep -q '^render backend: egl, '"
check "info --backend bad" expect_exit 2 "auto, egl or osmesa" "$cli" info --backend vulkan
png_width() { od -An -tu1 -j16 -N4 "$1" | awk '{print $1 * 16777216 + $2 * 65536 + $3 * 256 + $4}'; }

# A field with positive (in contact) and negative patches: a small generated surface.
"$cli" surface --n 16 --seed 5 --out "$dir/f.npy" >/dev/null 2>&1
"$cli" surface --n 16 --seed 6 --out "$dir/g.npy" >/dev/null 2>&1
check "info names the GL renderer" bash -c "'$cli' info | grep -q '^GL_RENDERER: '"
check "contact map" "$cli" render contact "$dir/f.npy" --circle 5 --label "(a)" --out "$dir/c.png"
check "PNG carries the colour map" grep -aq "Colormap" "$dir/c.png"
check "PNG carries the input" grep -aq "f.npy" "$dir/c.png"
check "raw PNG" "$cli" render contact "$dir/f.npy" --raw --scale 3 --out "$dir/raw.png"
check "raw PNG width = 16 x 3 + 2 x 2" test "$(png_width "$dir/raw.png")" -eq 52
check "height field PDF" "$cli" render height "$dir/f.npy" --contact "$dir/g.npy" --out "$dir/h.pdf"
check "PDF header" bash -c "head -c 5 '$dir/h.pdf' | grep -q '%PDF-'"
check "height field SVG" "$cli" render height "$dir/f.npy" --out "$dir/h.svg"
check "SVG embeds the raster" grep -q "<image" "$dir/h.svg"
check "osmesa backend" "$cli" render contact "$dir/f.npy" --backend osmesa --raw --out "$dir/o.png"
# the pixels (the PNGs' image data, decompressed): their Command texts differ
idat() { python3 -c 'import struct, sys, zlib
data, at, image = open(sys.argv[1], "rb").read(), 8, b""
while at < len(data):
    length, kind = struct.unpack(">I4s", data[at:at + 8])
    image += data[at + 8:at + 8 + length] if kind == b"IDAT" else b""
    at += 12 + length
sys.stdout.buffer.write(zlib.decompress(image))' "$1"; }
check "osmesa = egl pixels" bash -c "$(declare -f idat); '$cli' render contact '$dir/f.npy' --backend egl --raw --out '$dir/e.png' &&
  cmp -s <(idat '$dir/e.png') <(idat '$dir/o.png')"

# Forces default to the frames' colour map and norm (scenes, indent --frames, render view3d): magma, log
# over the two decades below the largest force (read from the file); heights stay viridis, linear.
figure_texts=$(realpath "$(dirname "$0")/figure_texts.py")
png_text() { python3 "$figure_texts" "$1" "$2=$3" >/dev/null; }
largest=$(python3 -c 'import array, ast, sys  # the largest of a little-endian float64 .npy, without numpy
data = open(sys.argv[1], "rb").read(); length = int.from_bytes(data[8:10], "little")
assert ast.literal_eval(data[10:10 + length].decode())["descr"] == "<f8"
print("%.9g" % max(array.array("d", data[10 + length:])))' "$dir/f.npy")
tenth=$(python3 -c 'import sys; print("%.9g" % (float(sys.argv[1]) / 100))' "$largest")
mkdir -p "$dir/norms"
"$cli" render contact "$dir/f.npy" --out "$dir/norms/default.png"
check "contact: magma by default" png_text "$dir/norms/default.png" Colormap magma
check "contact: log over two decades by default" png_text "$dir/norms/default.png" Norm "log [$tenth, $largest]"
"$cli" render contact "$dir/f.npy" --linear --colormap viridis --out "$dir/norms/linear.png"
check "contact --linear --colormap viridis" png_text "$dir/norms/linear.png" Norm "linear [0, $largest]"
check "contact --colormap viridis kept" png_text "$dir/norms/linear.png" Colormap viridis
"$cli" render height "$dir/f.npy" --out "$dir/norms/height.png"
check "height: viridis, linear" bash -c "figure_texts='$figure_texts'; $(declare -f png_text); png_text '$dir/norms/height.png' Colormap viridis &&
  png_text '$dir/norms/height.png' Norm linear"
check "--log with --linear refused" expect_exit 2 "expected one norm" \
  "$cli" render contact "$dir/f.npy" --log --linear --out "$dir/x.png"
check "--linear on heights refused" expect_exit 2 "heights are drawn linear" \
  "$cli" render height "$dir/f.npy" --linear --out "$dir/x.png"

# --clip P (S9): the default range with P % of the values cut at each end, the percentiles of the finite values
# (forces: of those > 0, the top end only), computed here by sorting (numpy.percentile's default, without numpy);
# a scan whose few spikes and dropouts set the default range is named on stderr with the option, drawn as before.
python3 -c 'import math, struct, sys  # 40 x 30 float64 .npy: a 1e-5 relief, 10 dropouts (0), 9 spikes 3e-4, 4 NaN
header = "{\x27descr\x27: \x27<f8\x27, \x27fortran_order\x27: False, \x27shape\x27: (30, 40), }"
header += " " * (117 - len(header)) + "\n"
values = [0.0 if i < 10 else 3e-4 if i % 131 == 7 else math.nan if i % 293 == 5 else 1e-5 + 5e-6 * math.sin(0.05 * i)
          for i in range(1200)]
open(sys.argv[1], "wb").write(b"\x93NUMPY\x01\x00" + struct.pack("<H", 118) + header.encode() + struct.pack("<1200d", *values))' "$dir/spiky.npy"
percentile() { python3 -c 'import array, math, sys  # FILE PERCENT heights|forces
data = open(sys.argv[1], "rb").read(); length = int.from_bytes(data[8:10], "little")
kept = sorted(v for v in array.array("d", data[10 + length:]) if math.isfinite(v) and (sys.argv[3] == "heights" or v > 0))
rank = float(sys.argv[2]) / 100 * (len(kept) - 1); k = math.floor(rank)
value = kept[k] + (rank - k) * (kept[k + 1] - kept[k]) if k + 1 < len(kept) else kept[k]
print("%.9g" % (value / 100 if len(sys.argv) > 4 else value))' "$@"; }
"$cli" render height "$dir/spiky.npy" --clip 2 --out "$dir/norms/clip.png"
check "height --clip 2: the 2nd .. 98th percentile" png_text "$dir/norms/clip.png" Norm \
  "linear [$(percentile "$dir/spiky.npy" 2 heights), $(percentile "$dir/spiky.npy" 98 heights)]"
"$cli" render contact "$dir/f.npy" --clip 5 --out "$dir/norms/clip-contact.png"
check "contact --clip 5: log up to the 95th percentile of the forces" png_text "$dir/norms/clip-contact.png" Norm \
  "log [$(percentile "$dir/f.npy" 95 forces tenth), $(percentile "$dir/f.npy" 95 forces)]"
"$cli" render height "$dir/spiky.npy" --out "$dir/norms/spiky.png" 2>"$dir/spiky.err"
check "outliers: one notice naming the file and --clip" bash -c "test \$(wc -l <'$dir/spiky.err') -eq 1 &&
  grep -q '^indentmap: $dir/spiky.npy: a few outliers set the colour range: .* --clip 1 cuts 1% ' '$dir/spiky.err'"
check "outliers: drawn min .. max as before" png_text "$dir/norms/spiky.png" Norm "linear [0, 0.0003]"
"$cli" render height "$dir/f.npy" --out "$dir/norms/plain.png" 2>"$dir/plain.err"
check "no outliers: no notice" test ! -s "$dir/plain.err"
check "--clip 50 refused" expect_exit 2 "--clip 50: expected a percentage in [0, 50) cut at each end" \
  "$cli" render height "$dir/f.npy" --clip 50 --out "$dir/x.png"
check "missing --out" expect_exit 2 "--out is required" "$cli" render contact "$dir/f.npy"
check "unknown mode" expect_exit 2 "expected contact, height or animate" "$cli" render map "$dir/f.npy"
check "bad colour map" expect_exit 2 "expected viridis" "$cli" render contact "$dir/f.npy" --colormap jet --out "$dir/x.png"
check "log norm needs vmin > 0" expect_exit 2 "logarithmic" "$cli" render contact "$dir/f.npy" --log --vmin 0 --out "$dir/x.png"
check "the default log norm names --vmin" expect_exit 2 "--vmin 0: a logarithmic norm needs --vmin > 0 (or --linear)" "$cli" render contact "$dir/f.npy" --vmin 0 --out "$dir/x.png"
# a force is finite (NaN marks no data): +-Inf refused naming the file and the first such patch (x, y) (S10); a
# height's +Inf (an open gap) is drawn as before
python3 -c 'import struct, sys  # a 4 x 3 float64 .npy, without numpy: NaN at (0, 0), +Inf at (2, 1), -Inf at (1, 2)
header = "{\x27descr\x27: \x27<f8\x27, \x27fortran_order\x27: False, \x27shape\x27: (3, 4), }"
header += " " * (117 - len(header)) + "\n"
values = [float("nan"), 1, 2, 3, 4, 5, float("inf"), 7, 8, float("-inf"), 10, 11]
open(sys.argv[1], "wb").write(b"\x93NUMPY\x01\x00" + struct.pack("<H", 118) + header.encode() + struct.pack("<12d", *values))' "$dir/inf.npy"
check "an infinite force refused" expect_exit 2 "inf.npy: contact map: force inf at patch (2, 1): expected a finite force (NaN marks no data)" "$cli" render contact "$dir/f.npy" "$dir/inf.npy" --out "$dir/x.png"
check "an infinite height drawn" "$cli" render height "$dir/inf.npy" --out "$dir/inf-height.png"
check "bad backend" expect_exit 2 "auto, egl or osmesa" "$cli" render contact "$dir/f.npy" --backend vulkan --out "$dir/x.png"
check "bad scale" expect_exit 2 "--scale = 0" "$cli" render contact "$dir/f.npy" --scale 0 --out "$dir/x.png"
check "unknown extension" expect_exit 2 ".png, .pdf or .svg" "$cli" render contact "$dir/f.npy" --out "$dir/x.tiff"
check "missing input" expect_exit 1 "missing.npy" "$cli" render contact "$dir/missing.npy" --out "$dir/x.png"
check "unwritable output" expect_exit 1 "no/such/dir" "$cli" render contact "$dir/f.npy" --out "$dir/no/such/dir/x.png"
check "nothing half-written" bash -c "! ls '$dir' | grep -q 'x\\.'"

check "animation GIF" "$cli" render animate "$dir/f.npy" "$dir/g.npy" --frames "$dir/frames" --out "$dir/a.gif"
check "frames written" test -s "$dir/frames/contact_0000.png" -a -s "$dir/frames/contact_0001.png"
check "GIF header" bash -c "head -c 6 '$dir/a.gif' | grep -q GIF89a"
# 32 x 32 patches: the anti-aliased circle's blends would take a frame past 256 colours.
"$cli" surface --n 32 --seed 5 --out "$dir/f32.npy" >/dev/null 2>&1
check "animation GIF with --circle" "$cli" render animate "$dir/f32.npy" "$dir/f32.npy" --circle 8 --frames "$dir/framesc" --out "$dir/c.gif"
check "GIF with --circle: PNG frames" test -s "$dir/framesc/contact_0001.png"
check "GIF without --circle" "$cli" render animate "$dir/f32.npy" "$dir/f32.npy" --frames "$dir/framesn" --out "$dir/n.gif"
check "GIF with --circle differs from without" bash -c "! cmp -s '$dir/n.gif' '$dir/c.gif'"
# Fields of different grids (reliability row 176): the files are named, not the frames' pixels.
check "animation of fields of two grids names the files" expect_exit 2 \
  "render animate: $dir/f32.npy (frame 1) is 32 x 32 but $dir/f.npy (frame 0) is" \
  "$cli" render animate "$dir/f.npy" "$dir/f32.npy" --frames "$dir/framesg" --out "$dir/g.gif"
if command -v ffmpeg >/dev/null; then
  check "MP4" "$cli" render animate "$dir/f.npy" "$dir/g.npy" --frames "$dir/frames2" --out "$dir/a.mp4"
else
  check "MP4 without ffmpeg" expect_exit 1 "ffmpeg not found" "$cli" render animate "$dir/f.npy" --frames "$dir/frames2" --out "$dir/a.mp4"
  check "frames kept without ffmpeg" test -s "$dir/frames2/contact_0000.png"
fi

finish
