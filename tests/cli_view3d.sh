#!/usr/bin/env bash
# Command-line tests of the 3-D view and the viewer page: `render view3d` (outputs, metadata,
# errors), `indent` and `run` writing index.html, and a scene's frames3d. Exits 77 (skipped) only
# when no OpenGL 3.3 core context can be created at all (and IM_REQUIRE_GL is not 1).
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export OMP_WAIT_POLICY=passive

source "$(dirname "$0")/lib.sh"
require_renderer "$cli"

# view3d's help names the surface formats render's names, from one list (findings DA11: ".npy, .gsf or text"
# while it reads every one, an .x3p too).
render_formats=$("$cli" render --help | sed -n 's/^Draws a field file (\(.*\) matrix).*/\1/p')
view3d_formats=$("$cli" render view3d --help | sed -n 's/^Draws HEIGHT (a surface or deformed surface file: \([^)]*\)).*/\1/p')
check "view3d's help names render's formats ($view3d_formats)" test -n "$render_formats" -a "$render_formats" = "$view3d_formats"

# indent writes its page beside history.csv and run.json, with the history as a table.
"$cli" indent --smooth --n 64 --alpha 70 --load 50,100 --fields --out "$dir/ind" >"$dir/indent.log" 2>&1
check "indent runs" test $? -eq 0
check "indent writes index.html" test -s "$dir/ind/index.html"
check "the page shows the history" grep -q '<h3><a href="history.csv">history.csv</a></h3>' "$dir/ind/index.html"
check "the page shows the run record" grep -q "Run record" "$dir/ind/index.html"
check "indent draws its history" test -s "$dir/ind/history.png"
check "the page shows the history figure" grep -q '<img src="history.png"' "$dir/ind/index.html"
check "the history table's headers carry units" grep -q '<th>load<br><span class="unit">(E\* δ²)</span></th>' "$dir/ind/index.html"

# --frames: a contact frame per step under the slider; a shorter rerun leaves none of the longer one's.
"$cli" indent --smooth --n 64 --alpha 70 --load 50:150:3 --frames --out "$dir/fr" >"$dir/frames.log" 2>&1
check "indent --frames runs" test $? -eq 0
check "a frame per step" test -s "$dir/fr/frames/contact_0002.png" -a ! -e "$dir/fr/frames/contact_0003.png"
check "the page has the slider" grep -q 'id="frame-slider"' "$dir/fr/index.html"
"$cli" indent --smooth --n 64 --alpha 70 --load 50,150 --frames --out "$dir/fr" >/dev/null 2>&1
check "the earlier run's frames are removed" test ! -e "$dir/fr/frames/contact_0002.png"
check "the periodic cell's history is drawn" bash -c "'$cli' indent --smooth --n 32 --periodic --punch sphere \
  --radius 8 --load 5,10 --out '$dir/per' >/dev/null 2>&1 && test -s '$dir/per/history.png'"

# --page-embed: one file, its images inside it.
"$cli" indent --smooth --n 64 --alpha 70 --load 50:150:3 --frames --page-embed --out "$dir/emb" >/dev/null 2>&1
check "indent --page-embed runs" test $? -eq 0
check "the embedded page has no relative image" bash -c "! grep -qE 'src=\"[^d]|\"frames/' '$dir/emb/index.html'"
check "the embedded page holds the images" grep -q 'src="data:image/png;base64,' "$dir/emb/index.html"

# render view3d: a figure with the exaggeration stated, a raw image of the asked size.
"$cli" surface --n 64 --slope 0.1 --seed 2 --out "$dir/s.npy" >/dev/null
"$cli" indent "$dir/s.npy" --alpha 70 --load 100 --fields --out "$dir/rough" >/dev/null 2>&1
v3=("$cli" render view3d "$dir/s.npy" --displacement "$dir/rough/displacement_0001.npy"
    --force "$dir/rough/force_0001.npy" --alpha 70)
check "view3d figure" "${v3[@]}" --exaggeration 4 --width 400 --height 300 --out "$dir/v.png"
check "exaggeration in the metadata" grep -qa "vertical exaggeration" "$dir/v.png"
# The default norm is the contact frames' (magma, log, two decades below the largest force);
# --linear the linear one up to the same force.
norm_of() { grep -ao 'Norm.[a-z]* \[[^]]*\]' "$1" | cut -c6-; }
"${v3[@]}" --width 320 --height 200 --out "$dir/default.png" >/dev/null 2>&1
"${v3[@]}" --width 320 --height 200 --linear --out "$dir/linear.png" >/dev/null 2>&1
read -r kind lo hi < <(norm_of "$dir/default.png" | tr -d '[],')
check "view3d's default norm is logarithmic" test "$kind" = log
check "it spans two decades" python3 -c "assert abs($lo * 100 / $hi - 1) < 1e-8"
check "the colour map is magma" grep -qa "magma" "$dir/default.png"
check "--linear: from 0 to the same largest force" test "$(norm_of "$dir/linear.png")" = "linear [0, $hi]"
check "--log with --linear refused" expect_exit 2 "expected one norm" "${v3[@]}" --log --linear --out "$dir/x.png"
check "view3d raw" "${v3[@]}" --width 320 --height 200 --raw --punch-mode cutaway --ortho --out "$dir/raw.png"
check "raw image is 320 x 200" bash -c "head -c 24 '$dir/raw.png' | od -An -tx1 | tr -d ' \n' | grep -q '00000140000000c8\$'"
check "view3d as PDF" "${v3[@]}" --width 320 --height 200 --out "$dir/v.pdf"
"$cli" surface --n 32 --out "$dir/small.npy" >/dev/null
check "force on another grid refused" expect_exit 2 "expected the grid of the heights" \
  "$cli" render view3d "$dir/s.npy" --force "$dir/small.npy" --out "$dir/x.png"
check "elevation out of range refused" expect_exit 2 "--elevation" \
  "$cli" render view3d "$dir/s.npy" --elevation 0 --out "$dir/x.png"
check "sphere needs a radius" expect_exit 2 "--radius" \
  "$cli" render view3d "$dir/s.npy" --punch sphere --out "$dir/x.png"
# A scan with missing points: refused naming --fill, which view3d takes as indent does (it had none).
"$cli" surface --n 64 --slope 0.1 --seed 2 --out "$dir/s.txt" >/dev/null
awk '/^#/ {print; next} {r++; if (r > 20 && r <= 35) for (i = 21; i <= 35; i++) $i = "nan"; print}' "$dir/s.txt" >"$dir/holes.txt"
check "missing points refused, naming --fill" expect_exit 2 "on request: --fill" \
  "$cli" render view3d "$dir/holes.txt" --width 320 --height 200 --out "$dir/x.png"
check "nothing left by refusals" test ! -e "$dir/x.png"
"$cli" render view3d "$dir/holes.txt" --fill --width 320 --height 200 --out "$dir/filled.png" 2>"$dir/filled.err"
check "--fill draws the scan" test -s "$dir/filled.png"
check "--fill warns of the points it invented" grep -q "(225 of 4096 points)" "$dir/filled.err"
# ... and indent's other surface-file options, from its table (--unit, --crop, --detrend, ...; they were indent's
# only): HEIGHT prepared as indent's SURFACE, so that the displacement of a cropped run's --fields fits it
"$cli" surface --n 32 --seed 4 --out "$dir/s32.npy" >/dev/null 2>&1
"$cli" surface --n 16 --seed 5 --out "$dir/u16.npy" >/dev/null 2>&1
check "a 16 x 16 displacement on a 32 x 32 HEIGHT refused" expect_exit 2 "grid 16 x 16: expected the grid of" \
  "$cli" render view3d "$dir/s32.npy" --displacement "$dir/u16.npy" --width 320 --height 200 --raw --out "$dir/x.png"
check "--crop, --detrend, --align, --unit, --npy-order: HEIGHT cropped to the displacement's grid" \
  "$cli" render view3d "$dir/s32.npy" --crop 8,8,16,16 --detrend plane --align median --unit nm --npy-order yx \
  --displacement "$dir/u16.npy" --width 320 --height 200 --raw --out "$dir/cropped.png"
check "--crop beyond HEIGHT refused naming it" expect_exit 2 "--crop: crop 0,0,64,64: expected X0,Y0,NX,NY with NX, NY >= 2 inside the 32 x 32 grid" \
  "$cli" render view3d "$dir/s32.npy" --crop 0,0,64,64 --width 320 --height 200 --raw --out "$dir/x.png"

# A scene with frames3d: 3-D frames, their GIF, and the page with the three frame panels.
cat >"$dir/scene.ini" <<INI
[scene]
name = view
output = $dir/scene
[surfaces]
n = 64
slopes = 0.08
seeds = 3
[punch]
alpha = 70
[loading]
load_star = 400
[output]
frames = yes
frames3d = yes
frame_count = 3
animation = gif
INI
"$cli" run "$dir/scene.ini" >"$dir/run.log" 2>&1
check "scene runs" test $? -eq 0
for f in frames/view3d_0000.png frames/view3d_0002.png view3d.gif contact.gif index.html; do
  check "wrote $f" test -s "$dir/scene/$f"
done
check "page has the 3-D frames" grep -q 'id="frame-view3d"' "$dir/scene/index.html"
check "page has the contact frames" grep -q 'id="frame-contact"' "$dir/scene/index.html"
check "frame title states the scale" grep -qa "N\* = 400" "$dir/scene/frames/view3d_0002.png"
# One colour scale for all frames: every 3-D frame's Norm text is the same, and is the first
# frame's (where the forces are smallest, so a per-frame norm would differ).
norms=$(for f in "$dir"/scene/frames/view3d_000[0-2].png; do grep -ao 'magma log \[[^]]*\]' "$f"; done | sort -u | wc -l)
check "one norm across the 3-D frames" test "$norms" -eq 1
# The real page in headless Chromium (when installed): no console message, the script ran.
if command -v chromium >/dev/null; then
  chromium --headless --no-sandbox --disable-gpu --no-first-run --disable-background-networking \
    --disable-component-update --disable-sync --user-data-dir="$dir/profile" --enable-logging=stderr --v=0 \
    --dump-dom "file://$dir/scene/index.html" >"$dir/dom.html" 2>"$dir/console.log"
  check "scene page: no console message" bash -c "! grep -q ':CONSOLE' '$dir/console.log'"
  check "scene page: the slider script ran" grep -q "step 1 of 3" "$dir/dom.html"
fi
# No 3-D frame cuts the block: the lowest drawn row left of the colour bar is the block's front
# corner (a few pixels), not a cut through its front face (hundreds of pixels at the panel's
# bottom edge: the 3-D frames' camera sat at 1.75 grid sides, too near for the block).
lowest_row_width() {
  python3 - "$1" <<'PY'
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
width, height, depth, colour = struct.unpack(">IIBB", data[16:26])
assert depth == 8 and colour in (2, 6), (depth, colour)
channels, raw, at = 3 if colour == 2 else 4, b"", 8
while at < len(data):
    length, kind = struct.unpack(">I4s", data[at:at + 8])
    raw += data[at + 8:at + 8 + length] if kind == b"IDAT" else b""
    at += 12 + length
raw, stride, rows, previous = zlib.decompress(raw), width * channels, [], bytearray(width * channels)
for y in range(height):
    kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - channels] if i >= channels else 0
        b, c = previous[i], previous[i - channels] if i >= channels else 0
        p = a + b - c
        nearest = a if abs(p - a) <= abs(p - b) and abs(p - a) <= abs(p - c) else b if abs(p - b) <= abs(p - c) else c
        line[i] = (line[i] + (0, a, b, (a + b) // 2, nearest)[kind]) & 255
    rows.append(line)
    previous = line
left = int(0.85 * width)
drawn = [sum(1 for x in range(left) if row[x * channels:x * channels + 3] != b"\xff\xff\xff") for row in rows]
print(next(count for count in reversed(drawn) if count))
PY
}
for f in "$dir"/scene/frames/view3d_000[0-2].png; do
  check "$(basename "$f"): the block's front corner is in the frame" test "$(lowest_row_width "$f")" -lt 20
done
sed 's/^frames = yes/frames = no/' "$dir/scene.ini" >"$dir/bad.ini"
check "frames3d needs frames" expect_exit 2 "set frames = yes too" "$cli" run "$dir/bad.ini"
# A punch the 3-D view cannot frame is refused before solving, naming its key (S12: solved, then refused at the
# camera, exit 2)
sed -e "s|^output = .*|output = $dir/needle|" -e 's/^alpha = 70/alpha = 1e-9/' "$dir/scene.ini" >"$dir/needle.ini"
check "a needle with frames3d: refused before solving" expect_exit 2 "[punch] alpha = 1e-09 with [output] frames3d" "$cli" run "$dir/needle.ini"
check "a needle with frames3d: nothing solved" bash -c "! grep -q 'histories' '$dir/err' && ! test -e '$dir/needle/results.csv'"
sed -e "s|^output = .*|output = $dir/noframes|" -e 's/^frames = yes/frames = no/' -e 's/^frames3d = yes/frames3d = no/' -e 's/^frame_count = 3/contact_panels = yes/' \
  "$dir/scene.ini" >"$dir/bad.ini"
check "animation needs frames (no GIF, and exit 0, before)" expect_exit 2 "animation animates the frames: set frames = yes too" "$cli" run "$dir/bad.ini"
# A frame key of an output the scene does not draw is warned about, naming it (it did nothing, silently);
# the scene still runs: frames = no for a quick run needs no other key removed.
sed -e "s|^output = .*|output = $dir/unused|" -e 's/^frames = yes/frames = no/' -e 's/^frames3d = yes/contact_panels = yes/' \
  -e 's/^animation = gif/frame_rate = 2/' "$dir/scene.ini" >"$dir/unused.ini"
"$cli" run "$dir/unused.ini" >"$dir/unused.log" 2>&1
check "unused frame keys: the scene runs" test $? -eq 0 -a -s "$dir/unused/contact_panels.png"
check "unused frame keys: frame_count named" grep -q "\[output\] frame_count does nothing: it applies to the frames (frames = yes)" "$dir/unused.log"
check "unused frame keys: frame_rate named" grep -q "\[output\] frame_rate does nothing: it applies to the animations" "$dir/unused.log"
check "unused frame keys: no other named" test "$(grep -c 'does nothing' "$dir/unused.log")" -eq 2
# The contact and height frames carry render's texts (S11: only the 3-D frames stated their norm): the
# contact frames the 3-D frames' norm, the height frames theirs.
texts="$(dirname "$0")/figure_texts.py"
view3d_norm=$(grep -ao 'magma log \[[^]]*\]' "$dir/scene/frames/view3d_0000.png" | cut -c7-)
check "a 3-D frame states its norm" test -n "$view3d_norm"
for f in contact_0000 contact_0002; do
  check "$f: the 3-D frames' norm, render's texts" python3 "$texts" "$dir/scene/frames/$f.png" "Norm=$view3d_norm" \
    Colormap=magma "Quantity=local force f / (E* δ²)" "Pixels per patch=1"
done
check "height frame: render's texts" python3 "$texts" "$dir/scene/frames/height_0001.png" "Norm=linear [" \
  Colormap=viridis "Quantity=deformed height" "Pixels per patch=1"
# The stage lines of one frame are in the singular ("frames: 1 steps", "1 3-D views" before).
sed -e "s|^output = .*|output = $dir/one|" -e 's/^frame_count = 3/frame_count = 1/' "$dir/scene.ini" >"$dir/one.ini"
"$cli" run "$dir/one.ini" >"$dir/one.log" 2>&1
check "one frame: 'frames: 1 step of'" grep -q "frames: 1 step of family 0" "$dir/one.log"
check "one frame: 'frames3d: 1 3-D view ('" grep -q "frames3d: 1 3-D view (" "$dir/one.log"
check "three frames: 'frames: 3 steps of'" grep -q "frames: 3 steps of family 0" "$dir/run.log"

# Frame size and rate: frame_rate sets every GIF frame's delay (1/10 s: a graphic control extension
# 21 f9 04 04 0a 00 per frame), frame3d_width/height the 3-D view, frame_scale the 2-D maps' pixels per
# patch (the contact frame is larger than at 1); the GIF frames are the annotated PNG frames' size.
png_size() { python3 -c "import struct,sys; d=open(sys.argv[1],'rb').read(24); print(*struct.unpack('>II', d[16:24]))" "$1"; }
gif_size() { python3 -c "import struct,sys; d=open(sys.argv[1],'rb').read(10); print(*struct.unpack('<HH', d[6:10]))" "$1"; }
delays() { python3 -c "import sys; print(open(sys.argv[1],'rb').read().count(bytes.fromhex('21f904040a00')))" "$1"; }
sed -e "s|^output = .*|output = $dir/sized|" -e 's/^animation = gif/animation = gif\nframe_rate = 10\nframe_scale = 2\nframe3d_width = 480\nframe3d_height = 270/' \
  "$dir/scene.ini" >"$dir/sized.ini"
check "scene with frame size and rate" "$cli" run "$dir/sized.ini"
check "3 frames of 1/10 s in contact.gif" test "$(delays "$dir/sized/contact.gif")" -eq 3
check "3 frames of 1/10 s in view3d.gif" test "$(delays "$dir/sized/view3d.gif")" -eq 3
check "contact.gif is the PNG frame's size" test "$(gif_size "$dir/sized/contact.gif")" = "$(png_size "$dir/sized/frames/contact_0000.png")"
check "view3d.gif is the PNG frame's size" test "$(gif_size "$dir/sized/view3d.gif")" = "$(png_size "$dir/sized/frames/view3d_0000.png")"
read -r w1 h1 < <(png_size "$dir/scene/frames/contact_0000.png")
read -r w2 h2 < <(png_size "$dir/sized/frames/contact_0000.png")
check "frame_scale = 2 makes a larger contact frame" test "$w2" -gt "$w1" -a "$h2" -gt "$h1"
read -r w3 _ < <(png_size "$dir/scene/frames/view3d_0000.png")
read -r w4 _ < <(png_size "$dir/sized/frames/view3d_0000.png")
check "frame3d_width = 480 narrows the 3-D frame by 480" test $((w3 - w4)) -eq 480
sed 's/^frame_rate = 10/frame_rate = 0/' "$dir/sized.ini" >"$dir/bad.ini"
check "frame_rate 0 refused" expect_exit 2 "frame_rate = '0': expected a number in [0.01, 100]" "$cli" run "$dir/bad.ini"
# Every frame of a history has one size, which its GIF needs: on a 64 x 64 map at 1 px per patch the
# title ("N* = 42" .. "N* = 1000") was wider than the map and widened some frames ("animation: frame 2
# is 231 x 196 ...: expected 220 x 196 like frame 0", exit 2): the titles now share one width.
sed -e "s|^output = .*|output = $dir/small|" -e 's/^frame_count = 3/frame_count = 24/' -e 's/^load_star = 400/load_star = 1000/' -e 's/^frames3d = yes/frames3d = no/' \
  "$dir/scene.ini" >"$dir/small.ini"
check "24 frames of a 64 x 64 map and their GIFs" "$cli" run "$dir/small.ini"
sizes=$(for f in "$dir"/small/frames/contact_00*.png; do png_size "$f"; done | sort -u | wc -l)
check "the 24 contact frames have one size" test "$sizes" -eq 1
check "their GIF is written" test -s "$dir/small/contact.gif"
finish
