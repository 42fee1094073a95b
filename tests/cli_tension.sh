#!/usr/bin/env bash
# Command-line tests of patches under tension (adhesion, issue 27): a field without tension is drawn
# exactly as before (the pixels of tests/data/tension, drawn by the code before the tension ramp), and
# a field with tension gets the tension's colour bar in `render contact`, `render animate`,
# `render view3d` and `indent --frames`. Exits 77 (skipped) only when no OpenGL context can be had.
set -u
cli=$1
data=$(dirname "$0")/data/tension
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export IM_FFTW_WISDOM=

source "$(dirname "$0")/lib.sh"
require_renderer "$cli"

png_width() { od -An -tu1 -j16 -N4 "$1" | awk '{print $1 * 16777216 + $2 * 65536 + $3 * 256 + $4}'; }

# same_pixels A B: the PNGs' headers and decompressed image data agree (their text chunks, which name
# the version and the source, may differ).
same_pixels() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import struct, sys, zlib
def pixels(path):
    data, header, idat = open(path, "rb").read()[8:], b"", b""
    while data:
        length, kind = struct.unpack(">I4s", data[:8])
        header = data[8:8 + length] if kind == b"IHDR" else header
        idat += data[8:8 + length] if kind == b"IDAT" else b""
        data = data[12 + length:]
    return header, zlib.decompress(idat)
sys.exit(0 if pixels(sys.argv[1]) == pixels(sys.argv[2]) else 1)
PY
}

# Without tension: the pixels the code before the tension ramp drew (its default map then: viridis, linear),
# figure and raw map.
check "repulsive figure: the pixels drawn before" bash -c "'$cli' render contact '$data/repulsive.txt' --colormap viridis --linear --circle 7 --scale 6 \
  --dpi 150 --out '$dir/fig.png' && $(declare -f same_pixels); same_pixels '$dir/fig.png' '$data/repulsive_figure.png'"
check "repulsive raw map: the pixels drawn before" bash -c "'$cli' render contact '$data/repulsive.txt' --colormap viridis --linear --raw --scale 3 \
  --out '$dir/raw.png' && $(declare -f same_pixels); same_pixels '$dir/raw.png' '$data/repulsive_raw.png'"

# The same field with a ring of patches under tension around its contact.
awk '{ for (i = 1; i <= NF; ++i) if ($i == 0 && NR > 3 && NR < 16 && i > 4 && i < 21) $i = -0.01 * (NR + i); print }' \
  "$data/repulsive.txt" >"$dir/adhesive.txt"
"$cli" render contact "$dir/adhesive.txt" --circle 7 --scale 6 --dpi 150 --out "$dir/adh.png"
check "tension: a second colour bar widens the figure" test "$(png_width "$dir/adh.png")" -gt "$(png_width "$dir/fig.png")"
check "tension: its PNG is not the repulsive one" bash -c "$(declare -f same_pixels); ! same_pixels '$dir/adh.png' '$dir/fig.png'"

# An animation of a repulsive and an adhesive field: both frames carry the shared tension bar (one size).
check "animate" "$cli" render animate "$data/repulsive.txt" "$dir/adhesive.txt" --frames "$dir/frames" --dpi 100 \
  --out "$dir/a.gif"
check "animate: frames of one size, with the tension bar" test "$(png_width "$dir/frames/contact_0000.png")" -eq \
  "$(png_width "$dir/frames/contact_0001.png")"
check "animate: the GIF" test -s "$dir/a.gif"
"$cli" render animate "$data/repulsive.txt" "$data/repulsive.txt" --frames "$dir/plain" --dpi 100 >/dev/null
check "animate without tension: narrower frames" test "$(png_width "$dir/plain/contact_0000.png")" -lt \
  "$(png_width "$dir/frames/contact_0000.png")"

# render view3d: the tension bar where --force has tension.
awk '{ for (i = 1; i <= NF; ++i) $i = 0; print }' "$data/repulsive.txt" >"$dir/flat.txt"
v3=("$cli" render view3d "$dir/flat.txt" --punch none --width 200 --height 150 --dpi 100)
check "view3d with tension" "${v3[@]}" --force "$dir/adhesive.txt" --out "$dir/v_adh.png"
check "view3d without tension" "${v3[@]}" --force "$data/repulsive.txt" --out "$dir/v_rep.png"
check "view3d: the tension bar widens the figure" test "$(png_width "$dir/v_adh.png")" -gt "$(png_width "$dir/v_rep.png")"

# indent --frames: an adhesive sphere's frames carry the tension bar, a repulsive one's not.
run=("$cli" indent --smooth --n 48 --punch sphere --radius 10 --approach 0.5,1 --frames)
check "indent --frames, adhesive" "${run[@]}" --adhesion-work 0.05 --adhesion-range 0.5 --out "$dir/adh_run" >/dev/null
check "indent --frames, repulsive" "${run[@]}" --out "$dir/rep_run" >/dev/null
check "indent --frames: the tension bar" test "$(png_width "$dir/adh_run/frames/contact_0000.png")" -gt \
  "$(png_width "$dir/rep_run/frames/contact_0000.png")"

finish
