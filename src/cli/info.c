#include "cli/cli.h"

#include <fftw3.h>
#include <getopt.h>
#include <gsl/gsl_version.h>
#include <omp.h>
#include <png.h>
#include <stdio.h>
#include <string.h>

static void usage(FILE *stream)
{
    fprintf(stream, "usage: indentmap info\n\nPrints the version, the libraries in use and the "
                    "OpenMP thread count (set it with OMP_NUM_THREADS).\n");
}

int cli_info(int argc, char **argv)
{
    if (argc > 1 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        usage(stdout);
        return CLI_EXIT_OK;
    }
    if (argc > 1) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    printf("indentmap %s\n", IM_VERSION);
    printf("fftw: %s\n", fftw_version);
    printf("gsl: %s\n", gsl_version);
    printf("libpng: %s\n", png_libpng_ver);
    printf("openmp threads: %d (of %d processors)\n", omp_get_max_threads(), omp_get_num_procs());
    return CLI_EXIT_OK;
}
