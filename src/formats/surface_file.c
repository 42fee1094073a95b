#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "formats/payload.h"
#include "formats/gwyddion.h"
#include "formats/readers.h"
#include "formats/spreadsheet.h"
#include "formats/text_columns.h"

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

enum file_kind { TEXT_OF_NUMBERS, OTHER_TEXT, UTF16_TEXT, GZIP, BINARY };

/* What a file looks like from its first 64 KiB: text whose first data line (after '#' comments, blank
 * lines and key=value headers) starts with a number or a column named x (a header row of x y z points),
 * as the text reader needs; other text (a vendor's
 * header, column names), whose first data line goes into first_line; UTF-16 text (by its byte-order
 * mark, as spreadsheet programs save "Unicode text", decoded by the text reader); gzip-compressed (text,
 * decompressed by the text reader); or binary (a NUL byte). A pipe
 * is taken as text of numbers: it cannot be looked at twice. */
static int look_at(const char *path, enum file_kind *kind, char *first_line, size_t size)
{
    *kind = TEXT_OF_NUMBERS; /* unless seen otherwise: the text reader names what is wrong */
    struct stat about;
    FILE *stream = stat(path, &about) == 0 && S_ISREG(about.st_mode) ? fopen(path, "rb") : NULL;
    if (!stream)
        return IM_OK;
    static const size_t LOOKED_AT = 65536;
    char *head = malloc(LOOKED_AT + 1);
    size_t length = head ? fread(head, 1, LOOKED_AT, stream) : 0;
    fclose(stream);
    if (!head)
        return im_fail(IM_ENOMEM, "%s: allocation of %zu bytes to look at it failed", path, LOOKED_AT + 1);
    head[length] = '\0';
    int utf16 = length >= 2 && ((head[0] == '\xff' && head[1] == '\xfe') || (head[0] == '\xfe' && head[1] == '\xff'));
    int gzip = length >= 2 && head[0] == '\x1f' && head[1] == '\x8b';
    *kind = utf16 ? UTF16_TEXT : gzip ? GZIP : memchr(head, '\0', length) ? BINARY : TEXT_OF_NUMBERS;
    for (char *line = head; *kind == TEXT_OF_NUMBERS && line < head + length; line += strcspn(line, "\n") + 1) {
        line += strspn(line, " \t\r\xef\xbb\xbf");
        if (*line == '\n' || *line == '#' || (isalpha((unsigned char)*line) && line[strcspn(line, "=\n")] == '='))
            continue;
        if (*line && !strchr("0123456789+-.", *line) && strncasecmp(line, "nan", 3) != 0 &&
            !text_columns_names_x_first(line)) {
            *kind = OTHER_TEXT;
            snprintf(first_line, size, "%.*s", (int)strcspn(line, "\r\n"), line);
        }
        break;
    }
    free(head);
    return IM_OK;
}

static surface_raw_reader reader_by_extension(const char *path)
{
    return has_extension(path, ".npy")   ? npy_read_raw
           : has_extension(path, ".gsf") ? gsf_read_raw
           : has_extension(path, ".sdf") ? sdf_read_raw
           : has_extension(path, ".nc")  ? netcdf_read_raw
           : has_extension(path, ".x3p") ? x3p_read_raw
           : has_extension(path, ".tmd") ? tmd_read_raw
                                         : NULL;
}

/* 1 when the file's first 8 bytes are signature. */
static int starts_with(const char *path, const unsigned char signature[8])
{
    unsigned char head[8];
    struct stat about;
    FILE *stream = stat(path, &about) == 0 && S_ISREG(about.st_mode) ? fopen(path, "rb") : NULL;
    size_t got = stream ? fread(head, 1, sizeof head, stream) : 0;
    if (stream)
        fclose(stream);
    return got == sizeof head && memcmp(head, signature, sizeof head) == 0;
}

static const unsigned char HDF5_SIGNATURE[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
static const unsigned char OLE2_SIGNATURE[8] = {0xd0, 0xcf, 0x11, 0xe0, 0xa1, 0xb1, 0x1a, 0xe1};

/* Readers of several channels that indentmap has itself: HDF5 (by extension or signature; after the
 * extensions above, since a NetCDF-4 .nc is HDF5 too) and contact.engineering containers (.zip). */
static surface_channel_reader channel_reader_for(const char *path)
{
    if (has_extension(path, ".h5") || has_extension(path, ".hdf5") || starts_with(path, HDF5_SIGNATURE))
        return hdf5_read_raw;
    return has_extension(path, ".zip") ? container_read_raw : NULL;
}

int surface_read_channel_format(const char *path, surface_channel_reader read, const im_surface_read_options *options,
                                im_field **out, im_surface_read_info *info)
{
    surface_stated stated;
    im_field *field = NULL;
    int status = read(path, options, &field, &stated);
    if (status == IM_OK)
        status = surface_finish(path, field, &stated, options, info);
    if (status != IM_OK)
        im_field_free(field);
    *out = status == IM_OK ? field : NULL;
    return status;
}

/* Text that is not numbers and that no Gwyddion module reads: say what it is, not only that no module
 * reads it (a table with a header row of column names, a profiler's text export of a line scan), and
 * the text reader's refusal, which names the line and what it expected there. */
static int refuse_other_text(const char *path, const char *first_line, const im_surface_read_options *options)
{
    char shown[48];
    size_t used = 0;
    for (size_t i = 0; first_line[i] && used + 1 < sizeof shown; ++i)
        shown[used++] = (unsigned char)first_line[i] < 0x20 ? '?' : first_line[i];
    shown[used] = '\0';
    im_field *field = NULL;
    int status = surface_read_format(path, text_read_raw, options, &field, NULL);
    im_field_free(field);
    if (status == IM_OK) /* cannot be: the text reader reads only lines that begin with a number or an x */
        return im_fail(IM_EFORMAT, "%s: text whose first data line, '%s', is not numbers", path, shown);
    char text_refusal[512];
    snprintf(text_refusal, sizeof text_refusal, "%s", im_last_error());
    return im_fail(IM_EFORMAT,
                   "%s: text whose first data line, '%s', is not numbers (column names, or a "
                   "vendor's text export), and no Gwyddion file module reads it: expected a matrix of heights, or "
                   "x y z points under a header row naming x, y and a height; as text: %s",
                   path, shown, text_refusal);
}

/* 1 when the text reader refuses the file as a line scan (its refusal then stands): text whose first
 * line is not numbers is judged by the text above its numbers before any Gwyddion module is tried. */
static int refused_as_line_scan(const char *path, const im_surface_read_options *options)
{
    im_field *field = NULL;
    int status = surface_read_format(path, text_read_raw, options, &field, NULL);
    im_field_free(field);
    return status == IM_EFORMAT && strstr(im_last_error(), LINE_SCAN_REFUSAL);
}

/* 1 (after saying why) when a channel is asked of a file indentmap's own readers read: they hold one. */
static int refuse_channel(const char *path, const im_surface_read_options *options)
{
    if (!options || !options->channel[0])
        return 0;
    im_fail(IM_EINVAL,
            "%s: channel '%.63s' asked of a file read by indentmap's own reader, which holds one channel "
            "(channels are chosen in instrument files read through Gwyddion's modules)",
            path, options->channel);
    return 1;
}

/* A binary file no Gwyddion module reads: the text reader's refusal names the first NUL byte (a text
 * file with a stray one is told where it is), and the message says that no module reads it either. */
static int refuse_binary(const char *path, const im_surface_read_options *options)
{
    if (starts_with(path, OLE2_SIGNATURE))
        return im_fail(IM_EFORMAT,
                       "%s: an OLE2 (Microsoft compound) document, as Digital Surf's Mountains documents "
                       "(.mnt) and spreadsheets (.xls) are, which no reader here opens: export the studiable from "
                       "MountainsMap as .sur (read through Gwyddion's modules) or the heights as text",
                       path);
    im_field *field = NULL;
    int status = surface_read_format(path, text_read_raw, options, &field, NULL);
    im_field_free(field);
    if (status == IM_OK) /* cannot be: the file holds a NUL byte the text reader refuses */
        return im_fail(IM_EFORMAT, "%s: no Gwyddion file module reads it", path);
    char text_refusal[512];
    snprintf(text_refusal, sizeof text_refusal, "%s", im_last_error());
    return im_fail(status,
                   "%s: a binary file no reader here opens: none of Gwyddion's file modules reads it "
                   "('indentmap formats' lists those that do), and as text: %s",
                   path, text_refusal);
}

int im_surface_read_with(const char *path, const im_surface_read_options *options, im_field **out,
                         im_surface_read_info *info)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(out, "out");
    *out = NULL;
    if (options && (unsigned)options->npy_order > IM_NPY_ORDER_XY)
        return im_fail(IM_EINVAL,
                       "%s: options->npy_order = %d: expected IM_NPY_ORDER_SIDECAR, IM_NPY_ORDER_YX or "
                       "IM_NPY_ORDER_XY",
                       __func__, (int)options->npy_order);
    surface_raw_reader read = reader_by_extension(path);
    if (read)
        return refuse_channel(path, options) ? IM_EINVAL : surface_read_format(path, read, options, out, info);
    surface_channel_reader read_channels = channel_reader_for(path);
    if (read_channels)
        return surface_read_channel_format(path, read_channels, options, out, info);
    char first_line[48] = "";
    enum file_kind kind;
    int looked = look_at(path, &kind, first_line, sizeof first_line);
    if (looked != IM_OK)
        return looked;
    if (kind == BINARY && spreadsheet_is_one(path))
        return spreadsheet_refuse(path);
    if (kind == TEXT_OF_NUMBERS || kind == GZIP || kind == UTF16_TEXT || !im_gwyddion_reader())
        return refuse_channel(path, options) ? IM_EINVAL
                                             : surface_read_format(path, text_read_raw, options, out, info);
    if (kind == OTHER_TEXT && refused_as_line_scan(path, options))
        return IM_EFORMAT;
    int status = surface_read_channel_format(path, gwyddion_read_raw, options, out, info);
    if (status != IM_EFORMAT || !strstr(im_last_error(), GWYDDION_UNKNOWN_FORMAT))
        return status;
    return kind == OTHER_TEXT ? refuse_other_text(path, first_line, options) : refuse_binary(path, options);
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
        int writable = formats_check_heights_or_missing_writable(field, path);
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

/* The pair's second file: the surface's record, or a .npy's units. */
static int write_sidecar(const char *path, const char *sidecar, const im_field *surface,
                         const im_surface_params *params, const char *source, const im_surface_stats *stats)
{
    if (!params && !source && !stats)
        return im_field_sidecar_write(path, surface, "height");
    im_surface_stats computed;
    int status = stats ? IM_OK : im_surface_statistics(surface, &computed);
    return status == IM_OK ? im_surface_sidecar_write(sidecar, surface, params, source, stats ? stats : &computed)
                           : status;
}

int im_surface_write_with_sidecar(const char *path, const im_field *surface, const im_surface_params *params,
                                  const char *source, const im_surface_stats *stats)
{
    ARG_REQUIRE(path, "path");
    ARG_VIEW(surface, "surface");
    if (!params && !source && !stats && !has_extension(path, ".npy"))
        return im_surface_write(path, surface);
    char sidecar[4096];
    int status = im_path_suffix(sidecar, sizeof sidecar, path, ".json");
    if (status != IM_OK)
        return status;
    int pair_lock = im_pair_writers_lock(path);
    if (pair_lock < 0)
        return IM_EIO;
    status = im_surface_write(path, surface);
    if (status == IM_OK)
        status = write_sidecar(path, sidecar, surface, params, source, stats);
    im_pair_writers_unlock(pair_lock);
    return status;
}
