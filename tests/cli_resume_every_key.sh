#!/usr/bin/env bash
# Every key the scene parser knows, edited, then `run --resume` over the finished run of the scene
# before the edit: the folder left behind is the one a fresh run of the edited scene writes (byte for
# byte, but for the solve times in members and histories and the PDFs' creation dates), so that no
# key's edit lets a stale result through (issue 32). Table-driven: RULES names, for each key of the
# parser's table (src/scene/keys.c, KEYS), the scene it is edited in and its edit, or why it has no
# resume to check; a key the table lacks (a new key) fails the test. --no-wisdom: estimated FFTW
# plans, so that two runs agree to the bit. Exit 77 (skipped) without an OpenGL context.
#   cli_resume_every_key.sh PATH_TO_INDENTMAP
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
require_renderer "$cli"
parser=$(dirname "$0")/../src/scene/keys.c

# device = gpu where the build has the GPU engine and Vulkan opens a device (`indentmap info` lists it
# under "Vulkan devices:"), else why not.
device_rule() {
  if "$cli" info | grep -A1 '^Vulkan devices:$' | grep -q '^  '; then
    echo 'solver.device|ensemble|device = gpu'
  else
    echo 'solver.device|-|cpu is the only device here; cpu and auto solve alike on a machine without a GPU (cli_device)'
  fi
}

# RULES: KEY|BASE|EDIT, EDIT being "key = value" lines of the key's section separated by ';', or
# KEY|-|WHY for a key without a resume of its own to check. resample_square alone changes no result
# (square pixels are read as they are; without it non-square ones are refused), so its edit turns it
# on with a file of the same heights on pixels 1 x 2 um.
RULES='
scene.name|ensemble|name = other
scene.output|-|another output folder is another run: nothing of the old folder is resumed
scene.quality|ensemble|quality = draft
surfaces.n|ensemble|n = 48
surfaces.m|ensemble|m = 48
surfaces.hurst|ensemble|hurst = 0.7
surfaces.lambda_s|ensemble|lambda_s = 3
surfaces.lambda_r|ensemble|lambda_r = 32
surfaces.lambda_0|ensemble|lambda_r = 32;lambda_0 = 48
surfaces.slope_definition|ensemble|slope_definition = fd
surfaces.slopes|ensemble|slopes = 0.04, 0.12
surfaces.seeds|ensemble|seeds = 2:4
surfaces.file|files|file = a.npy, c.npy
surfaces.detrend|files|detrend = plane
surfaces.align|files|align = median
surfaces.fill|files|fill = yes
surfaces.npy_order|files|npy_order = xy
surfaces.channel|instrument|channel = Height
surfaces.resample_square|pixels|file = rect.txt;resample_square = yes
punch.shape|sphere|shape = flat;radius = 20
punch.profile|profile|profile = wide.csv
punch.alpha|ensemble|alpha = 75
punch.radius|sphere|radius = 150
punch.periodic|periodic|periodic = yes;shape = cone
material.modulus|ensemble|modulus = 2
material.hardness|ensemble|hardness = 2
loading.control|sphere|control = displacement;steps = 0.5:2:4
loading.load_star|ensemble|load_star = 500
loading.steps|ensemble|steps = 100:600:5
output.contact_panels|ensemble|contact_panels = no
output.frames|ensemble|frames = no
output.frames3d|ensemble|frames3d = yes
output.page_embed|ensemble|page_embed = yes
output.table|ensemble|table = no
output.distributions|ensemble|distributions = yes
output.animation|ensemble|animation = gif
output.colormap|ensemble|colormap = viridis
output.log_norm|ensemble|log_norm = no
output.frames_slope|ensemble|frames_slope = 0.04
output.frames_clip|ensemble|frames_clip = 2
output.contact_panels_clip|ensemble|contact_panels_clip = 2
output.frame_count|ensemble|frame_count = 4
output.frame_rate|ensemble|animation = gif;frame_rate = 2
output.frame_scale|ensemble|frame_scale = 2
output.frame3d_width|ensemble|frames3d = yes;frame3d_width = 128
output.frame3d_height|ensemble|frames3d = yes;frame3d_height = 128
output.plots|ensemble|plots = fig7, fig5
adhesion.work|sticky|work = 0.06
adhesion.range|sticky|range = 0.7
adhesion.law|-|one law (maugis-dugdale): nothing to edit it to
adhesion.zone|sticky|zone = 4
solver.tol|ensemble|tol = 1e-9
'$(device_rule)

# The keys of the parser's table, "section.key" each.
known_keys() {
  sed -n '/^static const key_spec KEYS\[\] = {/,/^};/p' "$parser" |
    sed -nE 's/^ *\{"([a-z0-9_]+)", "([a-z0-9_]+)".*/\1.\2/p'
}

# base NAME: the scene NAME before any edit, its output folder $dir/out.
base() {
  case $1 in
    ensemble) printf '[scene]\nname = ref\n[surfaces]\nn = 64\nhurst = 0.8\nlambda_s = 4\nslopes = 0.04, 0.16\nseeds = 1:3\n[punch]\nshape = cone\nalpha = 80\n[material]\n[loading]\nload_star = 600\ncontrol = load\nsteps = 100:600:4\n[output]\ntable = yes\nplots = fig7\ncontact_panels = yes\nframes = yes\nframe_count = 6\n[solver]\n' ;;
    files) printf '[scene]\nname = files\n[surfaces]\nfile = a.npy, b.npy\n[punch]\nshape = cone\nalpha = 80\n[loading]\nload_star = 300\n[output]\ntable = yes\ncontact_panels = yes\n' ;;
    sphere) printf '[scene]\nname = sphere\n[surfaces]\nn = 64\nslopes = 0.04\nseeds = 1:2\n[punch]\nshape = sphere\nradius = 100\n[loading]\nload_star = 200\ncontrol = load\nsteps = 50:200:4\n[output]\nplots = fig5\n' ;;
    profile) printf '[scene]\nname = profile\n[surfaces]\nn = 64\nslopes = 0.04\nseeds = 1:2\n[punch]\nshape = profile\nprofile = narrow.csv\n[loading]\nload_star = 200\ncontrol = load\nsteps = 50:200:4\n[output]\nplots = fig5\ncontact_panels = yes\n' ;;
    periodic) printf '[scene]\nname = periodic\n[surfaces]\nn = 64\nslopes = 0.04\nseeds = 1:2\n[punch]\nperiodic = yes\n[loading]\nsteps = 0.004:0.016:4\n[output]\n' ;;
    instrument) printf '[scene]\nname = instrument\n[surfaces]\nfile = di-3.di\nchannel = ZSensor\n[punch]\nshape = cone\nalpha = 80\n[loading]\nload_star = 300\n[output]\ntable = yes\ncontact_panels = yes\n' ;;
    pixels) printf '[scene]\nname = pixels\n[surfaces]\nfile = square.txt\n[punch]\nshape = cone\nalpha = 80\n[loading]\nload_star = 300\n[output]\ntable = yes\ncontact_panels = yes\n' ;;
    sticky) printf '[scene]\nname = sticky\n[surfaces]\nn = 64\nslopes = 0\nseeds = 1\n[punch]\nshape = sphere\nradius = 48\n[adhesion]\nwork = 0.05\nrange = 0.6\nlaw = maugis-dugdale\n[loading]\ncontrol = displacement\nsteps = -1:1.5:8\n[output]\nplots = fig5\n' ;;
  esac
}

# edited FILE SECTION EDITS: FILE with each "key = value" of EDITS (';' between) set in [SECTION].
edited() {
  local file=$1 section=$2 edit edits
  IFS=';' read -ra edits <<<"$3"
  for edit in "${edits[@]}"; do
    awk -v section="[$section]" -v key="${edit%% =*}" -v line="$edit" '
      $0 == section { inside = 1; print; next }
      /^\[/ { if (inside && !done) { print line; done = 1 } inside = 0 }
      inside && index($0, key " = ") == 1 { if (!done) print line; done = 1; next }
      { print }
      END { if (!done) { if (!inside) print section; print line } }' "$file" >"$file.new" && mv "$file.new" "$file"
  done
}

# scene BASE [SECTION EDITS]: $dir/s.ini, writing into $dir/out.
scene() {
  base "$1" | sed "s|^name = .*|&\noutput = $dir/out|" >"$dir/s.ini"
  [ $# -lt 3 ] || edited "$dir/s.ini" "$2" "$3"
}

other_outputs() { ! same_outputs "$1" "$2" >/dev/null; }

run() { (cd "$dir" && "$cli" run --quiet --no-wisdom "$@" >/dev/null 2>>"$dir/log"); }

# The inputs the bases name.
seed=0
for name in a b c; do "$cli" surface --n 64 --slope 0.05 --seed $((seed += 1)) --out "$dir/$name.npy" >/dev/null; done
for name in narrow wide; do
  cone=$([ $name = narrow ] && echo 80 || echo 70)
  python3 -c "import math, sys; a = math.tan(math.radians(float(sys.argv[1])))
for k in range(41): print(k * 1.0, ',', k / a)" $cone | tr -d ' ' >"$dir/$name.csv"
done

# di-3.di: channels 0 'ZSensor' and 3 'Height' of 256 x 256 (tests/data/instruments/README.md).
cp "$(dirname "$0")/data/instruments/di-3.di" "$dir/"
# One surface as a Gwyddion text export on square pixels (1 x 1 um) and on pixels 1 x 2 um.
"$cli" surface --n 64 --slope 0.05 --seed 4 --out "$dir/heights.txt" >/dev/null
for pixels in square:64 rect:128; do
  (printf '# Width: 64 um\n# Height: %s um\n' "${pixels#*:}"; grep -v '^#' "$dir/heights.txt") >"$dir/${pixels%:*}.txt"
done

# The table covers the parser's keys, no more, no less.
known_keys | sort >"$dir/known"
echo "$RULES" | grep . | cut -d'|' -f1 | sort >"$dir/ruled"
check "every key of the parser has a rule ($(wc -l <"$dir/known") keys)" \
  bash -c "comm -23 '$dir/known' '$dir/ruled' | sed 's/^/no rule for /' | grep . && exit 1 || exit 0"
check "every rule is a key of the parser" \
  bash -c "comm -13 '$dir/known' '$dir/ruled' | sed 's/^/not a key: /' | grep . && exit 1 || exit 0"

# The finished run of each base, kept as $dir/base_NAME.
for name in $(echo "$RULES" | grep . | cut -d'|' -f2 | grep -v '^-$' | sort -u); do
  rm -rf "$dir/out"
  scene "$name"
  : >"$dir/log"
  check "base $name runs" run s.ini
  [ -d "$dir/out" ] && mv "$dir/out" "$dir/base_$name"
done

while IFS='|' read -r key name edits; do
  [ -n "$key" ] && [ "$name" != - ] || continue
  rm -rf "$dir/out" "$dir/fresh"
  scene "$name" "${key%%.*}" "$edits"
  : >"$dir/log"
  if ! run s.ini; then
    check "$key ($edits): the edited scene runs: $(cat "$dir/log")" false
    continue
  fi
  mv "$dir/out" "$dir/fresh"
  check "$key ($edits): the edit changes the outputs" other_outputs "$dir/base_$name" "$dir/fresh"
  cp -r "$dir/base_$name" "$dir/out"
  : >"$dir/log"
  check "$key ($edits): --resume exits 0" run --resume s.ini
  check "$key ($edits): resumed = fresh" same_outputs "$dir/out" "$dir/fresh"
done <<<"$RULES"

finish
