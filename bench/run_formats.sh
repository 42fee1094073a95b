#!/usr/bin/env bash
# Surface formats benchmark (issues 13 and 25): read time (median of REPEATS) and peak RSS of an N x N
# surface in each format, each format in its own process. The formats indentmap reads but does not
# write are made from the .npy: .tmd by NumPy (float32, in mm), .h5 by h5import (hdf5-tools), a
# contact.engineering container by Python's zipfile (stored, so that the copy is the cost). Prints CSV
# with the ratio of each to .npy:
# format,n,repeats,median_s,min_s,peak_rss_mib,field_mib,time_ratio_to_npy,rss_ratio_to_npy
#   bench/run_formats.sh [N (4096)] [REPEATS (5)]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
n=${1:-4096}
repeats=${2:-5}
cmake --build "$build" --target bench_formats >/dev/null
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$build/bench_formats" "$n" 1 "$dir" write
/usr/bin/python3 - "$dir" <<'PY'
import numpy as np, struct, sys, zipfile
d = sys.argv[1]; h = np.load(d + "/s.npy"); ny, nx = h.shape
with open(d + "/s.tmd", "wb") as f:
    f.write(b"Binary TrueMap Data File v2.0\r\n\0\0" + struct.pack("<IIffff", nx, ny, nx * 1e-5, ny * 1e-5, 0, 0))
    f.write((h * 1e3).astype("<f4").tobytes())
np.ascontiguousarray(h.T).astype("<f8").tofile(d + "/h.bin")  # [x, y], as SurfaceTopography reads HDF5
with zipfile.ZipFile(d + "/s.zip", "w", zipfile.ZIP_STORED) as z:
    z.writestr("meta.yml", "surfaces:\n- topographies:\n  - name: s\n    datafile: {original: s.npy}\n"
               "    size: [%g, %g]\n    unit: m\n" % (nx * 1e-8, ny * 1e-8))
    z.write(d + "/s.npy", "s.npy")
PY
printf 'PATH heights\nINPUT-CLASS FP\nINPUT-SIZE 64\nINPUT-BYTE-ORDER LE\nRANK 2\nDIMENSION-SIZES %d %d\nOUTPUT-CLASS FP\nOUTPUT-SIZE 64\nOUTPUT-ARCHITECTURE IEEE\nOUTPUT-BYTE-ORDER LE\n' \
  "$n" "$n" >"$dir/h.conf"
h5import "$dir/h.bin" -c "$dir/h.conf" -o "$dir/s.h5"
rm "$dir/h.bin"
ls -l "$dir" >&2
for format in npy nc x3p sdf gsf tmd h5 zip; do
  "$build/bench_formats" "$n" "$repeats" "$dir" "$format"
done | awk -F, 'BEGIN { print "format,n,repeats,median_s,min_s,peak_rss_mib,field_mib,time_ratio_to_npy,rss_ratio_to_npy" }
  $1 == "npy" { t = $4; m = $6 } { printf "%s,%.2f,%.2f\n", $0, $4 / t, $6 / m }'
