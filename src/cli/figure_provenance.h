/* What a figure drawn by `render` and `render view3d` records to be made again (figure_provenance.c),
 * and the shell quoting it shares with indent's Command (indent_record.c). */
#ifndef INDENTMAP_CLI_FIGURE_PROVENANCE_H
#define INDENTMAP_CLI_FIGURE_PROVENANCE_H

#include "front/front.h"

#include <jansson.h>
#include <limits.h>
#include <stddef.h>

/* The most bytes cli_shell_append writes for word: a blank, two quotes and each ' as '\''. */
size_t cli_shell_word_room(const char *word);
/* Writes " WORD" at text + used (size: the whole buffer), WORD quoted for a POSIX shell where it needs
 * it (a path with a space); returns the bytes used after it. */
size_t cli_shell_append(char *text, size_t size, size_t used, const char *word);

typedef struct cli_provenance {
    char *command;                    /* "PROGRAM ARGV...": each word UTF-8 (io.h: im_path_utf8), quoted */
    char directory[4 * PATH_MAX + 1]; /* where it ran: the command's relative paths are from there */
    json_t *inputs;                   /* the files read, with their SHA-256 (front.h: run_record_add_input) */
} cli_provenance;

/* The command line, program ("indentmap", "indentmap render") and argv[0..argc) (argv[0] the subcommand's
 * name), taken before getopt reorders argv, and the working directory. IM_ENOMEM or the error of getcwd.
 * Free with cli_provenance_free. */
int cli_provenance_start(const char *program, int argc, char *const *argv, cli_provenance *p);
/* Adds the input file path (NULL: nothing), given as key ("input", "--contact"); the error of a file that
 * cannot be read. */
int cli_provenance_add_input(cli_provenance *p, const char *key, const char *path);
/* A figure's texts (front.h: run_figure_texts): "Software", "Command", "Directory", the given texts, and
 * "Inputs". IM_ENOMEM. Free with run_figure_texts_free. */
int cli_provenance_texts(const cli_provenance *p, const im_png_text *given, int given_count, run_figure_texts *out);
void cli_provenance_free(cli_provenance *p);

#endif
