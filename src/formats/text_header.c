#include "formats/text_header.h"

#include "indentmap/status.h"
#include "core/number.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The text after "# KEY" (blanks skipped), or NULL when the header line is not about KEY. */
static const char *comment_value(const char *line, const char *key)
{
    const char *at = line + 1 + strspn(line + 1, " \t");
    size_t length = strlen(key);
    return strncmp(at, key, length) == 0 ? at + length + strspn(at + length, " \t") : NULL;
}

/* Half a unit of the last digit printed in the number text .. end, relative to its value number > 0:
 * how far the printed digits leave the value open ("87.6": 0.05 / 87.6, "1.250e-6": 0.0005 / 1.25). */
static double printed_rounding(const char *text, const char *end, double number)
{
    const char *point = NULL, *exponent = end;
    for (const char *c = text; c < end; ++c) {
        if (*c == '.')
            point = c;
        else if (*c == 'e' || *c == 'E') {
            exponent = c;
            break;
        }
    }
    long decimals = point ? (long)(exponent - point - 1) : 0;
    long power = exponent < end ? strtol(exponent + 1, NULL, 10) : 0;
    return 0.5 * pow(10.0, (double)(power - decimals)) / number;
}

/* A length > 0 followed by an optional unit, as Gwyddion's extents and Vision's pixel size state it;
 * rounding (unless NULL): what its printed digits leave open (printed_rounding). */
static int parse_length(const char *path, long line_number, const char *key, const char *value, double *length,
                        double *rounding, char *unit, size_t unit_size)
{
    char *end;
    double number = number_parse(value, &end);
    char unit_text[64] = "";
    int words = sscanf(end, "%63s", unit_text);
    if (end == value || !isfinite(number) || !(number > 0.0) || strlen(unit_text) >= unit_size)
        return im_fail(IM_EFORMAT, "%s:%ld: %s '%.40s': expected a finite length > 0 and a unit", path, line_number,
                       key, value);
    *length = number;
    if (rounding)
        *rounding = printed_rounding(value, end, number);
    snprintf(unit, unit_size, "%s", words == 1 ? unit_text : "");
    return IM_OK;
}

/* One extent of a Gwyddion export under any of its spellings (English, German). */
static int parse_extent(const char *path, long line_number, const char *line, const char *const keys[2],
                        double *extent, double *rounding, char *unit, size_t unit_size)
{
    for (int k = 0; k < 2; ++k) {
        const char *value = comment_value(line, keys[k]);
        if (value)
            return parse_length(path, line_number, keys[k], value, extent, rounding, unit, unit_size);
    }
    return IM_OK;
}

/* One unit name after a key, e.g. Gwyddion's "# Value units: m". */
static int parse_unit(const char *path, long line_number, const char *key, const char *value, char *unit,
                      size_t unit_size)
{
    char text[64] = "";
    if (sscanf(value, "%63s", text) != 1 || strlen(text) >= unit_size)
        return im_fail(IM_EFORMAT, "%s:%ld: %s '%.40s': expected one unit name", path, line_number, key, value);
    memcpy(unit, text, unit_size);
    return IM_OK;
}

/* A line stating the grid, "... 16 columns x 16 rows ..." (as im_text_write writes it). */
static void parse_shape_comment(const char *line, long line_number, text_header *header)
{
    const char *at = strstr(line, " columns x ");
    if (!at || header->line)
        return;
    const char *start = at;
    while (start > line && start[-1] >= '0' && start[-1] <= '9')
        --start;
    long columns, rows;
    if (start < at && sscanf(start, "%ld columns x %ld rows", &columns, &rows) == 2) {
        header->columns = columns;
        header->rows = rows;
        header->line = line_number;
    }
}

int text_header_parse_comment(const char *path, long line_number, const char *line, text_header *header)
{
    static const char *const WIDTH[2] = {"Width:", "Breite:"}, *const HEIGHT[2] = {"Height:", "H\u00f6he:"};
    parse_shape_comment(line, line_number, header);
    int status = parse_extent(path, line_number, line, WIDTH, &header->width, &header->width_rounding,
                              header->width_unit, sizeof header->width_unit);
    if (status == IM_OK)
        status = parse_extent(path, line_number, line, HEIGHT, &header->height, &header->height_rounding,
                              header->height_unit, sizeof header->height_unit);
    const char *value = comment_value(line, "Value units:");
    if (status == IM_OK && value)
        status = parse_unit(path, line_number, "Value units", value, header->value_unit, sizeof header->value_unit);
    return status;
}

int text_header_is_vision_line(const char *line)
{
    return isalpha((unsigned char)line[0]) && strchr(line, '=') != NULL;
}

/* The text after "KEY=" at the start of line, or NULL. */
static const char *vision_value(const char *line, const char *key)
{
    size_t length = strlen(key);
    return strncmp(line, key, length) == 0 && line[length] == '=' ? line + length + 1 : NULL;
}

static int parse_vision_grid(const char *path, long line_number, const char *line, text_header *header)
{
    long rows, columns;
    char end;
    if (sscanf(line, "h=%ld w=%ld %c", &rows, &columns, &end) != 2 || rows < 1 || columns < 1)
        return im_fail(IM_EFORMAT, "%s:%ld: '%.40s': expected 'h=ROWS w=COLUMNS'", path, line_number, line);
    header->rows = rows;
    header->columns = columns;
    header->line = line_number;
    return IM_OK;
}

static int parse_vision_factor(const char *path, long line_number, const char *value, text_header *header)
{
    char *end;
    double factor = number_parse(value, &end);
    if (end == value || !isfinite(factor) || factor == 0.0 || end[strspn(end, " \t\r\n")])
        return im_fail(IM_EFORMAT,
                       "%s:%ld: height conversion factor (-> m) '%.40s': expected a finite number "
                       "other than 0",
                       path, line_number, value);
    header->height_factor = factor;
    return IM_OK;
}

int text_header_parse_vision(const char *path, long line_number, const char *line, text_header *header)
{
    const char *value;
    if (vision_value(line, "h"))
        return parse_vision_grid(path, line_number, line, header);
    if ((value = vision_value(line, "pixel size")))
        return parse_length(path, line_number, "pixel size", value, &header->pixel_size, NULL, header->pixel_unit,
                            sizeof header->pixel_unit);
    if ((value = vision_value(line, "data unit")))
        return parse_unit(path, line_number, "data unit", value, header->data_unit, sizeof header->data_unit);
    if ((value = vision_value(line, "height conversion factor (-> m)")))
        return parse_vision_factor(path, line_number, value, header);
    return im_fail(IM_EFORMAT,
                   "%s:%ld: '%.40s': a header line of a kind this reader does not know (Wyko/Vision "
                   "ASCII: h= w=, pixel size=, data unit=, height conversion factor (-> m)=); expected numbers",
                   path, line_number, line);
}

int text_header_check_shape(const char *path, const text_header *header, long columns, long rows)
{
    if (!header->line || (header->columns == columns && header->rows == rows))
        return IM_OK;
    return im_fail(IM_EFORMAT,
                   "%s:%ld: the header states %ld columns x %ld rows, but the file has %ld "
                   "columns x %ld rows of data (%s)",
                   path, header->line, header->columns, header->rows, columns, rows,
                   rows < header->rows ? "rows are missing: truncated?" : "the size disagrees");
}

int text_header_states_a_matrix(const text_header *header)
{
    return header->width > 0.0 || header->height > 0.0 || header->line || header->pixel_size > 0.0;
}

/* Gwyddion's Height in the unit of its Width (a German export wrote "12.34 µm" and "5678.9 nm"). */
static int height_in_width_unit(const char *path, const text_header *header, double *height)
{
    *height = header->height;
    if (!(header->width > 0.0 && header->height > 0.0) || strcmp(header->width_unit, header->height_unit) == 0)
        return IM_OK;
    double width_metres = im_length_unit_metres(header->width_unit, NULL);
    double height_metres = im_length_unit_metres(header->height_unit, NULL);
    if (width_metres == 0.0 || height_metres == 0.0)
        return im_fail(IM_EFORMAT,
                       "%s: Width is in '%s' but Height in '%s': expected two length units (m, mm, "
                       "\u00b5m or um, nm, ...) or one unit",
                       path, header->width_unit, header->height_unit);
    *height = header->height * height_metres / width_metres;
    return IM_OK;
}

static int gwyddion_units(const char *path, const text_header *header, long columns, long rows,
                          surface_stated *stated)
{
    double height;
    int status = height_in_width_unit(path, header, &height);
    if (status != IM_OK)
        return status;
    if (header->width > 0.0 || height > 0.0) { /* one extent alone states square pixels */
        stated->units.delta_y = height > 0.0 ? height / (double)rows : 0.0;
        stated->units.delta_x = header->width > 0.0 ? header->width / (double)columns : stated->units.delta_y;
        memcpy(stated->units.lateral, header->width > 0.0 ? header->width_unit : header->height_unit,
               sizeof stated->units.lateral);
        if (header->width > 0.0 && height > 0.0) /* the ratio of the spacings is open by both roundings */
            stated->spacing_rounding = header->width_rounding + header->height_rounding;
    }
    memcpy(stated->units.height, header->value_unit, sizeof stated->units.height);
    stated->unstated_height = "no '# Value units:' line"; /* Gwyddion states it: a line cut, or a hand edit */
    return IM_OK;
}

/* Vision's values are in data unit; the conversion factor turns them into metres (a phase in rad
 * times the wavelength's share). Without a factor the data unit must itself be a length. */
static int vision_units(const char *path, const text_header *header, surface_stated *stated, double *value_factor)
{
    *stated = (surface_stated){.spacing_keys = "pixel size",
                               .lateral_key = "pixel size",
                               .height_key = header->height_factor != 0.0 ? "height conversion factor (-> m)"
                                                                          : "data unit"};
    stated->units.delta_x = stated->units.delta_y = header->pixel_size;
    memcpy(stated->units.lateral, header->pixel_unit, sizeof stated->units.lateral);
    if (header->height_factor != 0.0) {
        *value_factor = header->height_factor;
        snprintf(stated->units.height, sizeof stated->units.height, "m");
        snprintf(stated->conversion, sizeof stated->conversion,
                 "values in '%s' times the height conversion factor %.9g (-> m)", header->data_unit,
                 header->height_factor);
        return IM_OK;
    }
    if (header->data_unit[0] && im_length_unit_metres(header->data_unit, NULL) == 0.0)
        return im_fail(IM_EFORMAT,
                       "%s: data unit = '%s' is not a length and no 'height conversion factor (-> m)' "
                       "converts it: expected heights",
                       path, header->data_unit);
    memcpy(stated->units.height, header->data_unit, sizeof stated->units.height);
    return IM_OK;
}

int text_header_stated_units(const char *path, const text_header *header, long columns, long rows,
                             surface_stated *stated, double *value_factor)
{
    *value_factor = 1.0;
    if (header->pixel_size > 0.0 || header->height_factor != 0.0 || header->data_unit[0])
        return vision_units(path, header, stated, value_factor);
    *stated = (surface_stated){.spacing_keys = "Width / columns and Height / rows",
                               .lateral_key = "Width",
                               .height_key = "Value units"};
    return gwyddion_units(path, header, columns, rows, stated);
}
