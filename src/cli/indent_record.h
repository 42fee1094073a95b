/* indent's arguments in its run record, and the run made again from them (`indent --from-record`;
 * indent_record.c). */
#ifndef INDENTMAP_CLI_INDENT_RECORD_H
#define INDENTMAP_CLI_INDENT_RECORD_H

#include <jansson.h>

/* run.json's "arguments": the options as given, in their order, then SURFACE, paths made absolute,
 * without --out, --wisdom and --no-wisdom (where a run writes and plans is the machine's, not the
 * run's). */
typedef struct indent_arguments {
    json_t *list; /* strings: UTF-8, escaped (im_path_utf8) where not */
    int escaped;  /* 1 when one was not UTF-8: its bytes are not recoverable by the replay */
} indent_arguments;

/* Appends the long option named option ("load" for --load) with value (NULL for a flag; a path made
 * absolute when is_path) or, when option is NULL, the operand value. IM_ENOMEM, or the error of a path
 * that cannot be made absolute. */
int indent_arguments_add(indent_arguments *arguments, const char *option, const char *value, int is_path);

/* "indentmap indent ARGUMENTS", each argument quoted for a POSIX shell where it needs it (a path with a
 * space); NULL when out of memory. The caller frees it. */
char *indent_arguments_command(const indent_arguments *arguments);

/* What `indent --from-record` was given beside the record. */
typedef struct indent_replay_options {
    const char *out;    /* NULL: the record's folder, where the recorded run wrote */
    const char *wisdom; /* --wisdom; NULL: as the record's plans were made (estimated: --no-wisdom) */
    int no_wisdom;
} indent_replay_options;

/* The command line that makes a recorded run again: "indent", the record's arguments, --out and the
 * wisdom options. The record must be one of this version's indent runs, hold its arguments, and each
 * of its inputs still have its recorded SHA-256: IM_EFORMAT or IM_EINVAL naming the record (and the
 * changed file with both checksums) otherwise. */
typedef struct indent_replay {
    json_t *root; /* the record, which the argument strings borrow */
    char **argv;
    int argc;
    char out[4096];
} indent_replay;

int indent_replay_load(const char *record, const indent_replay_options *given, indent_replay *replay);
void indent_replay_free(indent_replay *replay);

#endif
