# Shared by the command-line tests (sourced): counting checks, and the closing line ctest reads.
failures=0
passes=0

# check NAME COMMAND...: runs COMMAND; a pass, or "FAIL: NAME" and a failure.
check() {
  local name=$1
  shift
  if "$@"; then passes=$((passes + 1)); else echo "FAIL: $name"; failures=$((failures + 1)); fi
}

# expect_exit CODE PHRASE COMMAND...: COMMAND exits with CODE and writes PHRASE on stderr. Needs the
# script's temporary folder in $dir.
expect_exit() {
  local code=$1 phrase=$2; shift 2
  "$@" >"$dir/out" 2>"$dir/err"
  local got=$?
  if [ "$got" -ne "$code" ] || ! grep -qF -- "$phrase" "$dir/err"; then
    echo "got exit $got, stderr: $(cat "$dir/err")"
    return 1
  fi
}

# finish: prints "N passed, N failed" and fails when any check failed.
finish() {
  echo "$passes passed, $failures failed"
  [ "$failures" -eq 0 ]
}

# history_rows FILE: a scene history's rows (after its "# ..." header line, whose checksum covers
# them) but for the solve times (column 11, seconds): what two runs of one scene must agree on.
history_rows() { tail -n +2 "$1" | cut -d, -f1-10,12-; }

# same_outputs A B: two output folders of one scene hold the same files, with the same bytes but for
# what varies from run to run: the solve times of table members (column 10, and so the row's checksum,
# 13) and of histories (column 11, and so the header's checksum), and the PDFs' creation dates. Names
# the first difference.
same_outputs() {
  local a=$1 b=$2 f
  diff <(cd "$a" && find . -type f ! -name .lock | sort) <(cd "$b" && find . -type f ! -name .lock | sort) || return 1
  while read -r f; do
    case $f in
      ./table/member_*.csv) cmp -s <(cut -d, -f10,13 --complement "$a/$f") <(cut -d, -f10,13 --complement "$b/$f") ;;
      ./histories/*.csv) cmp -s <(tail -n +2 "$a/$f" | cut -d, -f11 --complement) <(tail -n +2 "$b/$f" | cut -d, -f11 --complement) ;;
      *.pdf) cmp -s <(grep -av CreationDate "$a/$f") <(grep -av CreationDate "$b/$f") ;;
      *) cmp -s "$a/$f" "$b/$f" ;;
    esac || { echo "$f differs between $a and $b"; return 1; }
  done < <(cd "$a" && find . -type f ! -name .lock | sort)
}

# ensemble_scene FILE NAME OUTPUT [TOL]: the reduced ensemble that the concurrency, interrupt and
# full-disk tests run: 128 x 128, two slopes x four seeds, the 80 deg cone under load control to
# N* = 2400 in 12 steps, table1.csv and fig5's histories; TOL, when given, the solver's tolerance.
ensemble_scene() {
  local solver=""
  [ -n "${4:-}" ] && solver=$'[solver]\ntol = '"$4"
  cat >"$1" <<INI
[scene]
name = $2
output = $3
[surfaces]
n = 128
hurst = 0.8
lambda_s = 4
slopes = 0.04, 0.16
seeds = 1:4
[punch]
shape = cone
alpha = 80
[loading]
load_star = 2400
control = load
steps = 200:2400:12
$solver
[output]
table = yes
plots = fig5
INI
}

# require_renderer CLI: exits 77 (skipped) when no OpenGL 3.3 core context can be created at all,
# 1 instead when IM_REQUIRE_GL=1, and 1 when a renderer opens a context and then fails.
require_renderer() {
  local renderer
  renderer=$("$1" info | grep '^render backend')
  case $renderer in
    "render backend: unavailable (no OpenGL 3.3 core context"*)
      if [ "${IM_REQUIRE_GL:-}" = 1 ]; then
        echo "FAIL: IM_REQUIRE_GL=1 and $renderer" >&2
        exit 1
      fi
      echo "SKIPPED: $renderer" >&2
      exit 77 ;;
    "render backend: egl"* | "render backend: osmesa"*) ;;
    *)
      echo "FAIL: the renderer does not work: $renderer" >&2
      exit 1 ;;
  esac
}

# stats FILE [OPTIONS]: `$cli surface --stats` without detrending or taper, as Gwyddion's rms is taken.
stats() { local file=$1; shift; "$cli" surface --stats "$file" --detrend none --window none "$@"; }

# stated FILE KEY VALUE [REL]: the --stats output FILE's line KEY holds VALUE (to REL relative, default
# 5e-6: the six digits printed).
stated() {
  awk -v key="$2" -v want="$3" -v rel="${4:-5e-6}" '
    index($0, key) == 1 { split(substr($0, length(key) + 1), w, " "); got = w[1] + 0; found = 1
      if ((got - want) ^ 2 > (rel * want) ^ 2) { print key ": " got ", expected: " want; exit 1 } }
    END { if (!found) { print "no line " key; exit 1 } }' "$1"
}
