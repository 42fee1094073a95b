/* Instrument formats through Gwyddion's file modules: the program that runs them, and its stream. */
#define _GNU_SOURCE /* pipe2 */
#include "io/gwyddion.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

/* The program beside the running executable (a build tree's, or bin/ beside libexec/ when installed
 * so): found through /proc/self/exe, the program's own folder, never a path fixed at build time
 * that someone else could create later. */
static const char *reader_beside_this_program(void)
{
    static __thread char path[4096];
    ssize_t length = readlink("/proc/self/exe", path, sizeof path - 64);
    if (length <= 0)
        return NULL;
    path[length] = '\0';
    char *slash = strrchr(path, '/');
    if (!slash)
        return NULL;
    snprintf(slash + 1, 64, "indentmap-gwyddion-read");
    return access(path, X_OK) == 0 ? path : NULL;
}

const char *im_gwyddion_reader(void)
{
    const char *chosen = secure_getenv("INDENTMAP_GWYDDION_READER");
    if (chosen && chosen[0])
        return access(chosen, X_OK) == 0 ? chosen : NULL;
    const char *beside = reader_beside_this_program();
    if (beside)
        return beside;
#ifdef IM_GWYDDION_READER_INSTALLED
    if (access(IM_GWYDDION_READER_INSTALLED, X_OK) == 0)
        return IM_GWYDDION_READER_INSTALLED;
#endif
    return NULL;
}

enum { STREAM_LINE = 4096, MAX_LISTED = 8 };

/* One text line of the stream, without its newline, control bytes shown as '?' (titles come from
 * the files); 0 at the end of the stream. */
static int stream_line(FILE *stream, char *line)
{
    if (!fgets(line, STREAM_LINE, stream)) {
        line[0] = '\0';
        return 0;
    }
    size_t length = strcspn(line, "\n");
    if (line[length] != '\n')
        for (int c = fgetc(stream); c != EOF && c != '\n'; c = fgetc(stream))
            ; /* a longer line is cut */
    line[length] = '\0';
    for (char *at = line; *at; ++at)
        if ((unsigned char)*at < 0x20 && *at != '\t')
            *at = '?';
    return 1;
}

typedef struct stream_header {
    char module[64];
    char channels[512]; /* "0 'Height' [m], 1 'Phase' [deg], ..." for messages */
    int channel_count;
    int id, nx, ny, masked;
    double x_extent, y_extent;
    char lateral[16], height[16];
    char title[64];     /* the chosen channel's */
} stream_header;

/* "channel ID<TAB>XRES<TAB>YRES<TAB>ZUNIT<TAB>TITLE": appended to the list for messages. */
static void take_channel_line(const char *line, stream_header *header)
{
    int id = -1, consumed = 0;
    char unit[32] = "";
    sscanf(line, "channel %d\t%*d\t%*d\t%31[^\t]\t%n", &id, unit, &consumed);
    const char *title = consumed ? line + consumed : "";
    size_t used = strlen(header->channels);
    if (header->channel_count < MAX_LISTED)
        snprintf(header->channels + used, sizeof header->channels - used, "%s%d '%.40s' [%s]",
                 header->channel_count ? ", " : "", id, title, unit);
    else if (header->channel_count == MAX_LISTED)
        snprintf(header->channels + used, sizeof header->channels - used, ", ...");
    ++header->channel_count;
}

static int take_field_line(const char *path, const char *line, stream_header *header)
{
    char lateral[32], height[32];
    int consumed = 0;
    if (sscanf(line, "field %d %d %d %lf %lf %31s %31s %d %n", &header->id, &header->nx, &header->ny,
               &header->x_extent, &header->y_extent, lateral, height, &header->masked, &consumed) != 8 ||
        header->nx < 1 || header->ny < 1 || header->nx > IM_FIELD_MAX_SIDE || header->ny > IM_FIELD_MAX_SIDE ||
        !isfinite(header->x_extent) || !(header->x_extent > 0.0) || !isfinite(header->y_extent) ||
        !(header->y_extent > 0.0) || (header->masked != 0 && header->masked != 1))
        return im_fail(IM_EFORMAT, "%s: Gwyddion's reader described the field as '%.80s': expected sides 1 to %d "
                       "and extents > 0", path, line, IM_FIELD_MAX_SIDE);
    snprintf(header->lateral, sizeof header->lateral, "%.15s", strcmp(lateral, "-") ? lateral : "");
    snprintf(header->height, sizeof header->height, "%.15s", strcmp(height, "-") ? height : "");
    snprintf(header->title, sizeof header->title, "%.63s", consumed ? line + consumed : "");
    return IM_OK;
}

static int read_stream_header(FILE *stream, const char *path, stream_header *header, int *answered)
{
    char line[STREAM_LINE];
    if (!stream_line(stream, line) || strcmp(line, "indentmap-gwyddion-read 1") != 0)
        return im_fail(IM_EFORMAT, "%s: Gwyddion's reader gave no answer one can read (first line '%.40s')", path,
                       line);
    while (stream_line(stream, line)) {
        *answered = strncmp(line, "error ", 6) == 0 || strncmp(line, "field ", 6) == 0;
        if (strncmp(line, "error unknown-format ", 21) == 0)
            return im_fail(IM_EFORMAT, "%s: " GWYDDION_UNKNOWN_FORMAT ": %.200s", path, line + 21);
        if (strncmp(line, "error line-scan ", 16) == 0)
            return im_fail(IM_EFORMAT, "%s: " LINE_SCAN_REFUSAL ": Gwyddion's module '%s' reads it as %.200s; "
                           LINE_SCAN_ADVICE, path, header->module, line + 16);
        if (strncmp(line, "error failed ", 13) == 0)
            return im_fail(IM_EFORMAT, "%s: Gwyddion's file modules cannot read it: %.200s", path, line + 13);
        if (sscanf(line, "module %63s", header->module) == 1)
            continue;
        if (strncmp(line, "channel ", 8) == 0) {
            take_channel_line(line, header);
            continue;
        }
        if (strncmp(line, "field ", 6) != 0)
            return im_fail(IM_EFORMAT, "%s: Gwyddion's reader wrote '%.40s': expected a field", path, line);
        return take_field_line(path, line, header);
    }
    return im_fail(IM_EFORMAT, "%s: Gwyddion's reader ended before the field", path);
}

/* The heights, and NaN where the mask marks a point invalid; nothing may follow. */
static int read_stream_values(FILE *stream, const char *path, const stream_header *header, im_field *field)
{
    size_t count = im_field_count(field);
    if (fread(field->data, sizeof(double), count, stream) != count)
        return im_fail(IM_EFORMAT, "%s: Gwyddion's reader ended inside the heights (%zu expected)", path, count);
    for (size_t k = 0; header->masked && k < count; ++k) {
        int invalid = fgetc(stream);
        if (invalid == EOF)
            return im_fail(IM_EFORMAT, "%s: Gwyddion's reader ended inside the mask", path);
        if (invalid)
            field->data[k] = NAN;
    }
    return fgetc(stream) == EOF ? IM_OK : im_fail(IM_EFORMAT, "%s: Gwyddion's reader wrote more than the field", path);
}

/* Gwyddion keeps values in base SI units: heights in "m", and any other unit is not a height. */
static int state_units(const char *path, const stream_header *header, surface_stated *stated)
{
    if (header->height[0] && strcmp(header->height, "m") != 0)
        return im_fail(IM_EFORMAT, "%s: channel %d '%.40s' holds values in '%s', not heights (a length); its "
                       "channels: %s; choose one with --channel", path, header->id, header->title, header->height,
                       header->channels);
    *stated = (surface_stated){.spacing_keys = "Gwyddion's xreal / xres and yreal / yres",
                               .lateral_key = "Gwyddion's lateral unit", .height_key = "Gwyddion's value unit"};
    stated->units.delta_x = header->x_extent / header->nx;
    stated->units.delta_y = header->y_extent / header->ny;
    snprintf(stated->units.lateral, sizeof stated->units.lateral, "%s", header->lateral);
    snprintf(stated->units.height, sizeof stated->units.height, "%s", header->height);
    snprintf(stated->conversion, sizeof stated->conversion, "Gwyddion '%.16s': channel %d '%.24s' of %d",
             header->module, header->id, header->title, header->channel_count);
    return IM_OK;
}

/* A stream in a regular file (the fuzz harness's) must hold the values its field line claims before
 * they are allocated; from the program's pipe they come from a field Gwyddion already holds. */
static int check_values_present(FILE *stream, const char *path, const stream_header *header)
{
    struct stat about;
    long at = ftell(stream);
    double needed = (double)header->nx * header->ny * (sizeof(double) + (header->masked ? 1 : 0));
    if (fstat(fileno(stream), &about) != 0 || !S_ISREG(about.st_mode) || at < 0 ||
        (double)(about.st_size - at) >= needed)
        return IM_OK;
    return im_fail(IM_EFORMAT, "%s: Gwyddion's reader ended inside the heights (%d x %d claimed, %lld bytes left)",
                   path, header->nx, header->ny, (long long)(about.st_size - at));
}

/* The stream parsed; *answered says whether it held an error line or a field (else the program's exit
 * status and errors explain it better). */
static int stream_parse(FILE *stream, const char *path, im_field **out, surface_stated *stated, int *answered)
{
    *out = NULL;
    stream_header header = {0};
    int status = read_stream_header(stream, path, &header, answered);
    if (status == IM_OK)
        status = state_units(path, &header, stated);
    if (status == IM_OK)
        status = check_values_present(stream, path, &header);
    im_field *field = NULL;
    if (status == IM_OK)
        status = im_field_create(header.nx, header.ny, 1.0, &field);
    if (status == IM_OK)
        status = read_stream_values(stream, path, &header, field);
    if (status == IM_OK)
        *out = field;
    else
        im_field_free(field);
    return status;
}

int gwyddion_stream_file_read(const char *path, im_field **out)
{
    *out = NULL;
    FILE *stream = fopen(path, "rb");
    if (!stream)
        return im_fail(IM_EIO, "%s: cannot open: %s", path, strerror(errno));
    surface_stated stated;
    im_field *field = NULL;
    int answered = 0;
    int status = stream_parse(stream, path, &field, &stated, &answered);
    fclose(stream);
    if (status == IM_OK)
        status = surface_finish(path, field, &stated, NULL, NULL);
    if (status == IM_OK)
        *out = field;
    else
        im_field_free(field);
    return status;
}

/* The program's environment for one read: a pipe for its stream, a temporary file for its errors. */
typedef struct reader_process {
    pid_t child;
    FILE *from, *errors;
    int started;
    int answered; /* the stream held an error line or a field: its words are the refusal */
} reader_process;

/* Spawn attributes: no signal blocked and the default actions for those a caller may have changed
 * (Python ignores SIGPIPE; the alarm that bounds a module's time must end it). */
static void default_signals(posix_spawnattr_t *attributes)
{
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    int reset[] = {SIGPIPE, SIGINT, SIGTERM, SIGALRM, SIGCHLD};
    for (size_t k = 0; k < sizeof reset / sizeof *reset; ++k)
        sigaddset(&defaults, reset[k]);
    posix_spawnattr_init(attributes);
    posix_spawnattr_setsigmask(attributes, &none);
    posix_spawnattr_setsigdefault(attributes, &defaults);
    posix_spawnattr_setflags(attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
}

/* Starts the program on path ("--" first: a file may be named like an option), its stream on a pipe,
 * its errors (Gwyddion's warnings, a loader's message) into a temporary file quoted on failure. */
static int start_reader(const char *program, const char *path, const char *channel, reader_process *reader)
{
    int ends[2];
    reader->errors = tmpfile();
    if (!reader->errors || pipe2(ends, O_CLOEXEC) != 0)
        return im_fail(IM_EIO, "%s: cannot start Gwyddion's reader: %s", path, strerror(errno));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, ends[1], 1);
    posix_spawn_file_actions_adddup2(&actions, fileno(reader->errors), 2);
    posix_spawnattr_t attributes;
    default_signals(&attributes);
    char *arguments[] = {(char *)program, "--", (char *)path, channel[0] ? (char *)channel : NULL, NULL};
    int failed = posix_spawn(&reader->child, program, &actions, &attributes, arguments, environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    close(ends[1]);
    if (failed) {
        close(ends[0]);
        return im_fail(IM_EIO, "%s: cannot start Gwyddion's reader %s: %s", path, program, strerror(failed));
    }
    reader->started = 1;
    reader->from = fdopen(ends[0], "rb");
    if (reader->from)
        return IM_OK;
    close(ends[0]); /* the reader's next write fails and ends it */
    return im_fail(IM_ENOMEM, "%s: cannot read Gwyddion's reader: %s", path, strerror(errno));
}

/* The last line the program wrote on its standard error, or "". */
static void last_error_line(FILE *errors, char *line, size_t size)
{
    char text[STREAM_LINE];
    line[0] = '\0';
    rewind(errors);
    while (fgets(text, sizeof text, errors))
        if (text[strspn(text, " \t\r\n")])
            snprintf(line, size, "%.*s", (int)strcspn(text, "\r\n"), text);
}

/* The program's end: a crash or a hang in a vendor parser is a refusal of the file, not of the caller.
 * When another part of the process reaps children (SIGCHLD ignored, a watcher), the status is gone:
 * the stream alone then decides. */
static int finish_reader(const char *path, const reader_process *reader, int parsed)
{
    int how = 0;
    pid_t ended;
    while ((ended = waitpid(reader->child, &how, 0)) < 0 && errno == EINTR)
        ;
    if (ended < 0)
        return parsed;
    char said[200];
    last_error_line(reader->errors, said, sizeof said);
    if (WIFSIGNALED(how) && WTERMSIG(how) == SIGALRM)
        return im_fail(IM_EFORMAT, "%s: Gwyddion's file module ran out of time reading it (a damaged file?)", path);
    if (WIFSIGNALED(how) && WTERMSIG(how) != SIGPIPE)
        return im_fail(IM_EFORMAT, "%s: Gwyddion's file module crashed reading it (signal %d): a damaged file?%s%s",
                       path, WTERMSIG(how), said[0] ? " It said: " : "", said);
    if (parsed != IM_OK && !reader->answered && WIFEXITED(how) && WEXITSTATUS(how) != 0)
        return im_fail(IM_EFORMAT, "%s: Gwyddion's reader ended with status %d%s%s", path, WEXITSTATUS(how),
                       said[0] ? ": " : "", said);
    return parsed;
}

/* Values without a unit beside lateral sizes in a unit are counts or volts as often as lengths: their
 * unit is not guessed (a file with no units at all is read as a bare matrix). */
static int check_height_unit(const char *path, const surface_stated *stated, const im_surface_read_options *options)
{
    if (stated->units.height[0] || !stated->units.lateral[0] || (options && options->set.height[0]))
        return IM_OK;
    return im_fail(IM_EFORMAT, "%s: %s: its values have no unit beside lateral sizes in %s: give their unit "
                   "(--height-unit) if they are heights", path, stated->conversion, stated->units.lateral);
}

int gwyddion_read_raw(const char *path, const im_surface_read_options *options, im_field **out,
                      surface_stated *stated)
{
    *out = NULL;
    const char *program = im_gwyddion_reader();
    if (!program)
        return im_fail(IM_EFORMAT, "%s: a format read through Gwyddion's file modules, which this build lacks "
                       "(install libgwyddion20-dev and gwyddion, then rebuild)", path);
    reader_process reader = {0};
    int status = start_reader(program, path, options ? options->channel : "", &reader);
    if (status == IM_OK)
        status = stream_parse(reader.from, path, out, stated, &reader.answered);
    if (reader.from)
        fclose(reader.from); /* before the wait: a reader still writing ends on the closed pipe */
    if (reader.started)
        status = finish_reader(path, &reader, status);
    if (reader.errors)
        fclose(reader.errors);
    if (status == IM_OK)
        status = check_height_unit(path, stated, options);
    if (status != IM_OK && *out) {
        im_field_free(*out);
        *out = NULL;
    }
    return status;
}
