#!/usr/bin/env bash
# The shared library exports exactly the public API: every symbol `nm -D --defined-only` lists is a
# function the public headers declare, and every such function is exported. The declarations are GCC's
# reading of the headers (-aux-info, written when the build compiles a file including them all), not
# cmake/exports.cmake's, which made the version script.
#   exports.sh LIBRARY DECLARATIONS PUBLIC_INCLUDE_DIR...
set -euo pipefail
library=$1 declarations=$2
shift 2
[ -s "$declarations" ] || { echo "exports: no declarations in $declarations (-aux-info)" >&2; exit 1; }

exported=$(nm -D --defined-only "$library" | awk '$2 != "A" { sub(/@.*/, "", $3); print $3 }' | sort -u)
# Lines such as `/* DIR/field.h:39:NC */ extern int im_field_create (int, int, double, im_field **);`,
# kept when DIR is a public folder and the function is not static (field.h's inline helpers).
declared=$(for dir in "$@"; do
             grep -F "/* $dir/" "$declarations" | grep -v ' static ' |
               sed -E 's|^/\*[^*]*\*/ [^(]*[ *(]+([A-Za-z_][A-Za-z0-9_]*) \(.*|\1|'
           done | sort -u)
[ -n "$exported" ] || { echo "exports: $library exports nothing" >&2; exit 1; }
[ -n "$declared" ] || { echo "exports: the public headers declare no function in $declarations" >&2; exit 1; }

status=0
undeclared=$(comm -23 <(echo "$exported") <(echo "$declared"))
missing=$(comm -13 <(echo "$exported") <(echo "$declared"))
if [ -n "$undeclared" ]; then
  echo "exports: $library exports names no public header declares:" $undeclared >&2
  status=1
fi
if [ -n "$missing" ]; then
  echo "exports: $library does not export these functions of the public headers:" $missing >&2
  status=1
fi
[ $status -eq 0 ] && echo "exports: $(wc -l <<<"$exported") symbols, the public headers' functions exactly"
exit $status
