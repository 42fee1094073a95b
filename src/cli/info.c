#include "cli/cli.h"

#include "indentmap/render.h"
#include "indentmap/status.h"

#include <fftw3.h>
#include <gsl/gsl_version.h>
#include <omp.h>
#include <png.h>
#include <stdio.h>
#include <string.h>

static void usage(FILE *stream)
{
    fprintf(stream, "usage: indentmap info\n\nPrints the version, the libraries in use and the "
                    "OpenMP thread count (set it with OMP_NUM_THREADS), and the OpenGL renderer the\n"
                    "environment gives (choose it with IM_RENDER_BACKEND=auto|egl|osmesa).\n");
}

/* The render backend and GL strings; a machine without GL is reported, not an error. */
static void print_renderer(void)
{
    im_render_context *context = NULL;
    if (im_render_open(IM_RENDER_AUTO, &context) != IM_OK) {
        printf("render backend: unavailable (%s)\n", im_last_error());
        return;
    }
    printf("render backend: %s, %s\n", im_render_backend_name(context), im_render_display_name(context));
    printf("GL_RENDERER: %s\n", im_render_gl_renderer(context));
    printf("GL_VERSION: %s\n", im_render_gl_version(context));
    im_render_close(context);
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
    print_renderer();
    return CLI_EXIT_OK;
}
