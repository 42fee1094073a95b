#include "cli/cli.h"

#include "indentmap/info.h"
#include "indentmap/field.h"
#include "indentmap/render.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"

#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>

static void usage(FILE *stream)
{
    fprintf(stream, "usage: indentmap info [--backend auto|egl|osmesa] [--memory N]\n\nPrints the version, the "
                    "libraries in use and the OpenMP thread count (set it with OMP_NUM_THREADS), and\n"
                    "the OpenGL renderer of the backend (default: IM_RENDER_BACKEND, else auto).\n"
                    "A machine with no OpenGL 3.3 core context prints 'render backend: unavailable (...)';\n"
                    "a context that opens but fails (shaders, set-up) prints 'render backend: failed (...)'\n"
                    "and exits 1.\n"
                    "Then the Vulkan devices the GPU engine could use, one per line ('none: REASON' without\n"
                    "any, 'not built (IM_GPU off)' in a build without the engine).\n"
                    "--memory N prints instead the memory an N x N solve's plan needs (the default options:\n"
                    "preconditioner and cascade), on the half-space and periodic, on the CPU (host) and on the\n"
                    "GPU device = gpu takes (host and device, against the device's memory); the surface and\n"
                    "fields come on top (docs/solver.md, \"Limits\").\n");
}

enum { OPT_BACKEND = 256, OPT_MEMORY, OPT_HELP };

static const struct option LONG_OPTIONS[] = {{"backend", required_argument, 0, OPT_BACKEND},
                                             {"memory", required_argument, 0, OPT_MEMORY},
                                             {"help", no_argument, 0, OPT_HELP},
                                             {0, 0, 0, 0}};

typedef struct {
    im_render_backend backend;
    int memory_side; /* --memory N; 0: none */
} info_options;

static int apply_option(int code, const char *arg, void *state)
{
    info_options *o = state;
    if (code == OPT_MEMORY)
        return cli_parse_int("--memory", arg, 1, IM_FIELD_MAX_SIDE, &o->memory_side) == 0 ? 0 : -1;
    if (code != OPT_BACKEND)
        return -1;
    if (im_render_backend_from_name(arg, &o->backend) == IM_OK)
        return 0;
    fprintf(stderr, "indentmap: --backend: %s\n", im_last_error());
    return -1;
}

/* One engine's line of --memory: its estimate, or why it has none. */
static void print_plan_memory(int n, int periodic, int device)
{
    im_solver_options o = im_solver_options_default();
    o.periodic = periodic;
    o.device = device;
    im_solver_memory m;
    const int status = im_solver_memory_needed(n, n, &o, &m);
    const double gib = 1073741824.0;
    printf("  %-10s %s: ", periodic ? "periodic" : "half-space", device == IM_DEVICE_CPU ? "cpu" : "gpu");
    if (status != IM_OK && !m.gpu) {
        printf("none (%s)\n", im_last_error());
        return;
    }
    printf("host %.3g GiB", m.host_bytes / gib);
    if (m.gpu)
        printf(", device %.3g GiB of %s's %.3g GiB%s", m.device_bytes / gib, m.device, m.device_memory / gib,
               status == IM_OK ? "" : ": does not fit");
    printf("\n");
}

static int print_memory(int n)
{
    printf("memory of a %d x %d solve's plan (the surface and fields not counted):\n", n, n);
    for (int periodic = 0; periodic < 2; ++periodic)
        for (int gpu = 0; gpu < 2; ++gpu)
            print_plan_memory(n, periodic, gpu ? IM_DEVICE_GPU : IM_DEVICE_CPU);
    return CLI_EXIT_OK;
}

int cli_info(int argc, char **argv)
{
    info_options o = {.backend = IM_RENDER_AUTO};
    int parsed = cli_parse_options(argc, argv, LONG_OPTIONS, OPT_HELP, usage, apply_option, &o);
    if (parsed != 0)
        return parsed > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (optind < argc) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    if (o.memory_side)
        return print_memory(o.memory_side);
    im_render_backend backend = o.backend;
    int status = cli_render_backend(&backend);
    if (status != IM_OK) /* a bad IM_RENDER_BACKEND: bad input, exit 2 as for render */
        return cli_report(status);
    char *text = NULL;
    status = im_info_text(backend, &text);
    const int printed = text != NULL; /* a renderer that failed is named in the text: exit 1 */
    if (printed)
        fputs(text, stdout);
    free(text);
    return status == IM_OK ? CLI_EXIT_OK : printed ? CLI_EXIT_FAILURE : cli_report(status);
}
