/* The record a render figure carries: the command line as given, where it ran and its inputs' SHA-256. */
#include "cli/figure_provenance.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Whether text can stand unquoted in a POSIX shell's command line. */
static int shell_plain(const char *text)
{
    return text[0] &&
           strspn(text, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-+=.,:/@%") == strlen(text);
}

size_t cli_shell_word_room(const char *word) { return 4 * strlen(word) + 3; }

size_t cli_shell_append(char *text, size_t size, size_t used, const char *word)
{
    if (shell_plain(word))
        return used + (size_t)snprintf(text + used, size - used, " %s", word);
    used += (size_t)snprintf(text + used, size - used, " '");
    for (const char *c = word; *c; ++c)
        used += (size_t)snprintf(text + used, size - used, *c == '\'' ? "'\\''" : "%c", *c);
    return used + (size_t)snprintf(text + used, size - used, "'");
}

/* program and the words, each made UTF-8 and quoted. */
static char *command_text(const char *program, int argc, char *const *argv)
{
    size_t size = strlen(program) + 1, longest = 0;
    for (int i = 0; i < argc; ++i) {
        size_t escaped = 4 * strlen(argv[i]) + 1; /* each byte at most \xHH */
        size += 4 * escaped + 3;                  /* quoted: each ' as '\'' */
        longest = escaped > longest ? escaped : longest;
    }
    char *text = malloc(size), *word = malloc(longest);
    size_t used = text ? (size_t)snprintf(text, size, "%s", program) : 0;
    for (int i = 0; text && word && i < argc; ++i) {
        im_path_utf8(argv[i], word, longest);
        used = cli_shell_append(text, size, used, word);
    }
    if (!word) {
        free(text);
        text = NULL;
    }
    free(word);
    return text;
}

int cli_provenance_start(const char *program, int argc, char *const *argv, cli_provenance *p)
{
    *p = (cli_provenance){.command = command_text(program, argc, argv), .inputs = json_array()};
    char directory[PATH_MAX];
    if (!p->command || !p->inputs)
        return im_fail(IM_ENOMEM, "figure texts: out of memory");
    if (!getcwd(directory, sizeof directory))
        return im_fail(IM_EIO, "the working directory: %s", strerror(errno));
    im_path_utf8(directory, p->directory, sizeof p->directory);
    return IM_OK;
}

int cli_provenance_add_input(cli_provenance *p, const char *key, const char *path)
{
    return path ? run_record_add_input(p->inputs, key, path) : IM_OK;
}

int cli_provenance_texts(const cli_provenance *p, const im_png_text *given, int given_count, run_figure_texts *out)
{
    im_png_text texts[RUN_FIGURE_TEXTS_MAX];
    int count = 0;
    texts[count++] = (im_png_text){"Command", p->command};
    texts[count++] = (im_png_text){"Directory", p->directory};
    for (int i = 0; i < given_count && count < RUN_FIGURE_TEXTS_MAX - 2; ++i)
        texts[count++] = given[i];
    return run_figure_texts_make(texts, count, p->inputs, out);
}

void cli_provenance_free(cli_provenance *p)
{
    free(p->command);
    json_decref(p->inputs);
    *p = (cli_provenance){.command = NULL};
}
