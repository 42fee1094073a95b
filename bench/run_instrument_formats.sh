#!/usr/bin/env bash
# Read time and peak memory of instrument files through Gwyddion's modules (indentmap-gwyddion-read),
# against the same heights as .npy: median of REPEATS reads through the library (Python's im.read, one
# process), and the reader program's peak resident memory (/usr/bin/time).
#   bench/run_instrument_formats.sh BUILD_DIR [SURFACES_DIR] [REPEATS]
set -euo pipefail
build=${1:?build folder}
surfaces=${2:-$(dirname "$0")/../../shared/test-data/surfaces}
repeats=${3:-7}
reader=$build/indentmap-gwyddion-read
[ -x "$reader" ] || { echo "no $reader (IM_GWYDDION off)"; exit 77; }
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); median of $repeats reads"
printf '%-20s %10s %9s %10s %10s %8s %12s\n' file bytes grid gwyddion_ms npy_ms ratio reader_rss_MB
for file in opd-1.opd plu-1.plu bcrf-1.bcrf spot_1-1000nm.ibw di-1.di nid-1.nid metropro-1.dat sur-2.sur example_ps.tiff; do
  path=$surfaces/$file
  [ -f "$path" ] || continue
  rss=$(/usr/bin/time -f '%M' "$reader" -- "$path" 2>&1 >/dev/null | tail -1)
  INDENTMAP_GWYDDION_READER=$reader PYTHONPATH=$build/python /usr/bin/python3 - "$path" "$repeats" "$rss" <<'PY'
import os, statistics, sys, tempfile, time
import numpy as np
import indentmap as im
path, repeats, rss = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
def median_ms(read):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        read()
        times.append(1e3 * (time.perf_counter() - start))
    return statistics.median(times)
surface = im.read(path, fill=True)
npy = os.path.join(tempfile.mkdtemp(), "same.npy")
np.save(npy, surface.heights)
gwy = median_ms(lambda: im.read(path, fill=True))
plain = median_ms(lambda: im.read(npy))
ny, nx = surface.heights.shape
print(f"{os.path.basename(path):20s} {os.path.getsize(path):10d} {nx:4d}x{ny:<4d} {gwy:10.1f} {plain:10.2f} {gwy / plain:8.0f} {rss / 1024:12.1f}")
PY
done
