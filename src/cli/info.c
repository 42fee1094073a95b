#include "cli/cli.h"

#include "indentmap/info.h"
#include "indentmap/render.h"
#include "indentmap/status.h"

#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>

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

enum { OPT_BACKEND = 256, OPT_HELP };

static const struct option LONG_OPTIONS[] = {{"backend", required_argument, 0, OPT_BACKEND},
                                             {"help", no_argument, 0, OPT_HELP},
                                             {0, 0, 0, 0}};

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
