#!/usr/bin/env bash
# Runs each libFuzzer harness for a bounded time, one after the other:
#   fuzz/run.sh [SECONDS] [BUILD_DIR] [HARNESS...]     (defaults: 60, build-fuzz, all eleven)
# Builds first (fuzz/build.sh). Each harness runs in one process, starts from the committed seeds
# in fuzz/corpus/NAME and fuzz/regressions/NAME (read only; not its libhdf5-crash-* inputs) and adds
# what it discovers to BUILD_DIR/corpus/NAME (kept between runs); crashing inputs are written to
# BUILD_DIR/artifacts/NAME/ and the log to BUILD_DIR/logs/NAME.log. Prints one line per harness
# with libFuzzer's final stats; exits 1 if any harness found a crash, leak, timeout or OOM (for hdf5:
# other than a crash or allocation inside libhdf5 itself, see inside_libhdf5).
set -uo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
build_dir=${2:-build-fuzz}
shift 2 2>/dev/null || shift $#
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(scene npy text gsf sdf netcdf x3p gwyddion tmd hdf5 container)

fuzz/build.sh "$build_dir" >/dev/null || exit 1

# libhdf5 1.10 crashes inside itself on some hostile files (a memcpy into a failed allocation of a size
# the file states) and allocates the sizes they state; the library reads HDF5 in a child
# (src/formats/hdf5_child.c), where such a crash or allocation refuses the file. fuzz_hdf5 reads in-process,
# as a fuzzer must to see coverage, so it runs in fork mode on past crashes, and each new crash or OOM is
# replayed: a SEGV whose innermost frame, past libc and the sanitizer's interceptors, is in libhdf5, or a
# malloc beyond the limit that libhdf5 itself made, is counted as contained; every other artifact (a
# crash or allocation in indentmap's code, a leak, a timeout, an RSS overrun) is a finding.
inside_libhdf5() {
  local report frames='^ *#[0-9]+ '
  report=$(ASAN_OPTIONS=$asan_options LSAN_OPTIONS=$lsan_options "$build_dir/fuzz_hdf5" -rss_limit_mb=2048 "$1" 2>&1)
  if grep -q 'ERROR: AddressSanitizer: SEGV' <<<"$report"; then
    grep -E "$frames" <<<"$report" | grep -v -E 'sysdeps/|libc\.so|__interceptor_|__asan|__sanitizer' |
      head -1 | grep -q libhdf5
  elif grep -q 'ERROR: libFuzzer: out-of-memory (malloc(' <<<"$report"; then
    grep -E "$frames" <<<"$report" | grep -v -E 'fuzzer::|__sanitizer|__asan| in (malloc|calloc|realloc) ' |
      head -1 | grep -q libhdf5
  else
    return 1
  fi
}

failed=0
printf '%-6s %8s %12s %10s %s\n' harness seconds execs exec/s result
for name in "${harnesses[@]}"; do
  mkdir -p "$build_dir/corpus/$name" "$build_dir/artifacts/$name/earlier" "$build_dir/logs"
  # earlier runs' artifacts aside: an input found again is written again, and judged below with this run's
  find "$build_dir/artifacts/$name" -maxdepth 1 -type f -exec mv -f {} "$build_dir/artifacts/$name/earlier/" \;
  dict=()
  [ -f "fuzz/$name.dict" ] && dict=(-dict="fuzz/$name.dict")
  seeds=("fuzz/corpus/$name")
  if [ -d "fuzz/regressions/$name" ]; then
    # Inputs that crash libhdf5 itself (libhdf5-crash-*) would end the in-process harness at its first seed:
    # the library reads HDF5 in a child for that (src/formats/hdf5_child.c), and fuzz_regressions reads them so.
    # The other regressions are seeds, copied (libFuzzer takes folders) into BUILD_DIR/seeds/NAME.
    replayed="$build_dir/seeds/$name"
    rm -rf "$replayed" && mkdir -p "$replayed"
    find "fuzz/regressions/$name" -maxdepth 1 -type f ! -name 'libhdf5-crash-*' -exec cp {} "$replayed/" \;
    seeds+=("$replayed")
  fi
  log="$build_dir/logs/$name.log"
  # libhdf5 mallocs the sizes a hostile header states and handles a NULL (CMakeLists.txt, fuzz_regressions),
  # and leaks what it read of a damaged object header (fuzz/hdf5_lsan.supp: full stacks to match it).
  asan_options=${ASAN_OPTIONS:-} lsan_options=${LSAN_OPTIONS:-} mode=()
  if [ "$name" = hdf5 ]; then
    asan_options=allocator_may_return_null=1:fast_unwind_on_malloc=0${asan_options:+:$asan_options}
    lsan_options=suppressions=$PWD/fuzz/hdf5_lsan.supp${lsan_options:+:$lsan_options}
    mode=(-fork=1 -ignore_crashes=1)
  fi
  ASAN_OPTIONS=$asan_options LSAN_OPTIONS=$lsan_options "$build_dir/fuzz_$name" -max_total_time="$seconds" -max_len=4096 -timeout=10 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$build_dir/artifacts/$name/" "${mode[@]}" \
    "${dict[@]}" "$build_dir/corpus/$name" "${seeds[@]}" >"$log" 2>&1
  status=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  if [ ${#mode[@]} -gt 0 ]; then # fork mode's progress lines: "#EXECS: cov: ... exec/s RATE ..."
    execs=$(sed -n 's/^#\([0-9]*\): cov:.*/\1/p' "$log" | tail -1)
    rate=$(sed -n 's/^#[0-9]*: cov:.* exec\/s \([0-9]*\).*/\1/p' "$log" | tail -1)
  fi
  contained=0 found=()
  while IFS= read -r artifact; do
    if [ "$name" = hdf5 ] && [[ $(basename "$artifact") == @(crash|oom)-* ]] && inside_libhdf5 "$artifact"; then
      contained=$((contained + 1))
    else
      found+=("$(basename "$artifact")")
    fi
  done < <(find "$build_dir/artifacts/$name" -maxdepth 1 -type f)
  result=ok
  # fork mode ends non-zero after a crash it ran past: a finding only when no contained input explains it
  if [ ${#found[@]} -gt 0 ] || { [ $status -ne 0 ] && { [ ${#mode[@]} -eq 0 ] || [ $contained -eq 0 ]; }; }; then
    result="FOUND (exit $status): $(grep -m1 -E '^==[0-9]+==ERROR|runtime error|fuzz: ' "$log") -> ${found[*]}"
    failed=1
  elif [ $contained -gt 0 ]; then
    result="ok; $contained inputs crashed libhdf5 or made it allocate beyond the limit (contained: read in a child), in $build_dir/artifacts/$name"
  fi
  printf '%-6s %8s %12s %10s %s\n' "$name" "$seconds" "${execs:-?}" "${rate:-?}" "$result"
done
exit $failed
