#include "indentmap/io.h"

#include "indentmap/status.h"
#include "io/payload.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

static const char GSF_MAGIC[] = "Gwyddion Simple Field 1.0\n";

int im_gsf_write(const char *path, const im_field *field)
{
    char header[512];
    int length = snprintf(header, sizeof header, "%sXRes = %d\nYRes = %d\nXReal = %.17g\nYReal = %.17g\n",
                          GSF_MAGIC, field->nx, field->ny, field->nx * field->delta,
                          field->ny * field->delta);
    if (field->unit[0])
        length += snprintf(header + length, sizeof header - (size_t)length,
                           "XYUnits = %s\nZUnits = %s\n", field->unit, field->unit);
    size_t padding = 4 - (size_t)length % 4; /* at least one NUL ends the header */
    im_atomic_file file;
    int status = im_atomic_open(&file, path);
    if (status != IM_OK)
        return status;
    int ok = fwrite(header, 1, (size_t)length, file.stream) == (size_t)length;
    for (size_t i = 0; ok && i < padding; ++i)
        ok = fputc('\0', file.stream) != EOF;
    size_t count = im_field_count(field);
    for (size_t i = 0; ok && i < count; ++i) {
        float value = (float)field->data[i];
        ok = fwrite(&value, sizeof value, 1, file.stream) == 1;
    }
    if (!ok) {
        im_atomic_abort(&file);
        return im_fail(IM_EIO, "%s: write failed: %s", path, strerror(errno));
    }
    return im_atomic_commit(&file);
}

typedef struct gsf_header {
    long xres, yres;
    double xreal;
    char unit[16];
} gsf_header;

static void parse_header_line(const char *line, gsf_header *h)
{
    char key[64], value[128];
    if (sscanf(line, " %63[^= ] = %127[^\n]", key, value) != 2)
        return;
    if (strcmp(key, "XRes") == 0)
        h->xres = strtol(value, NULL, 10);
    else if (strcmp(key, "YRes") == 0)
        h->yres = strtol(value, NULL, 10);
    else if (strcmp(key, "XReal") == 0)
        h->xreal = strtod(value, NULL);
    else if (strcmp(key, "XYUnits") == 0)
        snprintf(h->unit, sizeof h->unit, "%.15s", value);
}

/* Reads the text header up to its terminating NUL and skips the padding to a multiple of 4. */
static int read_header(FILE *stream, const char *path, gsf_header *h)
{
    char line[256];
    size_t offset = 0, used = 0;
    int c;
    if (fread(line, 1, sizeof GSF_MAGIC - 1, stream) != sizeof GSF_MAGIC - 1 ||
        memcmp(line, GSF_MAGIC, sizeof GSF_MAGIC - 1) != 0)
        return im_fail(IM_EFORMAT, "%s: not a Gwyddion Simple Field (no '%.25s' line)", path, GSF_MAGIC);
    offset = sizeof GSF_MAGIC - 1;
    while ((c = fgetc(stream)) != EOF && c != '\0') {
        ++offset;
        if (c == '\n' || used + 1 == sizeof line) {
            line[used] = '\0';
            parse_header_line(line, h);
            used = 0;
        } else {
            line[used++] = (char)c;
        }
        if (offset > 1 << 20)
            return im_fail(IM_EFORMAT, "%s: header has no terminating NUL in its first MiB", path);
    }
    if (c == EOF)
        return im_fail(IM_EFORMAT, "%s: truncated header (no NUL padding before the data)", path);
    ++offset;
    while (offset % 4 != 0 && (c = fgetc(stream)) == '\0')
        ++offset;
    if (offset % 4 != 0)
        return im_fail(IM_EFORMAT, "%s: header padding is not NUL bytes up to a multiple of 4", path);
    if (h->xres < 1 || h->yres < 1) /* the upper bound is im_io_check_grid's */
        return im_fail(IM_EFORMAT, "%s: XRes = %ld, YRes = %ld: expected both >= 1", path, h->xres, h->yres);
    return IM_OK;
}

static int read_values(FILE *stream, const char *path, im_field *field)
{
    size_t count = im_field_count(field), got = 0;
    float value;
    while (got < count && fread(&value, sizeof value, 1, stream) == 1)
        field->data[got++] = value;
    if (got != count)
        return im_fail(IM_EFORMAT, "%s: truncated data: %zu of %zu values (XRes %d x YRes %d)", path,
                       got, count, field->nx, field->ny);
    if (fgetc(stream) != EOF)
        return im_fail(IM_EFORMAT, "%s: more data than XRes x YRes = %d x %d holds", path,
                       field->nx, field->ny);
    return im_io_check_finite(field, path);
}

int im_gsf_read(const char *path, im_field **out)
{
    *out = NULL;
    FILE *stream;
    int opened = im_read_open(path, "rb", IM_READ_OR_PIPE, &stream, NULL);
    if (opened != IM_OK)
        return opened;
    gsf_header header = {0};
    im_field *field = NULL;
    int status = read_header(stream, path, &header);
    if (status == IM_OK) {
        char claim[64];
        snprintf(claim, sizeof claim, "XRes %ld x YRes %ld float32", header.xres, header.yres);
        status = im_io_check_grid(stream, path, header.xres, header.yres, 4u, claim);
    }
    if (status == IM_OK) {
        double delta = header.xreal > 0.0 ? header.xreal / (double)header.xres : 1.0;
        status = im_field_create((int)header.xres, (int)header.yres, delta, &field);
        if (status != IM_OK)
            im_fail_context(status, "%s", path);
    }
    if (status == IM_OK) {
        snprintf(field->unit, sizeof field->unit, "%s", header.xreal > 0.0 ? header.unit : "");
        status = read_values(stream, path, field);
    }
    fclose(stream);
    if (status != IM_OK) {
        im_field_free(field);
        return status;
    }
    *out = field;
    return IM_OK;
}
