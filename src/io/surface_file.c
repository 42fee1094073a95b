#include "indentmap/io.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "io/payload.h"
#include "io/gwyddion.h"
#include "io/readers.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

static int has_extension(const char *path, const char *extension)
{
    size_t n = strlen(path), e = strlen(extension);
    return n > e && strcmp(path + n - e, extension) == 0;
}

/* 1 when the file is text whose first data line (after '#' comments, blank lines and key=value
 * headers) starts with a number, as the text reader needs; 0 for a binary file (a NUL byte in its
 * first 64 KiB) or text of another kind (a vendor's header). A pipe is taken as text: it cannot be
 * looked at twice. */
static int holds_text_numbers(const char *path)
{
    struct stat about;
    FILE *stream = stat(path, &about) == 0 && S_ISREG(about.st_mode) ? fopen(path, "rb") : NULL;
    if (!stream)
        return 1; /* the text reader names what is wrong with it */
    static const size_t LOOKED_AT = 65536;
    char *head = malloc(LOOKED_AT + 1);
    size_t length = head ? fread(head, 1, LOOKED_AT, stream) : 0;
    fclose(stream);
    if (!head)
        return 1;
    head[length] = '\0';
    int text = memchr(head, '\0', length) == NULL;
    for (char *line = head; text && line < head + length; line += strcspn(line, "\n") + 1) {
        line += strspn(line, " \t\r\xef\xbb\xbf");
        if (*line == '\n' || *line == '#' || (isalpha((unsigned char)*line) && line[strcspn(line, "=\n")] == '='))
            continue;
        text = strchr("0123456789+-.", *line) != NULL || strncasecmp(line, "nan", 3) == 0;
        break;
    }
    free(head);
    return text;
}

static surface_raw_reader reader_by_extension(const char *path)
{
    return has_extension(path, ".npy")   ? npy_read_raw
           : has_extension(path, ".gsf") ? gsf_read_raw
           : has_extension(path, ".sdf") ? sdf_read_raw
           : has_extension(path, ".nc")  ? netcdf_read_raw
           : has_extension(path, ".x3p") ? x3p_read_raw
                                         : NULL;
}

static int read_through_gwyddion(const char *path, const im_surface_read_options *options, im_field **out,
                                 im_surface_read_info *info)
{
    surface_stated stated;
    im_field *field = NULL;
    int status = gwyddion_read_raw(path, options ? options->channel : "", &field, &stated);
    if (status == IM_OK)
        status = surface_finish(path, field, &stated, options, info);
    if (status != IM_OK)
        im_field_free(field);
    *out = status == IM_OK ? field : NULL;
    return status;
}

int im_surface_read_with(const char *path, const im_surface_read_options *options, im_field **out,
                         im_surface_read_info *info)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(out, "out");
    *out = NULL;
    surface_raw_reader read = reader_by_extension(path);
    if (!read && im_gwyddion_reader() && !holds_text_numbers(path))
        return read_through_gwyddion(path, options, out, info);
    return surface_read_format(path, read ? read : text_read_raw, options, out, info);
}

int im_surface_read(const char *path, im_field **out)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(out, "out");
    return im_surface_read_with(path, NULL, out, NULL);
}

int im_surface_write(const char *path, const im_field *field)
{
    ARG_REQUIRE(path, "path");
    ARG_VIEW(field, "field");
    if (has_extension(path, ".npy")) { /* .npy holds any field; as a surface it must be one */
        int writable = io_check_heights_writable(field, path);
        return writable == IM_OK ? im_npy_write(path, field, IM_NPY_FLOAT64) : writable;
    }
    if (has_extension(path, ".gsf"))
        return im_gsf_write(path, field);
    if (has_extension(path, ".sdf"))
        return im_sdf_write(path, field);
    if (has_extension(path, ".nc"))
        return im_netcdf_write(path, field);
    if (has_extension(path, ".x3p"))
        return im_x3p_write(path, field);
    return im_text_write(path, field);
}
