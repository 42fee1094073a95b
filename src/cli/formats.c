/* indentmap formats: the surface formats this build reads, its own and Gwyddion's. */
#include "cli/cli.h"

#include "indentmap/io.h"

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

static const char *const OWN_FORMATS[] = {
    ".npy   NumPy array, float or integer (units in its .json sidecar)            read, write",
    ".gsf   Gwyddion Simple Field                                                read, write",
    ".sdf   ISO 25178-71, ASCII or binary                                        read, write",
    ".nc    NetCDF, SurfaceTopography / contact.engineering layout               read, write",
    ".x3p   ISO 25178-72 (ISO 5436-2 XML in a zip)                               read, write",
    ".tmd   TrueMap / GelSight binary (lengths and heights in mm)                read",
    ".h5    HDF5: each 2-D numeric data set a channel; a bare matrix             read",
    ".zip   contact.engineering container (meta.yml): each topography a channel  read",
    "text   matrix; x y z points on a grid; Gwyddion (English, German) and\n"
    "         Wyko/Vision ASCII exports; decimal commas                          read, write (matrix)",
};

static int compare_lines(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Prints the lines the program listed ("NAME<TAB>WHAT"), sorted by name. */
static void print_sorted(char **lines, int count)
{
    qsort(lines, (size_t)count, sizeof *lines, compare_lines);
    for (int k = 0; k < count; ++k) {
        char *what = strchr(lines[k], '\t');
        printf("  %-14.*s %s", what ? (int)(what - lines[k]) : 0, lines[k], what ? what + 1 : lines[k]);
    }
}

/* Gwyddion's modules that load files, as the program lists them. */
static int print_gwyddion_modules(const char *program)
{
    char command[4200];
    snprintf(command, sizeof command, "'%s' --formats", program);
    FILE *listing = strchr(program, '\'') ? NULL : popen(command, "r");
    if (!listing) {
        fprintf(stderr, "indentmap: formats: cannot run %s\n", program);
        return CLI_EXIT_FAILURE;
    }
    enum { MAX_MODULES = 1024 };
    static char lines[MAX_MODULES][256];
    char *sorted[MAX_MODULES];
    int count = 0;
    while (count < MAX_MODULES && fgets(lines[count], sizeof lines[count], listing)) {
        sorted[count] = lines[count];
        ++count;
    }
    int ended = pclose(listing);
    print_sorted(sorted, count);
    printf("(%d Gwyddion modules)\n", count);
    return ended == 0 && count > 0 ? CLI_EXIT_OK : CLI_EXIT_FAILURE;
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
    printf("indentmap's own readers:\n");
    for (size_t k = 0; k < sizeof OWN_FORMATS / sizeof *OWN_FORMATS; ++k)
        printf("  %s\n", OWN_FORMATS[k]);
    const char *program = im_gwyddion_reader();
    if (!program) {
        printf("Gwyddion's file modules: not in this build (install libgwyddion20-dev and gwyddion, then rebuild)\n");
        return CLI_EXIT_OK;
    }
    printf("Gwyddion's file modules, through %s (any other file that is not text):\n", program);
    return print_gwyddion_modules(program);
}
