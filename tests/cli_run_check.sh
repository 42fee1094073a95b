#!/usr/bin/env bash
# run --check (docs/scenes.md, "Checking a scene"): the bundled scenes pass it and nothing is written
# anywhere (the working folder, the scenes' folder, the wisdom cache); the outputs it lists are the files a
# real run of the scene writes (tiny scenes: table and histories, a sweep, and frames with panels where
# OpenGL is there); a bad key, a missing file and a scene too large for memory give the run's own error
# and exit status; the memory and disk estimates it prints are the numbers the run refuses with.
set -u
cli=$1
source_dir=$(cd "$(dirname "$0")/.." && pwd)
dir=$(mktemp -d)
trap "" EXIT
source "$(dirname "$0")/lib.sh"

# ---- the bundled scenes: exit 0, nothing written (the wisdom cache looked at, not made) ----
tree() { (cd "$1" && find . -path ./.git -prune -o -print | sort); }
mkdir "$dir/work" "$dir/home"
tree "$source_dir" >"$dir/source.before"
for scene in "$source_dir"/scenes/*.ini; do
  name=$(basename "$scene" .ini)
  (cd "$dir/work" && env -u IM_FFTW_WISDOM HOME="$dir/home" XDG_CACHE_HOME= "$cli" run "$scene" --check \
    >"$dir/$name.check" 2>"$dir/$name.check_err")
  check "$name: --check exits 0" test $? -eq 0
  check "$name: --check reports" grep -q "^indentmap run --check: scene $name would run" "$dir/$name.check"
  check "$name: --check lists run.json" grep -q "^  run.json$" "$dir/$name.check"
done
tree "$source_dir" >"$dir/source.after"
check "bundled scenes: nothing written beside the sources" diff "$dir/source.before" "$dir/source.after"
check "bundled scenes: nothing written in the working folder" test -z "$(ls -A "$dir/work")"
check "bundled scenes: no wisdom cache made" test -z "$(ls -A "$dir/home")"

# ---- the outputs listed are those a run writes ----
# same_list SCENE: every file the run wrote (but its lock) matches one line of --check's list, and every
# line matches a file; a line may name several files (", "), NNNN/MMMM a number, FF a family, SEED a seed,
# {a,b} either.
same_list() {
  python3 - "$dir/$1.check" "$dir/out_$1" <<'PY'
import os, re, sys
listed = []
for line in open(sys.argv[1]).read().split("outputs under", 1)[1].splitlines()[1:]:
    if not line.startswith("  "):
        break
    for name in re.split(r"  \(", line.strip())[0].split(", "):
        pattern = re.escape(name)
        pattern = re.sub(r"\\\{([^}]*)\\\}", lambda m: "(" + m.group(1).replace(",", "|") + ")", pattern)
        for word, number in (("NNNN", "[0-9]{4}"), ("MMMM", "[0-9]{4}"), ("FF", "[0-9]{2}"), ("SEED", "[0-9]+")):
            pattern = pattern.replace(word, number)
        listed.append((name, re.compile(pattern + "$")))
written = sorted(os.path.relpath(os.path.join(root, f), sys.argv[2])
                 for root, _, files in os.walk(sys.argv[2]) for f in files if f != ".lock")
unlisted = [f for f in written if not any(p.match(f) for _, p in listed)]
unwritten = [n for n, p in listed if not any(p.match(f) for f in written)]
for f in unlisted:
    print("written, not listed:", f)
for n in unwritten:
    print("listed, not written:", n)
sys.exit(1 if unlisted or unwritten or not written else 0)
PY
}

scene() { # scene NAME SURFACES LOADING OUTPUT: a tiny scene writing to out_NAME
  printf "[scene]\nname = %s\noutput = out_%s\n[surfaces]\n%b\n[punch]\nshape = cone\nalpha = 80\n[loading]\n%b\n[output]\n%b\n" \
    "$1" "$1" "$2" "$3" "$4" >"$dir/$1.ini"
}
checked_then_run() { # checked_then_run NAME: --check, then the run; 0 when both passed
  "$cli" run "$dir/$1.ini" --check >"$dir/$1.check" 2>"$dir/$1.check_err" && test ! -e "$dir/out_$1" &&
    "$cli" run --quiet "$dir/$1.ini" >/dev/null 2>"$dir/$1.err"
}
scene histories "n = 32\nslopes = 0, 0.08\nseeds = 5:6" "control = load\nload_star = 100\nsteps = 20:100:3" \
  "table = yes\nplots = fig1, fig2, fig3, fig5, fig6, fig7"
check "histories: --check writes nothing, then the run" checked_then_run histories
check "histories: the outputs listed are those written" same_list histories
scene unloading "n = 32\nslopes = 0.08\nseeds = 1" "control = displacement\nsteps = 0.5, 1, 0.5" \
  "plots = fig5\n[material]\nhardness = 0.5"
check "unloading: --check writes nothing, then the run" checked_then_run unloading
check "unloading: the outputs listed are those written" same_list unloading
"$cli" surface --n 48 --m 40 --slope 0.08 --seed 1 --out "$dir/s1.npy" >/dev/null &&
  "$cli" surface --n 48 --m 40 --slope 0.08 --seed 2 --out "$dir/s2.npy" >/dev/null
scene files "file = s1.npy, s2.npy" "control = load\nload_star = 100" "table = yes\nplots = fig3"
check "files: --check writes nothing, then the run" checked_then_run files
check "files: the outputs listed are those written" same_list files
check "files: each read as the run reads it" test "$(grep -c "^  file $dir/s[12].npy: 48 x 40, spacing 1 " "$dir/files.check")" -eq 2
scene adhesive "n = 32\nslopes = 0, 0.08\nseeds = 1" "control = displacement\nsteps = 0.2, 0.4, 0.2" \
  "plots = fig5, fig6\n[adhesion]\nwork = 0.0001\nrange = 0.2\n[material]\nhardness = 0.5"
sed -i 's/^shape = cone$/shape = sphere/; s/^alpha = 80$/radius = 100/' "$dir/adhesive.ini"
check "adhesive, unloaded: --check writes nothing, then the run" checked_then_run adhesive
check "adhesive, unloaded: the outputs listed are those written" same_list adhesive
scene sphere "n = 32\nslopes = 0.08\nseeds = 1:2" "control = load\nsteps = 20:100:3" "plots = sphere"
sed -i 's/^shape = cone$/shape = sphere/; s/^alpha = 80$/radius = 100/' "$dir/sphere.ini"
check "sphere: --check writes nothing, then the run" checked_then_run sphere
check "sphere: the outputs listed are those written" same_list sphere
scene sweep "n = 32\nslopes = 0.08\nseeds = 1:2\nlambda_s = 4, 8" "control = load\nload_star = 60" \
  "table = yes\nplots = fig2"
check "sweep: --check writes nothing, then the run" checked_then_run sweep
check "sweep: the outputs listed are those written" same_list sweep
scene periodic "n = 32\nslopes = 0.08\nseeds = 1:2" "steps = 0.002:0.01:3" "plots = fig3"
sed -i 's/^shape = cone$/periodic = yes/; /^alpha = 80$/d' "$dir/periodic.ini" # a rigid flat on the cell
check "periodic: --check writes nothing, then the run" checked_then_run periodic
check "periodic: the outputs listed are those written" same_list periodic
scene rendered "n = 32\nslopes = 0, 0.08\nseeds = 1" "control = load\nload_star = 100" \
  "contact_panels = yes\nframes = yes\nframe_count = 3\nanimation = gif\ndistributions = yes\nplots = density"
scene periodic_maps "n = 32\nslopes = 0.08\nseeds = 1:2" "steps = 0.002:0.01:2" \
  "contact_panels = yes\ndistributions = yes\n[material]\nhardness = 0.5"
sed -i 's/^shape = cone$/periodic = yes/; /^alpha = 80$/d' "$dir/periodic_maps.ini"
# every kind of output one cone scene can have (a new output missing from the listing fails here)
every="table = yes\ncontact_panels = yes\nframes = yes\nframe_count = 2\nframes3d = yes\nanimation = gif"
every+="\ndistributions = yes\nplots = fig1, fig2, fig3, fig5, fig6, fig7, flat_k, density"
scene every "n = 32\nslopes = 0, 0.08\nseeds = 1" "control = load\nload_star = 100\nsteps = 20:100:2" "$every"
if checked_then_run rendered; then
  check "rendered: the outputs listed are those written" same_list rendered
  check "every output: --check writes nothing, then the run" checked_then_run every
  check "every output: the outputs listed are those written" same_list every
  check "periodic maps: --check writes nothing, then the run" checked_then_run periodic_maps
  check "periodic maps: the outputs listed are those written" same_list periodic_maps
elif grep -qs "rendering with" "$dir/rendered.err" ||
  ! grep -qs "OpenGL\|EGL\|OSMesa\|render" "$dir/rendered.check_err" "$dir/rendered.err"; then # both refuse before any work
  check "rendered: --check writes nothing, then the run ($(cat "$dir"/rendered.*err | tail -1))" false
else
  echo "rendered: no OpenGL context here, not compared ($(cat "$dir"/rendered.*err | tail -1))"
fi

# --resume's reuse: a kept member is reused; one edited is named, solved again
check "kept members: reused by --resume" grep -q "^  table/member_01_6.csv  (kept: --resume reuses it)$" \
  <("$cli" run "$dir/histories.ini" --check 2>/dev/null)
sed -i '2s/^1,/2,/' "$dir/out_histories/table/member_01_6.csv"
"$cli" run "$dir/histories.ini" --check >"$dir/edited.check" 2>"$dir/edited.err"
check "an edited member: not reused" grep -q "^  table/member_01_6.csv$" "$dir/edited.check"
check "an edited member: the run's notice" grep -q "member_01_6.csv is damaged" "$dir/edited.err"

# ---- under mpirun (MPI builds with an mpiexec): rank 0 reports, each member on one rank; the list is the
# files the ranks' run writes; a sweep is refused as the run refuses it. Not on a sanitizer build: Open MPI's
# kept allocations need tests/mpi/mpi_lsan.supp, the renderer's above render_lsan.supp (one file a process);
# cli_mpi and mpi_scene run scenes over ranks there. ----
mpiexec=$(command -v mpiexec || command -v mpirun)
if ldd "$cli" 2>/dev/null | grep -q libasan; then
  echo "mpirun: not run on a sanitizer build"
elif "$cli" --help | grep -q mpi-indent && [ -n "$mpiexec" ]; then
  source "$(dirname "$0")/mpi/open_mpi_env.sh"
  sed 's/^output = out_histories$/output = out_ranks/; s/^name = histories$/name = ranks/' "$dir/histories.ini" >"$dir/ranks.ini"
  "$mpiexec" -n 2 --oversubscribe "$cli" run "$dir/ranks.ini" --check >"$dir/ranks.check" 2>"$dir/ranks.check_err"
  check "mpirun: --check exits 0" test $? -eq 0
  check "mpirun: rank 0 alone reports" test "$(grep -c "would run" "$dir/ranks.check")" -eq 1
  shares=$(sed -n 's/^  rank [01]: //p' "$dir/ranks.check" | tr ',' '\n' | sed 's/^ *//' | sort)
  members=$(sed -n 's|^  histories/member_\([0-9]*\)_\([0-9]*\)\.csv.*|family \1 seed \2|p' "$dir/ranks.check" | sort)
  check "mpirun: each member on one rank" test -n "$members" -a "$shares" = "$members"
  check "mpirun: nothing written" test ! -e "$dir/out_ranks"
  "$mpiexec" -n 2 --oversubscribe "$cli" run --quiet "$dir/ranks.ini" >/dev/null 2>"$dir/ranks.err"
  check "mpirun: the ranks' run" test $? -eq 0
  check "mpirun: the outputs listed are those written" same_list ranks
  "$mpiexec" -n 2 --oversubscribe "$cli" run --quiet "$dir/sweep.ini" >/dev/null 2>"$dir/sweep_ranks.run_err"
  run_status=$?
  "$mpiexec" -n 2 --oversubscribe "$cli" run "$dir/sweep.ini" --check >/dev/null 2>"$dir/sweep_ranks.check_err"
  check "mpirun: a sweep refused as the run refuses it" test $run_status -ne 0 -a $? -eq $run_status
  check "mpirun: the run's message" diff <(grep "^indentmap:" "$dir/sweep_ranks.run_err") \
    <(grep "^indentmap:" "$dir/sweep_ranks.check_err") # not mpirun's own lines (its job ids)
  check "mpirun: the sweep named" grep -q "sweep .* runs in a single process" "$dir/sweep_ranks.check_err"
  # a surface file that is another on rank 1 (node_local.npy, a link to each rank's fd 8, as cli_mpi.sh has it)
  "$cli" surface --n 32 --seed 1 --out "$dir/h1.npy" >/dev/null && "$cli" surface --n 32 --seed 2 --out "$dir/h2.npy" >/dev/null
  ln -s /proc/self/fd/8 "$dir/node_local.npy"
  scene node_local "file = h1.npy, node_local.npy" "load_star = 100" "table = yes"
  on_fd8() { echo "exec '$cli' run '$dir/node_local.ini' $2 8< '$1'"; } # on_fd8 FILE OPTION: a rank's command
  "$mpiexec" --oversubscribe -n 1 bash -c "$(on_fd8 "$dir/h1.npy" --quiet)" : -n 1 bash -c "$(on_fd8 "$dir/h2.npy" --quiet)" \
    >/dev/null 2>"$dir/node_local.run_err"
  run_status=$?
  "$mpiexec" --oversubscribe -n 1 bash -c "$(on_fd8 "$dir/h1.npy" --check)" : -n 1 bash -c "$(on_fd8 "$dir/h2.npy" --check)" \
    >"$dir/node_local.check" 2>"$dir/node_local.check_err"
  check "mpirun: a file another on rank 1: refused as the run refuses it" test $run_status -ne 0 -a $? -eq $run_status
  check "mpirun: a file another on rank 1: the run's message" grep -q "node_local.npy (\[surfaces\] file): rank 1 reads other bytes" \
    "$dir/node_local.check_err"
  check "mpirun: a file another on rank 1: no report" test ! -s "$dir/node_local.check"
else
  echo "mpirun: not compared (a build without MPI, or no mpiexec)"
fi

# ---- refusals: the run's own error and exit status, and nothing written ----
same_refusal() { # same_refusal NAME: run and run --check exit alike (not 0) with the same stderr (the memory
  # available capped, so that both state the same)
  IM_MEMORY_LIMIT_MIB=4096 "$cli" run --quiet "$dir/$1.ini" >/dev/null 2>"$dir/$1.run_err"
  local run=$?
  IM_MEMORY_LIMIT_MIB=4096 "$cli" run "$dir/$1.ini" --check >"$dir/$1.check" 2>"$dir/$1.check_err"
  local checked=$?
  [ "$run" -ne 0 ] && [ "$run" -eq "$checked" ] && diff "$dir/$1.run_err" "$dir/$1.check_err" &&
    test ! -s "$dir/$1.check" && test ! -e "$dir/out_$1"
}
scene badkey "n = 32\nslopes = 0.08\nseeds = 1\nhurts = 0.8" "load_star = 100" "table = yes"
check "a bad key: the run's error" same_refusal badkey
check "a bad key: names file, line and key" grep -q "badkey.ini:8: .*hurts" "$dir/badkey.check_err"
scene nofile "file = missing.npy" "load_star = 100" "table = yes"
check "a missing file: the run's error" same_refusal nofile
check "a missing file: named" grep -q "missing.npy" "$dir/nofile.check_err"
scene memory "n = 65536\nslopes = 0.08\nseeds = 1" "load_star = 1000" "table = yes"
check "too large for memory: the run's error" same_refusal memory
check "too large for memory: the estimate" grep -q "memory.ini: this scene needs about [0-9.]* MiB of memory" \
  "$dir/memory.check_err"

# ---- refused before any work by both, as the run would refuse them (the run writes nothing either) ----
scene smooth_sphere "n = 32\nslopes = 0\nseeds = 1" "control = load\nsteps = 20:100:2" "plots = sphere"
sed -i 's/^shape = cone$/shape = sphere/; s/^alpha = 80$/radius = 100/' "$dir/smooth_sphere.ini"
check "plots = sphere, no rough family: the run's error" same_refusal smooth_sphere
check "plots = sphere, no rough family: named" grep -q "plots = sphere needs a rough family" \
  "$dir/smooth_sphere.check_err"
scene smooth_fig7 "n = 32\nslopes = 0\nseeds = 1" "control = load\nsteps = 20:100:2" "plots = fig7"
check "plots = fig7, no rough family: the run's error" same_refusal smooth_fig7
scene smooth_flat_k "n = 32\nslopes = 0\nseeds = 1" "control = load\nload_star = 100" "plots = flat_k"
check "plots = flat_k, no rough family: the run's error" same_refusal smooth_flat_k
check "plots = flat_k, no rough family: named" grep -q "flat_k measures k on rough surfaces" \
  "$dir/smooth_flat_k.check_err"
scene groups "n = 32\nslopes = 0.02, 0.04, 0.06, 0.08, 0.1\nseeds = 1\nhurst = 0.7, 0.8" \
  "control = load\nload_star = 60" "table = yes\nplots = fig2" # 5 x 2 roughnesses, fig2 draws at most 8
check "fig2 of a sweep, too many roughnesses: the run's error" same_refusal groups
check "fig2 of a sweep, too many roughnesses: named" grep -q "fig2 of a sweep draws at most" "$dir/groups.check_err"
scene folder_file "n = 32\nslopes = 0.08\nseeds = 1" "load_star = 100" "table = yes"
echo "not a folder" >"$dir/plain"
sed -i "s|^output = out_folder_file$|output = $dir/plain|" "$dir/folder_file.ini"
check "output a regular file: the run's error" same_refusal folder_file
check "output a regular file: named" grep -q "output folder $dir/plain is not a directory" "$dir/folder_file.check_err"
scene file_parent "n = 32\nslopes = 0.08\nseeds = 1" "load_star = 100" "table = yes"
sed -i "s|^output = out_file_parent$|output = $dir/plain/deeper/out|" "$dir/file_parent.ini"
check "output under a regular file: the run's error" same_refusal file_parent
check "output under a regular file: named" grep -q "nearest existing parent, $dir/plain, is not a directory" \
  "$dir/file_parent.check_err"
mkdir -p "$dir/readonly" && chmod a-w "$dir/readonly"
scene unwritable "n = 32\nslopes = 0.08\nseeds = 1" "load_star = 100" "table = yes"
sed -i "s|^output = out_unwritable$|output = $dir/readonly/deeper/out|" "$dir/unwritable.ini"
if touch "$dir/readonly/probe" 2>/dev/null; then
  echo "an unwritable parent: not compared (written anyway: root?)"
else
  check "an unwritable parent: the run's error" same_refusal unwritable
  check "an unwritable parent: named" grep -q "parent, $dir/readonly, is not writable" "$dir/unwritable.check_err"
fi
scene locked "n = 32\nslopes = 0.08\nseeds = 1" "load_star = 100" "table = yes"
sed -i "s|^output = out_locked$|output = $dir/held|" "$dir/locked.ini"
mkdir "$dir/held"
flock "$dir/held/.lock" sleep 60 & # a run holding the folder's lock
locker=$!
sleep 0.5
check "a folder locked by a running run: the run's error" same_refusal locked
kill $locker
check "a folder locked by a running run: named" grep -q "is in use by another indentmap run" "$dir/locked.check_err"
check "a folder locked by a running run: nothing written there" test "$(ls -A "$dir/held")" = .lock

scene no_gl "n = 32\nslopes = 0.08\nseeds = 1" "load_star = 100" "contact_panels = yes"
without_gl() { # without_gl COMMAND...: with EGL that has no device (as cli_render.sh has it)
  (unset IM_REQUIRE_GL; export __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json IM_RENDER_BACKEND=egl; "$@")
}
check "no OpenGL context: the run's error, before any work" without_gl same_refusal no_gl
check "no OpenGL context: named" grep -q "no OpenGL 3.3 core context" "$dir/no_gl.check_err"

# ---- a damaged wisdom cache: the run removes it and goes on; --check says so and removes nothing ----
mkdir -p "$dir/cachehome/indentmap"
damaged=$source_dir/docs/images/adhesion_maps.png # an image where the wisdom should be
cp "$damaged" "$dir/cachehome/indentmap/fftw-wisdom"
cached() { env -u IM_FFTW_WISDOM XDG_CACHE_HOME="$dir/cachehome" "$cli" run "$@"; }
cached "$dir/histories.ini" --check >"$dir/cache.check" 2>"$dir/cache.check_err"
check "a damaged wisdom cache: --check exits 0, as the run does" test $? -eq 0
check "a damaged wisdom cache: --check tells the run's judgement" grep -q "the run would remove it and write it afresh" \
  "$dir/cache.check_err"
check "a damaged wisdom cache: --check removes nothing" cmp -s "$damaged" "$dir/cachehome/indentmap/fftw-wisdom"
sed 's/^output = out_histories$/output = out_cached/' "$dir/histories.ini" >"$dir/cached.ini"
cached --quiet "$dir/cached.ini" >/dev/null 2>"$dir/cache.run_err"
check "a damaged wisdom cache: the run exits 0" test $? -eq 0
check "a damaged wisdom cache: the run removes it" grep -q "removed, it is written afresh" "$dir/cache.run_err"

# ---- the estimates printed are the run's ----
scene estimate "n = 256\nslopes = 0, 0.08\nseeds = 1" "control = load\nload_star = 3000" "table = yes\ncontact_panels = yes"
refused_memory=$(OMP_NUM_THREADS=1 IM_MEMORY_LIMIT_MIB=1 "$cli" run --quiet "$dir/estimate.ini" 2>&1 |
  sed -n 's/.*this scene needs about \([0-9.]*\) MiB of memory.*/\1/p')
checked_memory=$(OMP_NUM_THREADS=1 "$cli" run "$dir/estimate.ini" --check 2>/dev/null |
  sed -n 's/^  memory: about \([0-9.]*\) MiB .*/\1/p')
echo "memory: the run refuses with $refused_memory MiB, --check prints $checked_memory MiB"
check "memory estimate: the run's" test -n "$refused_memory" -a "$refused_memory" = "$checked_memory"
refused_file=$( (ulimit -f 1; "$cli" run --quiet "$dir/estimate.ini" 2>&1) |
  sed -n 's/.*contact_panels.png would be about \([0-9.]*\) MiB.*/\1/p')
checked_file=$("$cli" run "$dir/estimate.ini" --check 2>/dev/null |
  sed -n 's/^  disk: .*(the largest, contact_panels.png, \([0-9.]*\) MiB).*/\1/p')
echo "disk: the run refuses contact_panels.png at $refused_file MiB, --check prints $checked_file MiB"
check "disk estimate: the run's" test -n "$refused_file" -a "$refused_file" = "$checked_file"
check "estimates: nothing written" test ! -e "$dir/out_estimate"

finish
