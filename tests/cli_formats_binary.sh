#!/usr/bin/env bash
# TrueMap .tmd, plain HDF5 and contact.engineering containers (issue 25): each read with the numbers an
# independent reading gives (Python over the raw bytes, h5dump, the inner file read alone), and their
# damaged or lying files refused naming the field. The shared instrument files are read when
# ../shared/test-data/surfaces is beside the checkout; constructed files are checked always.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
here=$(cd "$(dirname "$0")" && pwd)
source "$here/lib.sh"
shared=${IM_TEST_SURFACES:-$here/../../shared/test-data/surfaces}

check "formats lists .tmd, .h5 and .zip" bash -c "'$cli' formats | grep -q '^  .h5 ' && '$cli' formats | grep -q '^  .zip ' && '$cli' formats | grep -q '^  .tmd '"

# ---- TrueMap .tmd: constructed files (Python writes the layout GelSight's writetmd documents) ----
# tmd FILE COMMENT COLUMNS ROWS LENGTH_X LENGTH_Y [VALUES...]: heights 10 y + x when no VALUES given.
tmd() {
  python3 - "$@" <<'PY'
import struct, sys
path, comment, nx, ny, lx, ly = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5]), float(sys.argv[6])
values = [float(v) for v in sys.argv[7:]] or [10.0 * y + x for y in range(ny) for x in range(nx)]
with open(path, "wb") as f:
    f.write(b"Binary TrueMap Data File v2.0\r\n\0" + comment.encode() + b"\0")
    f.write(struct.pack("<IIffff", nx, ny, lx, ly, 0.0, 0.0) + struct.pack("<%df" % len(values), *values))
PY
}
tmd "$dir/rows.tmd" "Synthetic" 4 3 2.0 1.5
stats "$dir/rows.tmd" >"$dir/rows" 2>&1
check "tmd: grid and spacing in mm (length / columns)" grep -q 'grid             4 x 3, delta = 0.5 mm' "$dir/rows"
check "tmd: rows are y, x fastest (heights 10 y + x: mean 11.5)" stated "$dir/rows" mean 11.5
stats "$dir/rows.tmd" --crop 0,0,3,3 >"$dir/rows3" 2>&1
check "... the first three columns: mean 11" stated "$dir/rows3" mean 11
tmd "$dir/nocomment.tmd" "" 3 3 3.0 3.0 1 2 3 4 5 6 7 8 9
check "tmd: an empty comment (writetmd's) is read" bash -c "'$cli' surface --stats '$dir/nocomment.tmd' | grep -q 'delta = 1 mm'"
head -c 100 "$dir/rows.tmd" >"$dir/cut.tmd"
check "tmd: truncated data refused" expect_exit 2 "cut.tmd: truncated data: the header (columns 4 x rows 3 float32)" \
  "$cli" surface --stats "$dir/cut.tmd"
tmd "$dir/huge.tmd" "" 4000000 3 1.0 1.0 1 2 3
check "tmd: a lying column count refused naming it" expect_exit 2 "huge.tmd: columns = 4000000, rows = 3: expected each in" \
  "$cli" surface --stats "$dir/huge.tmd"
tmd "$dir/negative.tmd" "" 3 3 -1.0 3.0 1 2 3 4 5 6 7 8 9
check "tmd: a negative length refused naming it" expect_exit 2 "negative.tmd: length x = -1: expected a positive length" \
  "$cli" surface --stats "$dir/negative.tmd"
printf 'Binary TrueMap Data File v1.0\r\n\0' >"$dir/v1.tmd"
check "tmd: another magic refused" expect_exit 2 "v1.tmd: not a TrueMap file" "$cli" surface --stats "$dir/v1.tmd"
check "tmd: --channel refused (one channel)" expect_exit 2 "holds one channel" \
  "$cli" surface --stats "$dir/rows.tmd" --channel 1

# ---- contact.engineering containers: constructed (Python's zipfile; meta.yml as contact.engineering writes it) ----
# container ZIP META_YML FILE...: a zip of meta.yml (text) and the files.
container() { python3 -c 'import sys, zipfile
z = zipfile.ZipFile(sys.argv[1], "w", zipfile.ZIP_DEFLATED); z.writestr("meta.yml", sys.argv[2])
[z.write(f, f.rsplit("/", 1)[-1]) for f in sys.argv[3:]]' "$@"; }
printf '1 2 3 4\n5 6 7 8\n2 4 6 8\n1 3 5 7\n' >"$dir/bare.txt"
meta='surfaces:
- topographies:
  - name: profile
    datafile: {original: bare.txt}
    size: !!python/tuple [10.0]
    unit: um
  - name: map
    datafile: {original: bare.txt}
    size: !!python/tuple
    - 8.0
    - 8.0
    unit: um
    height_scale: 0.5
    detrend_mode: height
'
container "$dir/c.zip" "$meta" "$dir/bare.txt"
stats "$dir/bare.txt" >"$dir/bare" 2>&1
stats "$dir/c.zip" >"$dir/c" 2>&1
check "container: the first map by default, spacing from meta.yml's size (8 um / 4)" \
  grep -q 'grid             4 x 4, delta = 2 µm' "$dir/c"
rms=$(awk '/^h_rms/ { print $2 }' "$dir/bare")
check "container: heights times height_scale 0.5 (the text alone: $rms)" stated "$dir/c" h_rms "$(awk -v r="$rms" 'BEGIN { print r / 2 }')" 1e-5
check "container: the line scan asked for is refused as one" expect_exit 2 "topography 0 'profile' is a line scan" \
  "$cli" surface --stats "$dir/c.zip" --channel profile
check "container: a topography not there lists them" expect_exit 2 "its topographies: 0 'profile' (line scan), 1 'map' (map)" \
  "$cli" surface --stats "$dir/c.zip" --channel 7
printf '# Width: 4 µm\n# Height: 4 µm\n# Value units: µm\n1 2 3 4\n5 6 7 8\n2 4 6 8\n1 3 5 7\n' >"$dir/export.txt"
container "$dir/lying.zip" "${meta//bare.txt/export.txt}" "$dir/export.txt"
check "container: a file stating another size than meta.yml's is refused" expect_exit 2 \
  "meta.yml's size 8 x 8 um differs from its file's 4e-06 x 4e-06 m" "$cli" surface --stats "$dir/lying.zip"
container "$dir/profiles.zip" "${meta//8.0/}" "$dir/bare.txt"
check "container: a malformed size is refused naming it" expect_exit 2 "meta.yml: size = '': expected a finite number" \
  "$cli" surface --stats "$dir/profiles.zip"
container "$dir/nometa.zip" "" "$dir/bare.txt"
python3 -c 'import sys, zipfile; zipfile.ZipFile(sys.argv[1], "w").write(sys.argv[2], "bare.txt")' "$dir/plain.zip" "$dir/bare.txt"
check "a zip without meta.yml is refused as no container" expect_exit 2 "plain.zip: a zip archive without meta.yml" \
  "$cli" surface --stats "$dir/plain.zip"
check "container: an empty meta.yml is refused" expect_exit 2 "expected a list 'surfaces'" \
  "$cli" surface --stats "$dir/nometa.zip"
mkdir "$dir/tmp"
TMPDIR=$dir/tmp "$cli" surface --stats "$dir/c.zip" >/dev/null 2>&1
TMPDIR=$dir/tmp "$cli" surface --stats "$dir/lying.zip" >/dev/null 2>&1
check "container: the topography's temporary copy is removed, read or refused" test -z "$(ls -A "$dir/tmp")"

# ---- HDF5 read in a child: a file that crashes libhdf5 itself (fuzz_hdf5's input) is refused, not fatal ----
crash=$here/../fuzz/regressions/hdf5/libhdf5-crash-segv-reading-group-btree.h5
check "h5: a file that crashes libhdf5 is refused naming it (exit 2, was 139)" expect_exit 2 \
  "libhdf5-crash-segv-reading-group-btree.h5: the HDF5 library (libhdf5) crashed reading it (signal 11): the file is damaged or hostile" \
  "$cli" surface --stats "$crash"
cp "$crash" "$dir/hostile.nc" # NetCDF-4 is HDF5: netCDF parsed it with libhdf5 in-process
check "nc: the same file as NetCDF-4 is refused naming it (exit 2, was 139)" expect_exit 2 \
  "hostile.nc: netCDF's HDF5 layer (libnetcdf, libhdf5) crashed reading it (signal 11): the file is damaged or hostile" \
  "$cli" surface --stats "$dir/hostile.nc"

if [ ! -d "$shared" ]; then
  echo "no $shared: the shared tmd, h5 and zip files are not checked"
  finish
  exit $?
fi

# ---- the shared files ----
stats "$shared/tmd-1.tmd" >"$dir/tmd1" 2>&1
check "tmd-1.tmd: 300 x 300 of 18.9566 mm / 300" grep -q 'grid             300 x 300, delta = 0.0631887 mm' "$dir/tmd1"
read -r mean rms < <(python3 -c 'import struct, sys
b = open(sys.argv[1], "rb").read(); nx, ny = struct.unpack("<II", b[56:64])
h = struct.unpack("<%df" % (nx * ny), b[80:]); m = sum(h) / len(h)
print(m, (sum((v - m) ** 2 for v in h) / len(h)) ** 0.5)' "$shared/tmd-1.tmd")
check "tmd-1.tmd: mean as Python reads the bytes ($mean mm)" stated "$dir/tmd1" mean "$mean"
check "tmd-1.tmd: h_rms as Python reads the bytes ($rms mm)" stated "$dir/tmd1" h_rms "$rms"

h5=$shared/multiple_data_sets.h5
stats "$h5" >"$dir/h5" 2>&1
check "h5: the first 2-D data set by default, a bare matrix" grep -q 'grid             256 x 256, delta = 1 *$' "$dir/h5"
check "h5: ... and says which" grep -q "HDF5 data set 'dataset1', channel 0 of 2" "$dir/h5"
check "h5: a data set by name, its first index x" bash -c "'$cli' surface --stats '$h5' --channel DataSet2 | grep -q 'grid             640 x 480'"
check "h5: a data set not there lists them" expect_exit 2 "its 2-D data sets: 0 'dataset1' (256 x 256), 1 'dataset2' (640 x 480)" \
  "$cli" surface --stats "$h5" --channel 2
if command -v h5dump >/dev/null; then
  # h5dump's values (17 digits): DATA rows are the first index (x), columns the second (y).
  dumped() { h5dump -m '%.17g' -d "$1" -w 0 "$h5" | awk -v nx="$2" -v ny="$3" '/DATA \{/ { d = 1; next } d && /^ *\}/ { d = 0 }
    d { sub(/^ *\([0-9]+,[0-9]+\): /, ""); gsub(/,/, " "); for (i = 1; i <= NF; ++i) { if (row < nx && i <= ny) { s += $i; n++ }; all += $i; q += $i * $i; m++ } row++ }
    END { printf "%.12g %.12g %.12g\n", all / m, sqrt(q / m - (all / m) ^ 2), s / n }'; }
  read -r mean rms block < <(dumped dataset1 16 4)
  check "h5: mean as h5dump gives ($mean)" stated "$dir/h5" mean "$mean"
  check "h5: h_rms as h5dump gives ($rms)" stated "$dir/h5" h_rms "$rms" 1e-5
  check "h5: x is the first index (16 x 4 block's mean $block)" stated <(stats "$h5" --crop 0,0,16,4) mean "$block"
fi

zip=$shared/container-2.zip
stats "$zip" >"$dir/zip" 2>&1
check "container-2.zip: its one map (the Nanoscope file), 100 nm / 512" grep -q 'grid             512 x 512, delta = 1.95312e-10 m' "$dir/zip"
check "... named" grep -q "contact.engineering topography 1 'gain_control_uncd_35.001' of 3" "$dir/zip"
if "$cli" formats | grep -q "^  nanoscope "; then
  unzip -o -q "$zip" gain_control_uncd_35_z03tr3R.001 -d "$dir"
  stats "$dir/gain_control_uncd_35_z03tr3R.001" >"$dir/inner" 2>&1
  check "... heights as the inner file read alone (height_scale is the file's own factor, not applied twice)" \
    diff <(grep -E '^(h_rms|mean)' "$dir/inner") <(grep -E '^(h_rms|mean)' "$dir/zip")
fi
check "mnt-1.mnt: refused saying it is an OLE2 document and what to export" expect_exit 2 \
  "an OLE2 (Microsoft compound) document, as Digital Surf's Mountains documents (.mnt)" "$cli" surface --stats "$shared/mnt-1.mnt"
check "container-2.zip: its line scans refused as such" expect_exit 2 "'uncd_stylus_300um_5mar_3.txt' is a line scan" \
  "$cli" surface --stats "$zip" --channel uncd_stylus_300um_5mar_3.txt
finish
