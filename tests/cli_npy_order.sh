#!/usr/bin/env bash
# .npy arrays indexed [x, y], as SurfaceTopography's heights() are (issue 25, D15): --npy-order on
# surface --stats and indent, and a sidecar's "order", on a 128 x 64 grid stored with shape (128, 64).
# The values themselves: tests/test_gsf_npy_layouts.c.
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

finish
