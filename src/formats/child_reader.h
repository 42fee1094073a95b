/* formats/child_reader.h: a file read by a program of indentmap's own in a child process.
 *
 * Some parsers cannot be made safe from the caller's side: Gwyddion's vendor modules, and libhdf5,
 * which crashes on some hostile files inside the library. They run in a program of their own
 * (indentmap-gwyddion-read, indentmap-hdf5-read) that writes what it read on its standard output; the
 * library starts it, parses that stream, and turns a crash or a hang of the program into a refusal of
 * the file, never an end of the caller (a Python kernel, an MPI rank). */
#ifndef INDENTMAP_FORMATS_CHILD_READER_H
#define INDENTMAP_FORMATS_CHILD_READER_H

#include <stdio.h>

/* How long a child program may read one file before its own alarm (SIGALRM) ends it: a parser looping on a
 * damaged file. Each program sets it; the library reports it as "ran out of time". */
enum { CHILD_READ_SECONDS = 300 };

/* The longest line of a stream's text part (a longer one is cut). */
enum { CHILD_STREAM_LINE = 4096 };

typedef struct child_program {
    const char *name;        /* e.g. "indentmap-hdf5-read", looked for beside the running executable */
    const char *mode;        /* an argument before the file's, choosing what the program reads, or NULL */
    const char *environment; /* e.g. "INDENTMAP_HDF5_READER": names another program */
    const char *installed;   /* its installed path (libexec), or NULL */
    const char *reader;      /* the program in messages: "Gwyddion's reader" */
    const char *parser;      /* what crashes or hangs in it: "Gwyddion's file module" */
    const char *damage;      /* what a crash says of the file: "a damaged file?" */
} child_program;

/* The program to run: the one the environment variable names (read with secure_getenv; NULL when it is not
 * executable), else the one beside the running executable (found through /proc/self/exe), else the one beside
 * the shared object holding this code (dladdr: libindentmap.so, the Python extension), never a path fixed at
 * build time that someone else could create later; else the installed one; NULL when there is none. */
const char *child_program_path(const child_program *program);

/* Parses the program's stream into result. *answered: whether the stream held the program's own answer
 * (a refusal or the data), which then decides over its exit status. */
typedef int (*child_stream_parser)(FILE *stream, const char *path, void *result, int *answered);

/* Runs executable (its mode when it has one, "--", path, then channel unless it is "") with its stream on a pipe and its standard
 * error kept, parses the stream, then waits for it: IM_EFORMAT naming path when it died by a signal (its
 * alarm: "ran out of time"; another: "crashed", naming the signal and quoting its last line of errors), or
 * when it ended with a non-zero status without answering (its last line of errors quoted); else the
 * parser's status. The program runs with no signal blocked and the default actions (Python ignores
 * SIGPIPE); when another part of the process reaps children, the stream alone decides. */
int child_read(const child_program *program, const char *executable, const char *path, const char *channel,
               child_stream_parser parse, void *result);

/* One text line of a stream into line (CHILD_STREAM_LINE bytes), without its newline and with control bytes
 * but tabs shown as '?' (the text comes from files); 0 at the end of the stream. */
int child_stream_line(FILE *stream, char *line);

/* Writes prefix then text as one line of a stream: control bytes but tabs written as '?', so that no text from
 * a file can break a line. */
void child_stream_put_line(FILE *stream, const char *prefix, const char *text);

#endif
