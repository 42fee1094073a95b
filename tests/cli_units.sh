#!/usr/bin/env bash
# Units end to end on the command line (issue 13): a surface in µm solved in SI (--length-unit m),
# run.json naming the units, every field with a sidecar stating its units, and render labelling the
# force in newtons with a scale bar in metres (the numbers themselves: tests/test_units.c).
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

source "$(dirname "$0")/lib.sh"

"$cli" surface --n 32 --delta 0.2 --unit um --slope 0.1 --out "$dir/s.gsf" >/dev/null
check "the .gsf states metres, as Gwyddion reads it" grep -aqx "XYUnits = m" "$dir/s.gsf"
"$cli" indent "$dir/s.gsf" --length-unit m --e-star 1e9 --e-star-unit Pa --approach 1e-7,2e-7 --fields \
  --out "$dir/si" >/dev/null 2>&1
check "SI indentation runs" test $? -eq 0
check "run.json: lengths in m" grep -q '"length": "m"' "$dir/si/run.json"
check "run.json: loads in N" grep -q '"load": "N"' "$dir/si/run.json"
check "force sidecar: N" grep -q '"value_unit": "N"' "$dir/si/force_0002.npy.json"
check "force sidecar: spacing in m" grep -q '"unit": "m"' "$dir/si/force_0002.npy.json"
check "gap sidecar: lengths in m" bash -c "grep -q '\"unit\": \"m\"' '$dir/si/gap_0002.npy.json' && grep -q '\"value_unit\": \"\"' '$dir/si/gap_0002.npy.json'"
check "the surface read back in m" bash -c "'$cli' surface --stats '$dir/si/gap_0001.npy' | grep -q 'delta = 2e-07 m'"
"$cli" render contact "$dir/si/force_0002.npy" --out "$dir/f.png" >/dev/null 2>&1
status=$?
if [ $status -eq 0 ]; then
  check "render labels the force in N" grep -aq "local force f / N" "$dir/f.png"
  # view3d's colour bar by the maps' rule (figure.h: im_figure_colorbar_label); it said E* δ² whatever the unit
  "$cli" render view3d "$dir/s.gsf" --displacement "$dir/si/displacement_0002.npy" --force "$dir/si/force_0002.npy" \
    --width 160 --height 120 --out "$dir/v.png" >/dev/null 2>&1
  check "view3d labels the force in N" python3 "$(dirname "$0")/figure_texts.py" "$dir/v.png" "Quantity=local force f / N"
fi
"$cli" surface --n 32 --delta 0.2 --unit um --slope 0.1 --out "$dir/s.npy" >/dev/null
"$cli" indent "$dir/s.npy" --e-star 2 --approach 0.02 --fields --out "$dir/um" >/dev/null 2>&1
check "no --e-star-unit: forces in E* µm²" grep -q '"value_unit": "E\* µm²"' "$dir/um/force_0001.npy.json"
"$cli" surface --n 16 --out "$dir/plain.npy" >/dev/null
check "--length-unit needs a unit" expect_exit 2 "plain.npy: states no length unit to convert into m from" \
  "$cli" indent "$dir/plain.npy" --length-unit m --approach 0.5 --out "$dir/x"
printf '{"delta": "wide"}' >"$dir/plain.npy.json"
check "a malformed sidecar is refused, named" expect_exit 2 "plain.npy.json: expected \"delta\" a number > 0" \
  "$cli" surface --stats "$dir/plain.npy"

finish
