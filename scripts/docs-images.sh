#!/bin/bash
# Regenerates the images under docs/images that the project's commands make, each with the command or
# scene the docs name beside it, so that every picture in the docs is the current renderer's.
# usage: scripts/docs-images.sh BUILD [OUTDIR]
#   BUILD   a build folder holding the program (indentmap) with its OpenGL renderer
#   OUTDIR  where the images go (default: docs/images of this checkout)
# The runs go to $IM_DOCS_WORK (default: a new temporary folder, removed at the end unless it was
# given). Scenes run with --resume, so a second call with the same IM_DOCS_WORK reuses what the first
# finished. FFTW wisdom is off (IM_FFTW_WISDOM empty), so no wisdom file is read or written.
#
# tradeoff.png is drawn again from docs/tradeoff.csv (`bench_tradeoff --plot`, built here): measuring
# it anew is `bench_tradeoff CSV PNG` (docs/benchmarks.md, "Speed against accuracy"), whose numbers
# the docs quote.
#
# Sizes: the bundled scenes' own figures are copied as they are written. Three show 512 x 512 patches
# of rough detail at one pixel per patch, which no option draws smaller: fig4's contact panels and
# height frame (about 420 and 480 KB; a scene has no figure size) and the height field (505 KB; it was
# 670 KB at two pixels per patch). fig5 and fig6 are the full scene (51 histories of 25 approaches,
# about 4 minutes on 2 quiet cores, 15 or more on a busy one). The images over 300 KB are listed at
# the end.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "$1" && pwd)
out=${2:-$root/docs/images}
cli="$build/indentmap"
export IM_FFTW_WISDOM='' OMP_WAIT_POLICY=passive
work=${IM_DOCS_WORK:-}
if [ -z "$work" ]; then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$out" "$work"

# keep SOURCE NAME: copies SOURCE to OUTDIR/NAME and says how large it is
keep() {
  cp "$1" "$out/$2"
  printf "%-28s %7d bytes  from %s\n" "$2" "$(stat -c %s "$out/$2")" "${1#"$work"/}"
}

# scene INI NAME: runs the scene INI into WORK/NAME (resumed when it was started before)
scene() { "$cli" run --resume --quiet "$1" --out "$work/$2" > /dev/null; }

paper_scenes() {
  local name
  for name in fig1 fig2 fig3 fig7; do
    scene "$root/scenes/$name.ini" "$name"
    keep "$work/$name/$name.png" "$name.png"
  done
  scene "$root/scenes/angle_sweep.ini" angle_sweep
  keep "$work/angle_sweep/fig2.png" angle_sweep.png
  scene "$root/scenes/sphere.ini" sphere
  keep "$work/sphere/sphere_regimes.png" sphere_regimes.png
  # fig5 and fig6 share their 51 histories: one scene draws both
  sed -e 's/^name = fig5$/name = fig5_fig6/' -e 's/^plots = fig5$/plots = fig5, fig6/' "$root/scenes/fig5.ini" \
    > "$work/fig5_fig6.ini"
  scene "$work/fig5_fig6.ini" fig5_fig6
  keep "$work/fig5_fig6/fig5.png" fig5.png
  keep "$work/fig5_fig6/fig6.png" fig6.png
}

# the main job: README's panels, ring-averaged density and last height frame
fig4_scene() {
  scene "$root/scenes/fig4.ini" fig4
  keep "$work/fig4/contact_panels.png" fig4_contact_panels.png
  keep "$work/fig4/contact_density.png" fig4_contact_density.png
  keep "$work/fig4/frames/height_0011.png" fig4_height_frame.png
}

# docs/scenes.md's distributions: the smooth cone and two roughnesses at the paper's contact radius
# relative to the box (N* = 9300 on 256^2), first seed
distributions_scene() {
  cat > "$work/distributions.ini" <<'INI'
[scene]
name = distributions
[surfaces]
n = 256
hurst = 0.8
lambda_s = 4
slopes = 0, 0.04, 0.16
seeds = 1
[punch]
shape = cone
alpha = 80
[loading]
control = load
load_star = 9300
[output]
distributions = yes
INI
  scene "$work/distributions.ini" distributions
  keep "$work/distributions/distributions.png" distributions.png
}

# docs/rendering.md: one rough cone's force field (N = 2770 E* delta^2: the smooth contact radius is
# 100 patches) as a contact map and on its hill-shaded surface (at one pixel per patch: every patch
# of the relief is still a pixel of its own)
render_maps() {
  local dir="$work/maps"
  mkdir -p "$dir"
  "$cli" surface --n 512 --slope 0.08 --seed 1 --out "$dir/s0.08.npy" > /dev/null
  "$cli" indent "$dir/s0.08.npy" --load 2770 --fields --out "$dir/r0.08" > /dev/null
  "$cli" render contact "$dir/r0.08/force_0001.npy" --circle 100 --label "(e)" \
    --title "α = 80°, h′_{rms} = 0.08, N = 2770 E* δ²" --out "$dir/contact_map.png" > /dev/null
  keep "$dir/contact_map.png" contact_map_log_magma.png
  "$cli" render height "$dir/s0.08.npy" --contact "$dir/r0.08/force_0001.npy" --scale 1 \
    --title "h′_{rms} = 0.08, contact at N = 2770 E* δ² outlined" --out "$dir/height_field.png" > /dev/null
  keep "$dir/height_field.png" height_field.png
}

# README and docs/rendering.md: the 3-D view of a 256^2 surface under the cone at N = 3000 E* delta^2,
# the camera's default distance (the nearest that shows the whole block and punch)
render_view3d() {
  local dir="$work/view3d"
  mkdir -p "$dir"
  "$cli" surface --n 256 --slope 0.08 --seed 1 --out "$dir/s256.npy" > /dev/null
  "$cli" indent "$dir/s256.npy" --load 3000 --fields --out "$dir/run" > /dev/null
  "$cli" render view3d "$dir/s256.npy" --displacement "$dir/run/displacement_0001.npy" \
    --force "$dir/run/force_0001.npy" --exaggeration 3 --punch-mode cutaway --elevation 28 \
    --width 1280 --height 640 --dpi 150 --out "$dir/view3d.png" > /dev/null
  keep "$dir/view3d.png" view3d.png
}

# docs/benchmarks.md: the benchmarks that draw them, and tests/cli_indent.sh's adhesive sphere
benchmark_figures() {
  "$root/bench/run_plasticity.sh" "$build" "$work/plasticity" > /dev/null
  keep "$work/plasticity/plastic_impressions.png" plastic_impressions.png
  keep "$work/plasticity/rough_0.1/load_displacement.png" load_displacement.png
  "$root/bench/run_adhesion.sh" "$build" "$work/adhesion" > /dev/null
  keep "$work/adhesion/adhesion_maps.png" adhesion_maps.png
  "$cli" indent --smooth --n 96 --punch sphere --radius 64 --adhesion-work 0.05305 --adhesion-range 0.6366 \
    --approach -1:2:16,1.9:-1.5:35 --out "$work/sticky" > /dev/null
  keep "$work/sticky/force_distance.png" adhesion_force_distance.png
}

# docs/benchmarks.md: the speed/accuracy trade, drawn from the committed measurement
tradeoff_figure() {
  cmake --build "$build" --target bench_tradeoff >/dev/null
  "$build/bench_tradeoff" --plot "$root/docs/tradeoff.csv" "$work/tradeoff.png"
  keep "$work/tradeoff.png" tradeoff.png
}

fig4_scene
tradeoff_figure
render_maps
render_view3d
distributions_scene
benchmark_figures
paper_scenes
large=$(find "$out" -name '*.png' -size +300k -printf '%f ')
[ -z "$large" ] || echo "over 300 KB: $large"
