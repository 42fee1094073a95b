/* Profile files (indenter.h's im_profile_read): a .npy height field for a 2-D profile, or an
 * (r, z) table, one sample per line, for an axisymmetric one. */
#include "indentmap/indenter.h"
#include "core/args.h"

#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/status.h"
#include "core/number.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define MAX_SAMPLES 10000000

typedef struct sample_table {
    double *r, *z;
    long *line; /* each sample's line in the file, for the messages */
    int count, capacity;
} sample_table;

static void table_free(sample_table *t)
{
    free(t->r);
    free(t->z);
    free(t->line);
}

static int table_push(sample_table *t, double r, double z, long line, const char *path)
{
    if (t->count == t->capacity) {
        if (t->capacity >= MAX_SAMPLES)
            return im_fail(IM_EINVAL, "%s:%ld: more than %d samples", path, line, MAX_SAMPLES);
        int capacity = t->capacity ? 2 * t->capacity : 64;
        double *nr = realloc(t->r, sizeof(double) * (size_t)capacity);
        if (nr)
            t->r = nr;
        double *nz = nr ? realloc(t->z, sizeof(double) * (size_t)capacity) : NULL;
        if (nz)
            t->z = nz;
        long *nl = nz ? realloc(t->line, sizeof(long) * (size_t)capacity) : NULL;
        if (!nl)
            return im_fail(IM_ENOMEM, "%s: %d profile samples", path, capacity);
        t->line = nl;
        t->capacity = capacity;
    }
    t->r[t->count] = r;
    t->z[t->count] = z;
    t->line[t->count++] = line;
    return IM_OK;
}

static const char *skip_blanks(const char *s)
{
    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')
        ++s;
    return s;
}

/* "r z", "r,z" or "r, z": 1 when two numbers and nothing else; 0 otherwise. */
static int parse_pair(const char *text, double *r, double *z)
{
    char *end;
    errno = 0;
    *r = number_parse(text, &end);
    if (end == text)
        return 0;
    const char *s = skip_blanks(end);
    if (*s == ',')
        s = skip_blanks(s + 1);
    else if (s == end)
        return 0;
    const char *start = s;
    *z = number_parse(start, &end);
    return end != start && *skip_blanks(end) == '\0';
}

/* A line without a digit (a header such as "r,z"). */
static int holds_no_number(const char *text)
{
    for (; *text; ++text)
        if (isdigit((unsigned char)*text))
            return 0;
    return 1;
}

static int read_table(FILE *file, const char *path, sample_table *t)
{
    char buffer[4096];
    long line = 0;
    int status = IM_OK, seen_content = 0;
    while (status == IM_OK && fgets(buffer, sizeof buffer, file)) {
        ++line;
        if (!strchr(buffer, '\n') && !feof(file))
            return im_fail(IM_EINVAL, "%s:%ld: line longer than %zu characters: expected 'r z' or 'r,z'", path, line,
                           sizeof buffer - 2);
        const char *s = skip_blanks(buffer);
        if (*s == '\0' || *s == '#')
            continue;
        double r, z;
        if (parse_pair(s, &r, &z))
            status = table_push(t, r, z, line, path);
        else if (!seen_content && holds_no_number(s))
            ; /* a header line */
        else
            status = im_fail(IM_EINVAL, "%s:%ld: '%.*s': expected two numbers 'r z' or 'r,z' (a profile sample)",
                             path, line, (int)strcspn(s, "\r\n"), s);
        seen_content = 1;
    }
    if (status == IM_OK && ferror(file))
        status = im_fail(IM_EIO, "%s: read error: %s", path, strerror(errno));
    return status;
}

/* The table's samples as a profile; a refusal names the file and the sample's line. */
static int table_profile(const sample_table *t, const char *path, im_profile **out)
{
    if (t->count == 0)
        return im_fail(IM_EINVAL, "%s: no profile sample: expected at least 3 lines 'r z' or 'r,z'", path);
    int status = im_profile_axisymmetric(t->r, t->z, t->count, out);
    if (status != IM_OK) {
        const char *message = im_last_error();
        int sample = -1;
        if (sscanf(message, "profile sample %d", &sample) == 1 && sample >= 0 && sample < t->count)
            im_fail_context(status, "%s:%ld", path, t->line[sample]);
        else
            im_fail_context(status, "%s", path);
    }
    return status;
}

static int read_field_profile(const char *path, double delta, im_profile **out)
{
    im_field *field = NULL;
    int status = im_npy_read(path, &field);
    if (status == IM_OK) {
        field->delta = delta;
        status = im_profile_field(field, out);
        if (status != IM_OK)
            im_fail_context(status, "%s", path);
    }
    im_field_free(field);
    return status;
}

int im_profile_read(const char *path, double delta, im_profile **out)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(out, "out");
    *out = NULL;
    size_t length = path ? strlen(path) : 0;
    if (!path)
        return im_fail(IM_EINVAL, "profile file: NULL path");
    if (length >= 4 && strcasecmp(path + length - 4, ".npy") == 0)
        return read_field_profile(path, delta, out);
    FILE *file = fopen(path, "r");
    if (!file)
        return im_fail(IM_EIO, "%s: cannot open the profile: %s", path, strerror(errno));
    sample_table t = {0};
    int status = read_table(file, path, &t);
    fclose(file);
    if (status == IM_OK)
        status = table_profile(&t, path, out);
    table_free(&t);
    return status;
}
