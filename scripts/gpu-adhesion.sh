# The adhesive sphere at Tabor's mu = 10 on the GPU engine (issue 27; docs/solver.md, "Across Tabor's mu"):
# sourced by `GPUCHECK_MU10=1 scripts/gpu-check.sh run` on the device machine, which has set up the driver
# and "${runner[@]}". Maugis-Dugdale's zone l = 0.0028 L spans a patch only from L = 357 patches per
# reduced radius, out of reach of two CPU cores; MU10_L picks the grid (default: the estimate of the
# largest that fits about 4 minutes, docs/benchmarks.md, "Adhesion"), MU10_LIMIT the seconds it may take.
# Each step is printed as it is solved, so a run cut by the limit still leaves the curve so far; then the
# retraction's errors against Maugis-Dugdale (test_adhesion --mu).
mu10_runs() {
  local out=$1 scale=${MU10_L:-96} limit=${MU10_LIMIT:-210} status=0
  echo "mu = 10 sphere at L = $scale on the GPU (limit $limit s)" | tee "$out/mu10.txt"
  local start=$SECONDS
  timeout "$limit" "${runner[@]}" "$carry/bin/test_adhesion" --mu 10 --L "$scale" --device gpu 2>&1 |
    tee -a "$out/mu10.txt" || status=1
  echo "mu = 10, L = $scale: $((SECONDS - start)) s" | tee -a "$out/mu10.txt"
  return $status
}
