#!/usr/bin/env bash
# The whole grid's displacement's memory (docs/benchmarks.md, "The whole grid's displacement: memory"):
# peak RSS of `indent --smooth --n N --punch sphere --radius 200 --approach 2` with and without --fields,
# on its small window and (--full) on the whole grid, each in its own process. With BASE=another
# indentmap binary, the same runs of it too, and its written fields compared with this build's byte
# for byte. Prints CSV: binary,n,window,fields,peak_rss_mib,wall_s,same_bits
#   [BUILD=build] [BASE=path/to/indentmap] bench/run_fields_memory.sh [N ... (1024 2048)]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
cmake --build "$build" --target indentmap_cli >/dev/null
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
binaries=("$build/indentmap")
[ -n "${BASE:-}" ] && binaries+=("$BASE")
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(1024 2048)
echo "binary,n,window,fields,peak_rss_mib,wall_s,same_bits"
for n in "${sizes[@]}"; do
  for window in small full; do
    for fields in no yes; do
      for b in "${!binaries[@]}"; do
        out="$dir/$b-$n-$window-$fields"
        args=(indent --smooth --n "$n" --punch sphere --radius 200 --approach 2 --out "$out")
        [ "$window" = full ] && args+=(--full)
        [ "$fields" = yes ] && args+=(--fields)
        IM_FFTW_WISDOM= /usr/bin/time -f "%M %e" -o "$dir/time" "${binaries[$b]}" "${args[@]}" >/dev/null
        read -r kib wall <"$dir/time"
        same=""
        if [ "$b" = 1 ] && [ "$fields" = yes ]; then
          same=yes
          for f in force gap displacement; do
            cmp -s "$dir/0-$n-$window-$fields/${f}_0001.npy" "$out/${f}_0001.npy" || same=no
          done
        fi
        awk -v b="$([ "$b" = 0 ] && echo build || echo base)" -v n="$n" -v w="$window" -v f="$fields" -v k="$kib" \
          -v t="$wall" -v s="$same" 'BEGIN { printf "%s,%s,%s,%s,%.1f,%s,%s\n", b, n, w, f, k / 1024, t, s }'
      done
    done
  done
done
