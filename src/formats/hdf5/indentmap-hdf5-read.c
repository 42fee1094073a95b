/* indentmap-hdf5-read: reads one plain HDF5 or NetCDF-4 file with libhdf5 and hands the chosen data set to
 * indentmap over its standard output (the stream of src/formats/hdf5_child.c).
 *
 * Why a separate program: libhdf5 1.10 crashes inside itself on some hostile files (fuzz/regressions/hdf5/
 * libhdf5-crash-*), which no caller can guard against; a crash here ends this program, and the library
 * refuses the file instead of taking its caller (a Python kernel, an MPI rank) down with it.
 *
 * Usage: indentmap-hdf5-read [--] FILE [CHANNEL]   CHANNEL: a data set's index or name; default: the first
 *        indentmap-hdf5-read --netcdf [--] FILE     a NetCDF-4 file (HDF5 underneath), as netcdf.c reads it
 * Exit status 0 with the field written, 2 with a refusal written, 1 when the stream could not be written. A
 * read that runs longer than CHILD_READ_SECONDS is ended by SIGALRM. */
#include "formats/child_reader.h"
#include "formats/hdf5.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

/* In a sanitizer build this program behaves as in a plain one, whose crash the library reports: a size
 * libhdf5 cannot allocate is a NULL it handles (glibc's malloc gives one), a fault inside libhdf5 ends the
 * program by its signal, and what libhdf5 keeps until exit is not a leak report (exit status 23). The parse
 * itself is checked in-process by fuzz/fuzz_hdf5.c and the fuzz_regressions test. */
const char *__asan_default_options(void);
const char *__asan_default_options(void) { return "allocator_may_return_null=1:handle_segv=0:detect_leaks=0"; }

int main(int argc, char **argv)
{
    int netcdf4 = argc > 1 && strcmp(argv[1], "--netcdf") == 0;
    int first = 1 + netcdf4;
    first += argc > first && strcmp(argv[first], "--") == 0; /* "--": a file may be named like an option */
    if (argc - first < 1 || argc - first > 2 - netcdf4) {
        fprintf(stderr, "usage: %s [--] FILE [CHANNEL] | --netcdf [--] FILE\n", argv[0]);
        return 2;
    }
    alarm(CHILD_READ_SECONDS);
    return hdf5_child_write(stdout, argv[first], argc - first == 2 ? argv[first + 1] : "", netcdf4);
}
