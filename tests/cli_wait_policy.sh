#!/usr/bin/env bash
# The OpenMP wait policy: unless the user chose one, indentmap runs with GOMP_SPINCOUNT=3000
# (idle threads spin briefly, then sleep, instead of libgomp's default 300000 spins on shared
# cores); a policy or spin count the user set is kept. libgomp prints what it resolved with OMP_DISPLAY_ENV.
set -u
cli=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"

# spin_count ENV...: libgomp's resolved GOMP_SPINCOUNT for `indentmap --version` run with ENV only,
# as the program image that runs sees it (libgomp prints it at every load: the image that
# re-executes itself prints it too, before it runs anything)
spin_count() {
  env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$@" OMP_DISPLAY_ENV=verbose "$cli" --version 2>&1 >/dev/null |
    sed -n "s/^ *GOMP_SPINCOUNT = '\([0-9]*\)'.*/\1/p" | tail -n 1
}

check "default: a short spin (3000)" test "$(spin_count)" = 3000
check "OMP_WAIT_POLICY=passive is kept" test "$(spin_count OMP_WAIT_POLICY=passive)" = 0
check "OMP_WAIT_POLICY=active is kept" test "$(spin_count OMP_WAIT_POLICY=active)" -gt 0
check "GOMP_SPINCOUNT is kept" test "$(spin_count GOMP_SPINCOUNT=12345)" = 12345
check "the program still runs and answers" bash -c "env -u OMP_WAIT_POLICY '$cli' --version | grep -q '^indentmap '"
finish
