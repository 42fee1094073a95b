#include "cli/cli.h"

#include "indentmap/gpu_config.h"
#include "indentmap/render.h"
#include "indentmap/status.h"
#if IM_HAVE_GPU
#include "gpu/vulkan.h"
#endif

#include <fftw3.h>
#include <getopt.h>
#include <gsl/gsl_version.h>
#include <omp.h>
#include <png.h>
#include <stdio.h>
#include <string.h>

static void usage(FILE *stream)
{
    fprintf(stream, "usage: indentmap info [--backend auto|egl|osmesa]\n\nPrints the version, the "
                    "libraries in use and the OpenMP thread count (set it with OMP_NUM_THREADS), and\n"
                    "the OpenGL renderer of the backend (default: IM_RENDER_BACKEND, else auto).\n"
                    "A machine with no OpenGL 3.3 core context prints 'render backend: unavailable (...)';\n"
                    "a context that opens but fails (shaders, set-up) prints 'render backend: failed (...)'\n"
                    "and exits 1.\n"
                    "Then the Vulkan devices the GPU engine could use, one per line ('none: REASON' without\n"
                    "any, 'not built (IM_GPU off)' in a build without the engine).\n");
}

/* The render backend and GL strings; a machine without GL is reported, not an error, but a
 * renderer that opens a context and then fails is. */
static int print_renderer(im_render_backend backend)
{
    im_render_context *context = NULL;
    int status = cli_render_open(backend, &context);
    if (status == IM_EINVAL) /* a bad IM_RENDER_BACKEND: bad input, exit 2 as for render */
        return cli_report(status);
    if (status != IM_OK) {
        int missing = im_render_context_missing(status, im_last_error());
        printf("render backend: %s (%s)\n", missing ? "unavailable" : "failed", im_last_error());
        return missing ? CLI_EXIT_OK : CLI_EXIT_FAILURE;
    }
    printf("render backend: %s, %s\n", im_render_backend_name(context), im_render_display_name(context));
    printf("GL_RENDERER: %s\n", im_render_gl_renderer(context));
    printf("GL_VERSION: %s\n", im_render_gl_version(context));
    im_render_close(context);
    return CLI_EXIT_OK;
}

/* The Vulkan devices, one line each; none is not an error (the CPU solver needs no GPU). */
static void print_vulkan_devices(void)
{
    printf("Vulkan devices:");
#if IM_HAVE_GPU
    char text[4096];
    if (gpu_devices_describe(text, sizeof text) != IM_OK) {
        printf(" none: %s\n", im_last_error());
        return;
    }
    printf("\n");
    char *rest = NULL;
    for (char *line = strtok_r(text, "\n", &rest); line; line = strtok_r(NULL, "\n", &rest))
        printf("  %s\n", line);
#else
    printf(" not built (IM_GPU off)\n");
#endif
}

enum { OPT_BACKEND = 256, OPT_HELP };

static const struct option LONG_OPTIONS[] = {
    {"backend", required_argument, 0, OPT_BACKEND}, {"help", no_argument, 0, OPT_HELP}, {0, 0, 0, 0}};

static int apply_option(int code, const char *arg, void *state)
{
    if (code != OPT_BACKEND)
        return -1;
    if (im_render_backend_from_name(arg, state) == IM_OK)
        return 0;
    fprintf(stderr, "indentmap: --backend: %s\n", im_last_error());
    return -1;
}

int cli_info(int argc, char **argv)
{
    im_render_backend backend = IM_RENDER_AUTO;
    int parsed = cli_parse_options(argc, argv, LONG_OPTIONS, OPT_HELP, usage, apply_option, &backend);
    if (parsed != 0)
        return parsed > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (optind < argc) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    printf("indentmap %s\n", IM_VERSION);
    printf("fftw: %s\n", fftw_version);
    printf("gsl: %s\n", gsl_version);
    printf("libpng: %s\n", png_libpng_ver);
    printf("openmp threads: %d (of %d processors)\n", omp_get_max_threads(), omp_get_num_procs());
    int status = print_renderer(backend);
    if (status != CLI_EXIT_USAGE)
        print_vulkan_devices();
    return status;
}
