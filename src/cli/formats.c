/* indentmap formats: the surface formats this build reads, its own and Gwyddion's. */
#include "cli/cli.h"

#include "indentmap/info.h"
#include "indentmap/status.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *stream)
{
    fprintf(stream, "usage: indentmap formats\n\nLists the surface formats this build reads (surface --stats, "
                    "indent, scenes' file =, Python's\nread): its own readers, then each of Gwyddion's file "
                    "modules when the build has\nindentmap-gwyddion-read (Debian: libgwyddion20-dev and "
                    "gwyddion at build time).\n");
}

int cli_formats(int argc, char **argv)
{
    if (argc > 1 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        usage(stdout);
        return CLI_EXIT_OK;
    }
    if (argc > 1) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    char *text = NULL;
    int status = im_formats_text(&text);
    if (text)
        fputs(text, stdout);
    free(text);
    if (status == IM_OK)
        return CLI_EXIT_OK;
    fprintf(stderr, "indentmap: %s\n", im_last_error());
    return CLI_EXIT_FAILURE;
}
