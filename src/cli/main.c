/* indentmap: the command-line program. Git-style subcommands, each with --help. */
#include "cli/cli.h"
#include "indentmap/mpi.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

typedef struct subcommand {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} subcommand;

static const subcommand SUBCOMMANDS[] = {
    {"surface", cli_surface, "generate a self-affine rough surface, or measure one (--stats FILE)"},
    {"theory", cli_theory, "the paper's contact-area theory for a cone: eqs. (6), (7), (12) and gamma(r)"},
    {"indent", cli_indent, "indent a surface with a cone, sphere or flat punch: history.csv, run.json, fields"},
    {"render", cli_render, "draw a force or height field file as a figure (PNG, PDF, SVG) or animation"},
    {"run", cli_run, "run a scene file (scenes/fig4.ini: the paper's Fig. 4): solve, render, write"},
    {"formats", cli_formats, "list the surface formats this build reads (its own, and Gwyddion's file modules)"},
    {"info", cli_info, "print the version, FFTW version and OpenMP thread count"},
#if IM_HAVE_MPI
    {"mpi-indent", cli_mpi_indent,
     "one indentation of one surface over MPI ranks (mpirun -n K indentmap mpi-indent)"},
#endif
};
static const int SUBCOMMAND_COUNT = (int)(sizeof SUBCOMMANDS / sizeof SUBCOMMANDS[0]);

static void usage(FILE *stream)
{
    fprintf(stream, "usage: indentmap [--version] [--help] COMMAND [OPTIONS]\n\n"
                    "Indentation of rough elastic surfaces by a cone: solve, compare with theory, "
                    "draw.\n\ncommands:\n");
    for (int i = 0; i < SUBCOMMAND_COUNT; ++i)
        fprintf(stream, "  %-10s %s\n", SUBCOMMANDS[i].name, SUBCOMMANDS[i].summary);
    fprintf(stream, "\n'indentmap COMMAND --help' describes a command's options.\n");
}

/* Standard output is checked to the end: a full disk or a closed pipe makes the command fail
 * (exit 1 with the reason) instead of leaving a cut file behind an exit status of 0. */
static int close_standard_output(int status)
{
    errno = 0;
    int failed = fflush(stdout) != 0;
    int saved = errno;
    failed |= ferror(stdout) != 0;
    failed |= fclose(stdout) != 0;
    if (!saved)
        saved = errno;
    if (!failed)
        return status;
    fprintf(stderr, "indentmap: standard output: write failed: %s; what was written there is incomplete\n",
            saved ? strerror(saved) : "an earlier write failed");
    return status == CLI_EXIT_OK ? CLI_EXIT_FAILURE : status;
}

int main(int argc, char **argv)
{
    cli_prefer_short_spinning(argv);
    if (argc < 2) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    if (strcmp(argv[1], "--version") == 0) {
        printf("indentmap %s\n", IM_VERSION);
        return close_standard_output(CLI_EXIT_OK);
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "help") == 0) {
        usage(stdout);
        return close_standard_output(CLI_EXIT_OK);
    }
    for (int i = 0; i < SUBCOMMAND_COUNT; ++i)
        if (strcmp(argv[1], SUBCOMMANDS[i].name) == 0)
            return cli_apply_memory_limit() != 0 ? CLI_EXIT_USAGE
                                                 : close_standard_output(SUBCOMMANDS[i].run(argc - 1, argv + 1));
    fprintf(stderr, "indentmap: '%s' is not a command\n\n", argv[1]);
    usage(stderr);
    return CLI_EXIT_USAGE;
}
