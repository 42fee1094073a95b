#!/usr/bin/env bash
# .npy arrays indexed [x, y], as SurfaceTopography's heights() are (issue 25, D15): --npy-order on
# surface --stats and indent, a sidecar's "order", and a scene's npy_order, on a 128 x 64 grid stored
# with shape (128, 64). The values themselves: tests/test_gsf_npy_layouts.c.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

source "$(dirname "$0")/lib.sh"

# 64 columns by 128 rows as written: shape (128, 64), which an [x, y] reading makes 128 x 64.
"$cli" surface --n 64 --m 128 --slope 0.1 --out "$dir/xy.npy" >/dev/null
grid() { "$cli" surface --stats "$@" | awk '/^grid/ { sub(",", "", $4); print $2 "x" $4 }'; }
check "rows along y by default: 64 x 128" test "$(grid "$dir/xy.npy")" = "64x128"
check "--npy-order xy: 128 x 64" test "$(grid "$dir/xy.npy" --npy-order xy)" = "128x64"
check "--npy-order yx: 64 x 128" test "$(grid "$dir/xy.npy" --npy-order yx)" = "64x128"
check "--npy-order xy: the reading is stated" bash -c "'$cli' surface --stats '$dir/xy.npy' --npy-order xy |
  grep -q '^values  *indexed \[x, y\]'"
check "--crop along the 128 x side" bash -c \
  "'$cli' surface --stats '$dir/xy.npy' --npy-order xy --crop 100,0,28,64 >/dev/null"
check "--npy-order zz is refused" expect_exit 2 "--npy-order 'zz': expected yx (rows are y) or xy" \
  "$cli" surface --stats "$dir/xy.npy" --npy-order zz

"$cli" indent "$dir/xy.npy" --npy-order xy --approach 0.5 --out "$dir/indent" >/dev/null 2>&1
check "indent --npy-order xy runs" test $? -eq 0
check "run.json: the grid 128 x 64" grep -q '"nx": 128' "$dir/indent/run.json"
check "run.json: how the values were read" grep -q '"values": "indexed \[x, y\]"' "$dir/indent/run.json"

# The sidecar's "order" (here with delta and unit) is the default; the option overrides it.
sed 's/^{/{"order": "xy", /' "$dir/xy.npy.json" >"$dir/tmp.json" && mv "$dir/tmp.json" "$dir/xy.npy.json"
check "sidecar order xy: 128 x 64" test "$(grid "$dir/xy.npy")" = "128x64"
check "--npy-order yx overrides the sidecar" test "$(grid "$dir/xy.npy" --npy-order yx)" = "64x128"

# A scene's npy_order reaches every file: xy.npy (sidecar: xy) and rows.npy (128 x 64, rows along y)
# share one grid as their sidecars say, not when npy_order overrides both.
"$cli" surface --n 128 --m 64 --slope 0.1 --seed 3 --out "$dir/rows.npy" >/dev/null
scene() { # scene NAME [KEY-LINE]
  printf '[scene]\nname = %s\noutput = %s\n[surfaces]\nfile = xy.npy, rows.npy\n%s\n[loading]\nload_star = 100\n[output]\ntable = yes\n' \
    "$1" "$1" "${2:-}" >"$dir/$1.ini"
}
scene sidecar
"$cli" run --quiet "$dir/sidecar.ini" >/dev/null 2>&1
check "scene: the sidecars' orders give one grid" test $? -eq 0
check "scene: run.json records npy_order" grep -q '"npy_order": "sidecar"' "$dir/sidecar/run.json"
scene yx "npy_order = yx"
check "scene: npy_order = yx overrides the sidecar" expect_exit 2 "is 128 x 64 with delta" \
  "$cli" run --quiet "$dir/yx.ini"
scene bad "npy_order = zx"
check "scene: npy_order = zx is refused" expect_exit 2 "npy_order = 'zx': expected one of sidecar|yx|xy" \
  "$cli" run --quiet "$dir/bad.ini"

finish
