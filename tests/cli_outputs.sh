#!/usr/bin/env bash
# Outputs never destroy inputs or unrelated files: every writing option of every subcommand is given
# an input (or its sidecar, or a file of another kind) as its output; each must be refused with
# exit 2 and the file left byte for byte as it was. Also: the FFTW wisdom file (--wisdom,
# IM_FFTW_WISDOM) is neither an input, nor an output, nor anything but wisdom; standard output is
# checked to the end; a scene's name cannot lead outside output/; duplicate seeds are refused.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
export OMP_NUM_THREADS=1
cd "$dir" || exit 1

"$cli" surface --n 32 --seed 3 --out s.npy >/dev/null || exit 1
"$cli" indent s.npy --approach 0.5 --fields --out made >/dev/null || exit 1
cp made/force_0001.npy f.npy
printf '[scene]\nname = kept\n[surfaces]\nn = 32\n' >scene.ini
mkdir keep && cp s.npy s.npy.json f.npy scene.ini keep/

# refused CODE PHRASE FILE COMMAND...: exits CODE with PHRASE on stderr and FILE unchanged.
refused() {
  local code=$1 phrase=$2 file=$3; shift 3
  expect_exit "$code" "$phrase" "$@" && cmp -s "$file" "keep/$(basename "$file")"
}
over="would overwrite"

# surface: each output option onto the measured file, its sidecar, another name of it
for option in --out --png --psd --histograms; do
  check "surface $option onto the input" refused 2 "$over the input file" s.npy "$cli" surface --stats s.npy $option s.npy
  check "surface $option onto the input's sidecar" refused 2 "the sidecar of the input file" s.npy.json \
    "$cli" surface --stats s.npy $option s.npy.json
done
mkdir sub && ln -s ../s.npy sub/link.npy && ln s.npy hard.npy
check "surface --png onto ./sub/../s.npy" refused 2 "$over" s.npy "$cli" surface --stats s.npy --png ./sub/../s.npy
check "surface --png onto a symlink to the input" refused 2 "$over" s.npy "$cli" surface --stats s.npy --png sub/link.npy
check "surface --psd onto a hard link of the input" refused 2 "$over" s.npy "$cli" surface --stats s.npy --psd hard.npy
check "surface --out whose sidecar is the input" refused 2 "$over" s.npy.json "$cli" surface --stats s.npy.json --out s.npy
# files of another kind than the one written, inputs or not
check "surface --psd onto a scene file" refused 2 "holds an INI file" scene.ini "$cli" surface --stats s.npy --psd scene.ini
check "surface --png onto a surface" refused 2 "holds a NumPy array" f.npy "$cli" surface --stats s.npy --png f.npy
check "surface --out (.npy) onto a scene file" refused 2 "holds an INI file" scene.ini "$cli" surface --n 16 --out scene.ini
check "surface --out .npy over a surface: allowed" bash -c "'$cli' surface --n 16 --out again.npy >/dev/null"
check "... and again, same kind" bash -c "'$cli' surface --n 16 --out again.npy >/dev/null"

# indent: the run's files in --out, --fields, --wisdom
mkdir -p d1 d2 && cp s.npy d1/history.csv && cp s.npy d2/force_0001.npy && cp s.npy keep/history.csv && cp s.npy keep/force_0001.npy
check "indent --out holding the input as history.csv" refused 2 "over the input file" d1/history.csv \
  "$cli" indent d1/history.csv --approach 1 --out d1
check "indent --fields onto the input" refused 2 "over the input file" d2/force_0001.npy \
  "$cli" indent d2/force_0001.npy --approach 1 --fields --out d2
check "indent --wisdom onto the input" refused 2 "not FFTW wisdom" s.npy "$cli" indent s.npy --approach 1 --wisdom s.npy --out o1
check "indent --wisdom onto a scene file" refused 2 "holds an INI file" scene.ini \
  "$cli" indent s.npy --approach 1 --wisdom scene.ini --out o2
check "indent --wisdom onto one of its outputs" expect_exit 2 "would be one of the run's outputs" \
  "$cli" indent s.npy --approach 1 --wisdom o3/history.csv --out o3
check "IM_FFTW_WISDOM onto the input" refused 2 "IM_FFTW_WISDOM s.npy" s.npy \
  env IM_FFTW_WISDOM=s.npy "$cli" indent s.npy --approach 1 --out o4
check "indent --wisdom of a device" expect_exit 2 "is not a regular file" "$cli" indent s.npy --approach 1 --wisdom /dev/zero --out o5
check "indent --wisdom: a new file is written" bash -c "'$cli' indent s.npy --approach 1 --wisdom w.wisdom --out o6 >/dev/null && head -c 6 w.wisdom | grep -q '(fftw-'"
check "indent --wisdom: wisdom is replaced by wisdom" bash -c "'$cli' indent s.npy --approach 1 --wisdom w.wisdom --out o6 >/dev/null"

# render: --out, --contact, --frames
check "render contact --out onto the input" refused 2 "$over the input file" f.npy "$cli" render contact f.npy --out f.npy
check "render height --out onto --contact" refused 2 "$over the input file" f.npy \
  "$cli" render height s.npy --contact f.npy --out f.npy
check "render --out onto an input's sidecar" refused 2 "the sidecar of the input file" s.npy.json \
  "$cli" render height s.npy --out s.npy.json
mkdir -p frames && cp f.npy frames/contact_0000.png && cp f.npy keep/contact_0000.png
check "render animate --frames onto the input" refused 2 "$over the input file" frames/contact_0000.png \
  "$cli" render animate frames/contact_0000.png --frames frames
check "render animate --out onto the input" refused 2 "$over the input file" f.npy \
  "$cli" render animate f.npy --frames frames2 --out f.npy
cp scene.ini scene.png && cp scene.png keep/
check "render --out onto a scene file" refused 2 "holds an INI file" scene.png "$cli" render contact f.npy --out scene.png

# run: the scene, its surface file, the wisdom, the name
printf '[scene]\noutput = here\n[surfaces]\nfile = s.npy\n[loading]\nsteps = 1, 2\n[output]\nplots = fig5\n' >file.ini
cp file.ini keep/
check "run: IM_FFTW_WISDOM onto the scene" refused 2 "IM_FFTW_WISDOM scene.ini" scene.ini \
  env IM_FFTW_WISDOM=scene.ini "$cli" run scene.ini
check "run: IM_FFTW_WISDOM onto the surface file" refused 2 "IM_FFTW_WISDOM s.npy" s.npy \
  env IM_FFTW_WISDOM=s.npy "$cli" run file.ini
check "run: IM_FFTW_WISDOM in the output folder" expect_exit 2 "lies in the output folder here" \
  env IM_FFTW_WISDOM=here/w.wisdom "$cli" run file.ini
check "... nothing written" test ! -e here
check "run: output holding the scene" refused 2 "would hold the scene file" file.ini \
  bash -c "sed 's/^output = here/output = ./' file.ini >dot.ini && cp dot.ini keep/ && '$cli' run dot.ini"
printf '[scene]\nname = ../../escape\n' >name.ini
mkdir deep # run from here, output/../../escape would be $dir/escape
check "run: name = ../../escape" expect_exit 2 "name.ini:2: name = '../../escape': expected a plain name" \
  bash -c "cd deep && '$cli' run ../name.ini"
check "run: nothing written outside output/" test ! -e escape -a ! -e deep/output
printf '[scene]\nname = twice\n[surfaces]\nn = 32\nseeds = 1,2,1\n' >seeds.ini
check "run: duplicate seeds" expect_exit 2 "seeds.ini:5: seeds = '1,2,1': seed 1 is given twice" "$cli" run seeds.ini

# an output that is a symbolic link is written through it (reliability finding 1): the link stays, its
# target holds what a plain write of the same name holds; a dangling link's target is made; a loop is
# refused naming the path
mkdir -p links/target links/plain
written_through() { # written_through LINK PLAIN: LINK still a link, its target equal to PLAIN
  test -L "$1" && cmp -s "$(readlink -f "$1")" "$2"
}
for name in s.npy s.png s.csv s.x3p; do ln -s "target/$name" "links/$name"; done
"$cli" surface --n 16 --seed 5 --out links/plain/s.npy >/dev/null
cp links/plain/s.npy links/target/s.npy # an old file under the link, of the same kind
"$cli" surface --n 16 --seed 4 --out links/s.npy >/dev/null # replaced through the link
"$cli" surface --n 16 --seed 4 --out links/plain/s.npy >/dev/null
check "surface --out through a symlink" written_through links/s.npy links/plain/s.npy
"$cli" surface --stats s.npy --psd links/s.csv >/dev/null && "$cli" surface --stats s.npy --psd links/plain/s.csv >/dev/null
check "surface --psd through a dangling symlink: its target made" written_through links/s.csv links/plain/s.csv
"$cli" surface --n 16 --delta 0.1 --unit um --out links/s.x3p >/dev/null
check "surface --out .x3p through a symlink" bash -c "test -L links/s.x3p && '$cli' surface --stats links/target/s.x3p >/dev/null"
"$cli" render contact f.npy --out links/s.png >/dev/null # (its text chunks name the path given)
check "render --out through a symlink" bash -c "test -L links/s.png && head -c 4 links/target/s.png | grep -q PNG"
mkdir -p linked && ln -s ../links/target/history.csv linked/history.csv
"$cli" indent s.npy --approach 0.5 --out linked >/dev/null
check "indent's history.csv through a symlink" bash -c "test -L linked/history.csv && grep -q '^step,' links/target/history.csv"
ln -s loop.b links/loop.a && ln -s loop.a links/loop.b
check "a loop of symbolic links refused, naming the path" expect_exit 2 \
  "links/loop.a: a loop of symbolic links" "$cli" surface --n 16 --out links/loop.a
check "... and left as it was" test "$(readlink links/loop.a)" = loop.b

# standard output is checked to the end
check "theory > /dev/full: exit 1" expect_exit 1 "standard output: write failed: No space left on device" \
  bash -c "'$cli' theory --rho 0.01:100:2000 --format csv >/dev/full"
check "surface --stats > /dev/full: exit 1" expect_exit 1 "standard output: write failed" \
  bash -c "'$cli' surface --stats s.npy >/dev/full"
check "--version > /dev/full: exit 1" expect_exit 1 "standard output" bash -c "'$cli' --version >/dev/full"

check "inputs unchanged at the end" bash -c "cmp s.npy keep/s.npy && cmp s.npy.json keep/s.npy.json && cmp f.npy keep/f.npy && cmp scene.ini keep/scene.ini"
finish
