/* Reading a scene file: the INI lines, each key given once in a known section and parsed by its
 * entry of keys.c's table, the contents noted, then the settings completed and checked (check.c).
 * Every error is one message with the file and line ("scene.ini:7: ..."). */
#include "indentmap/scene.h"
#include "scene/contents.h"
#include "indentmap/io.h"
#include "indentmap/status.h"
#include "scene/check.h"
#include "scene/keys.h"
#include "scene/values.h"

#include <errno.h>
#include <ini.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct parse_context {
    im_scene *scene;
    FILE *stream;
    int line;                      /* physical lines read so far, counted by read_line */
    int error_line;                /* the first line refused by read_line or handle_key, 0 if none */
    int key_line[SCENE_KEY_COUNT]; /* the line of each key of keys.h's table given, 0 if none */
    char sections[16][32];         /* the sections opened so far, to refuse one opened twice */
    int section_lines[16], section_count;
    char steps[INI_MAX_LINE];  /* [loading] steps as written (a line of inih's buffer fits) */
    char contents_section[32]; /* the section of the last key noted in the scene's contents */
} parse_context;

/* Stops parsing at the line being read with a message (im_fail); inih then sees the end of the file. */
static char *refuse_line(parse_context *context, const char *format, ...) __attribute__((format(printf, 2, 3)));
static char *refuse_line(parse_context *context, const char *format, ...)
{
    char message[512];
    va_list arguments;
    va_start(arguments, format);
    vsnprintf(message, sizeof message, format, arguments);
    va_end(arguments);
    im_fail(IM_EFORMAT, "%s", message);
    context->error_line = context->line + 1;
    return NULL;
}

/* 0 with the error recorded when the line opens a [section] opened before (inih would merge the
 * two silently, the later keys replacing the earlier); 1 otherwise. */
static int check_section_once(parse_context *context, const char *line)
{
    const char *open = line + strspn(line, " \t");
    const char *close = *open == '[' ? strchr(open, ']') : NULL;
    if (!close)
        return 1;
    char name[32];
    snprintf(name, sizeof name, "%.*s", (int)(close - open - 1), open + 1);
    for (int i = 0; i < context->section_count; ++i) {
        if (strcmp(context->sections[i], name) == 0) {
            --context->line; /* refuse_line names the line being read */
            refuse_line(context, "[%s] is opened twice (first on line %d): expected each section once", name,
                        context->section_lines[i]);
            return 0;
        }
    }
    if (context->section_count < (int)(sizeof context->sections / sizeof context->sections[0])) {
        snprintf(context->sections[context->section_count], sizeof context->sections[0], "%s", name);
        context->section_lines[context->section_count++] = context->line;
    }
    return 1;
}

/* inih's line reader: one physical line per call, counted so that errors know their line.
 * Debian's libinih hands it a fixed buffer of INI_MAX_LINE (200) bytes; fgets would cut a longer
 * line in two and inih would parse the tail as a line of its own, silently when it begins with a
 * blank (a continuation that replaces the value, e.g. half a `slopes` list). So a line that does
 * not fit, or a NUL byte (which would end the line early for inih), stops parsing with an error. */
static char *read_line(char *buffer, int size, void *user)
{
    parse_context *context = user;
    if (context->error_line)
        return NULL; /* the first error is reported; nothing after it matters */
    int length = 0, c;
    while ((c = getc(context->stream)) != EOF) {
        if (c == '\0')
            return refuse_line(context, "a NUL byte: expected a text file");
        if (c == '\n' && length == size - 1)
            break; /* the newline itself need not be kept */
        if (length == size - 1)
            return refuse_line(context,
                               "line longer than %d characters, the INI reader's limit "
                               "(for long lists of values use first:last:count)",
                               size - 1);
        buffer[length++] = (char)c;
        if (c == '\n')
            break;
    }
    if (length == 0)
        return NULL; /* end of file, or a read error that scene_load_file reports */
    buffer[length] = '\0';
    ++context->line;
    return check_section_once(context, buffer) ? buffer : NULL;
}

/* IM_EFORMAT for a key the table does not have, with the nearest key (or section) it has. */
static int unknown_name(const char *section, const char *name)
{
    if (!scene_section_exists(section)) {
        const char *suggestion = im_scene_suggest_key(NULL, section);
        return im_fail(IM_EFORMAT, "unknown section [%s]%s%s%s", section, suggestion ? "; did you mean [" : "",
                       suggestion ? suggestion : "", suggestion ? "]?" : "");
    }
    const char *suggestion = im_scene_suggest_key(section, name);
    return im_fail(IM_EFORMAT, "unknown key '%s' in [%s]%s%s%s", name, section, suggestion ? "; did you mean '" : "",
                   suggestion ? suggestion : "", suggestion ? "'?" : "");
}

/* Every key given fits in im_scene.contents: each once, its line within inih's buffer, and each
 * section's header once. */
_Static_assert(SCENE_KEY_COUNT *(INI_MAX_LINE + 4) + 16 * 32 < IM_SCENE_CONTENTS,
               "im_scene.contents holds every key a scene can give");

/* Appends a key accepted to the scene's contents, under its section's header when the section
 * changes (each section is opened once: check_section_once). */
static void note_contents(parse_context *context, const char *section, const char *name, const char *value)
{
    char *contents = context->scene->contents;
    size_t used = strlen(contents), size = sizeof context->scene->contents;
    if (strcmp(context->contents_section, section) != 0) {
        snprintf(context->contents_section, sizeof context->contents_section, "%s", section);
        used += (size_t)snprintf(contents + used, size - used, "[%s]\n", section);
    }
    snprintf(contents + used, size - used, "%s = %s\n", name, value);
}

/* Key index given on the current line: parsed by its entry of the table, once. */
static int parse_key(parse_context *context, int index, const char *value)
{
    const key_spec *spec = scene_key(index);
    if (context->key_line[index])
        return im_fail(IM_EFORMAT, "[%s] %s is given twice (first on line %d): expected each key once", spec->section,
                       spec->key, context->key_line[index]);
    context->key_line[index] = context->line;
    if (spec->parse == scene_parse_later)
        snprintf(context->steps, sizeof context->steps, "%s", value);
    return spec->parse(spec, value, context->scene);
}

/* inih calls this for every key; returning 0 stops parsing and makes ini_parse return the line. */
static int handle_key(void *user, const char *section, const char *name, const char *value)
{
    parse_context *context = user;
    if (context->error_line)
        return 0; /* keep the first error */
    int index = scene_key_index(section, name);
    int status = index < 0 ? unknown_name(section, name) : parse_key(context, index, value);
    if (status != IM_OK) {
        context->error_line = context->line;
        return 0;
    }
    note_contents(context, section, name, value);
    return 1;
}

/* A scene is a few kilobytes; a larger file is not one (and is not read whole). */
enum { SCENE_MAX_BYTES = 1 << 20 };

static int any_key_given(const parse_context *context)
{
    for (int i = 0; i < SCENE_KEY_COUNT; ++i)
        if (context->key_line[i])
            return 1;
    return 0;
}

/* The defaults, and what scene_complete fills unless the scene gives it. */
static void begin_scene(im_scene *scene, const char *path)
{
    scene_defaults(scene);
    snprintf(scene->path, sizeof scene->path, "%s", path);
    scene->surface.ny = -1;
    scene->surface.lambda_r = -1;
    scene->output_dir[0] = '\0';
    scene->tol = -1;
}

/* Parses an open scene into *scene (set up by its caller) and closes the stream. */
static int parse_stream(const char *path, FILE *stream, im_scene *scene)
{
    parse_context context = {.scene = scene, .stream = stream};
    int line = ini_parse_stream(read_line, &context, handle_key, &context);
    int read_failed = ferror(context.stream), read_errno = errno;
    fclose(context.stream);
    if (line == -2)
        return im_fail(IM_ENOMEM, "%s: out of memory while parsing", path);
    /* inih's own error (a malformed line) precedes any error of ours, else it is the same line */
    if (line > 0 && line != context.error_line)
        return im_fail(IM_EFORMAT, "%s:%d: malformed line: expected [section], key = value or a comment", path, line);
    if (context.error_line) /* its message is the last error */
        return im_fail_context(IM_EFORMAT, "%s:%d", path, context.error_line);
    if (read_failed)
        return im_fail(IM_EIO, "%s:%d: cannot read: %s", path, context.line + 1, strerror(read_errno));
    if (!any_key_given(&context))
        return im_fail(IM_EFORMAT,
                       "%s: no settings: a scene asks for its outputs with keys such as [output] "
                       "plots (see docs/scenes.md)",
                       path);
    scene_complete(scene, scene->tol != -1, scene->surface.ny != -1, scene->surface.lambda_r != -1,
                   scene->output_dir[0] != '\0');
    const scene_given given = {scene, context.key_line, context.steps};
    int inconsistent = scene_check_keys(&given);
    if (inconsistent)
        return im_fail_context(IM_EFORMAT, "%s:%d", path, inconsistent);
    return IM_OK;
}

int scene_load_file(const char *path, im_scene *scene)
{
    begin_scene(scene, path);
    FILE *stream;
    long long size;
    int opened = im_read_open(path, "r", IM_READ_REGULAR, &stream, &size);
    if (opened != IM_OK)
        return opened;
    if (size > SCENE_MAX_BYTES) {
        fclose(stream);
        return im_fail(IM_EINVAL, "%s: %lld bytes: expected a scene file of at most %d bytes", path, size,
                       SCENE_MAX_BYTES);
    }
    return parse_stream(path, stream, scene);
}

int scene_load_text(const char *text, const char *path, im_scene *scene)
{
    begin_scene(scene, path);
    FILE *stream = fmemopen((void *)text, strlen(text), "r");
    if (!stream)
        return im_fail(IM_ENOMEM, "%s: cannot read the scene's contents: %s", path, strerror(errno));
    return parse_stream(path, stream, scene);
}
