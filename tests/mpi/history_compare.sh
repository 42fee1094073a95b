# mpi-indent's histories against indent's (sourced by cli_mpi.sh and cli_history.sh).
# history_differences SERIAL_CSV MPI_CSV [TOL]: prints the values where the MPI history (its stdout or
# history.csv) is not indent's, column by column by history.h's names: counts (step, patches, iterations,
# perimeter) exact, residuals to 1e-3 of indent's, every other value to TOL relative (1e-9 unless given; 1e-12
# absolute); the seconds and the convolutions (the MPI solver recomputes u where the serial one sums a few
# patches directly) aside. Exit status 1 when a value or the row count differs.
history_differences() {
  awk -F, -v tol="${3:-1e-9}" 'NR == FNR { for (c = 1; c <= NF; ++c) serial[FNR, c] = $c; rows = FNR; next }
    FNR == 1 { for (c = 1; c <= NF; ++c) name[c] = $c; next }
    { for (c = 1; c <= NF; ++c) {
        a = serial[FNR, c]; b = $c
        if (name[c] == "seconds" || name[c] == "convolutions" || a == b) continue
        t = name[c] == "residual" ? 1e-3 : tol
        d = a - b; if (d < 0) d = -d; s = a < 0 ? -a : a
        if (a == "nan" || b == "nan" || name[c] ~ /(step|patches|iterations|perimeter)$/ || d > t * s + 1e-12) {
          print "row " FNR - 1 ", " name[c] ": indent " a ", mpi-indent " b; bad = 1 } } }
    END { exit bad || FNR != rows }' "$1" "$2"
}
