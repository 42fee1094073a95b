/* Length units of surface files, and the step every reader ends with: applying them. */
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "indentmap/surface.h"
#include "formats/payload.h"
#include "formats/readers.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct length_unit {
    const char *name, *canonical;
    double metres;
} length_unit;

/* Spellings met in Gwyddion, profilometer and AFM exports; "µ" is U+00B5, "μ" U+03BC, "Å" U+00C5
 * and U+212B (the Angstrom sign). */
static const length_unit LENGTH_UNITS[] = {{"m", "m", 1.0},
                                           {"cm", "cm", 1e-2},
                                           {"mm", "mm", 1e-3},
                                           {"\u00b5m", "\u00b5m", 1e-6},
                                           {"\u03bcm", "\u00b5m", 1e-6},
                                           {"um", "\u00b5m", 1e-6},
                                           {"micron", "\u00b5m", 1e-6},
                                           {"nm", "nm", 1e-9},
                                           {"pm", "pm", 1e-12},
                                           {"\u00c5", "\u00c5", 1e-10},
                                           {"\u212b", "\u00c5", 1e-10},
                                           {"A", "\u00c5", 1e-10},
                                           {"angstrom", "\u00c5", 1e-10}};

double im_length_unit_metres(const char *name, const char **canonical)
{
    ARG_REQUIRE_OR(name, "name", 0.0);
    for (size_t i = 0; i < sizeof LENGTH_UNITS / sizeof *LENGTH_UNITS; ++i) {
        if (strcmp(name, LENGTH_UNITS[i].name) == 0) {
            if (canonical)
                *canonical = LENGTH_UNITS[i].canonical;
            return LENGTH_UNITS[i].metres;
        }
    }
    return 0.0;
}

/* 1 when --unit (options->set.lateral) is to convert the surface into that unit rather than name its
 * unit: the file states a length unit and --delta does not restate the spacing. Relabelling would
 * keep the spacing's number and change what it means (a 78.125 nm spacing read as 7.8125e-08 nm). */
static int unit_converts(const surface_stated *stated, const im_surface_read_options *options)
{
    return options && options->set.lateral[0] && !(options->set.delta_x > 0.0) &&
           im_length_unit_metres(stated->units.lateral, NULL) > 0.0;
}

/* The unit the surface is converted into: express_in, else --unit on a file stating its own; "": none. */
static const char *conversion_target(const surface_stated *stated, const im_surface_read_options *options)
{
    if (options && options->express_in[0])
        return options->express_in;
    return unit_converts(stated, options) ? options->set.lateral : "";
}

/* The file's units with the user's overrides applied, and the keys (or options) behind each. */
static surface_stated merge_overrides(const surface_stated *stated, const im_surface_read_options *options)
{
    surface_stated merged = *stated;
    const im_surface_units *set = options ? &options->set : NULL;
    if (set && set->delta_x > 0.0) {
        merged.units.delta_x = set->delta_x;
        merged.units.delta_y = set->delta_y > 0.0 ? set->delta_y : set->delta_x;
        merged.spacing_keys = "--delta";
        merged.spacing_rounding = 0.0; /* set exactly */
    }
    if (set && set->lateral[0] && !unit_converts(stated, options)) {
        memcpy(merged.units.lateral, set->lateral, sizeof merged.units.lateral);
        merged.lateral_key = "--unit";
    }
    if (set && set->height[0]) {
        memcpy(merged.units.height, set->height, sizeof merged.units.height);
        merged.height_key = "--height-unit";
    }
    if (merged.units.delta_x > 0.0 && !(merged.units.delta_y > 0.0))
        merged.units.delta_y = merged.units.delta_x; /* a file stating one extent: square pixels */
    return merged;
}

/* |delta_x - delta_y| / their mean; 0 when no spacing is stated. */
static double spacing_difference(const im_surface_units *u)
{
    return u->delta_x > 0.0 ? fabs(u->delta_x - u->delta_y) / (0.5 * (u->delta_x + u->delta_y)) : 0.0;
}

/* The difference up to which pixels are square (formats.h, IM_SQUARE_PIXEL_TOLERANCE). */
static double square_tolerance(const surface_stated *s)
{
    return fmax(IM_SQUARE_PIXEL_TOLERANCE, fmin(s->spacing_rounding, IM_SQUARE_PIXEL_PRINTED_LIMIT));
}

/* Pixels square within tolerance (difference: spacing_difference), or to be resampled; otherwise refused. */
static int check_square_pixels(const char *path, const surface_stated *s, double difference, double tolerance,
                               int resample)
{
    if (difference <= tolerance || resample)
        return IM_OK;
    const char *unit = s->units.lateral;
    return im_fail(IM_EFORMAT,
                   "%s: %s: non-square pixels, x spacing %.9g and y spacing %.9g%s%s differ by %.3g "
                   "of their mean, beyond the %.3g %s that rounding explains: resample them onto square pixels "
                   "(--resample-square; resample_square = yes in a scene, resample_square=True in Python)",
                   path, s->spacing_keys, s->units.delta_x, s->units.delta_y, unit[0] ? " " : "", unit, difference,
                   tolerance, tolerance > IM_SQUARE_PIXEL_TOLERANCE ? "(the extents' printed digits)" : "(2^-16)");
}

/* Metres per unit of a stated unit, or 0 after recording an error naming its key. */
static double stated_metres(const char *path, const char *key, const char *unit, const char **canonical)
{
    double metres = im_length_unit_metres(unit, canonical);
    if (metres == 0.0)
        im_fail(IM_EFORMAT, "%s: %s = '%.15s': expected a length unit (m, cm, mm, \u00b5m or um, nm, pm, \u00c5)",
                path, key, unit);
    return metres;
}

/* Factor that brings the heights into the lateral unit, and the canonical lateral unit; IM_EFORMAT
 * for a unit that is not a length or heights in a unit with no lateral unit to compare. */
static int height_factor(const char *path, const surface_stated *s, double *factor, const char **lateral)
{
    *factor = 1.0;
    *lateral = "";
    if (!s->units.lateral[0] && !s->units.height[0])
        return IM_OK;
    if (!s->units.lateral[0])
        return im_fail(IM_EFORMAT,
                       "%s: %s = '%.15s' gives the heights a unit but the lateral spacing has none: "
                       "state it (--delta and --unit) so that slopes compare lengths in one unit",
                       path, s->height_key, s->units.height);
    double lateral_metres = stated_metres(path, s->lateral_key, s->units.lateral, lateral);
    if (lateral_metres == 0.0)
        return IM_EFORMAT;
    if (!s->units.height[0])
        return IM_OK;
    double height_metres = stated_metres(path, s->height_key, s->units.height, NULL);
    if (height_metres == 0.0)
        return IM_EFORMAT;
    *factor = height_metres / lateral_metres;
    return IM_OK;
}

/* Heights whose unit the file leaves unknown beside a lateral unit: not assumed to share it. */
static int check_height_unit_stated(const char *path, const surface_stated *s)
{
    if (!s->height_unit_unknown || !s->units.lateral[0] || s->units.height[0])
        return IM_OK;
    return im_fail(IM_EFORMAT,
                   "%s: no %s: the heights' unit is not stated, and is not assumed to be the lateral "
                   "unit (%s): state it (a %s line, or --height-unit)",
                   path, s->height_key, s->units.lateral, s->height_key);
}

/* Missing points (NaN): filled on request, else refused naming the first one and the remedy. */
static int missing_points(const char *path, im_field *field, int fill, long *filled)
{
    size_t count = im_field_count(field), i = 0;
    while (i < count && !isnan(field->data[i]))
        ++i;
    if (i == count)
        return IM_OK;
    if (!fill)
        return im_fail(IM_EFORMAT,
                       "%s: value nan at (x=%zu, y=%zu): a missing point; expected finite heights "
                       "(filled from their neighbours on request: --fill, a scene's fill = yes, Python's fill=True)",
                       path, i % (size_t)field->nx, i / (size_t)field->nx);
    int status = im_surface_fill_missing(field, filled);
    return status == IM_OK ? IM_OK : im_fail_context(IM_EFORMAT, "%s", path);
}

/* Converts the spacing from the field's lateral unit into `unit`, multiplies *factor, the heights'
 * conversion still to be applied, by the same ratio and sets *ratio to it. */
static int express_in(const char *path, im_field *field, const char *unit, double *factor, double *ratio)
{
    const char *canonical = "";
    double target = im_length_unit_metres(unit, &canonical), source = im_length_unit_metres(field->unit, NULL);
    if (target == 0.0)
        return im_fail(IM_EINVAL,
                       "--length-unit '%.15s': expected a length unit (m, cm, mm, \u00b5m or um, nm, pm, "
                       "\u00c5)",
                       unit);
    if (source == 0.0)
        return im_fail(IM_EFORMAT, "%s: states no length unit to convert into %s from: give it (--unit)", path, unit);
    *ratio = source / target;
    *factor *= *ratio;
    field->delta *= *ratio;
    snprintf(field->unit, sizeof field->unit, "%s", canonical);
    return IM_OK;
}

/* The spacing and unit of the field, and its heights brought into that unit (and into express_in's,
 * whose ratio to the stated unit goes to *ratio). */
static int apply_units(const char *path, im_field *field, const surface_stated *merged,
                       const im_surface_read_options *options, double *factor, double *ratio)
{
    const char *lateral;
    int status = height_factor(path, merged, factor, &lateral);
    if (status != IM_OK)
        return status;
    const im_surface_units *u = &merged->units;
    field->delta = u->delta_x > 0.0 ? 0.5 * (u->delta_x + u->delta_y) : 1.0; /* delta_x when they are equal */
    snprintf(field->unit, sizeof field->unit, "%s", lateral);
    *ratio = 1.0;
    const char *target = conversion_target(merged, options);
    if (target[0] && (status = express_in(path, field, target, factor, ratio)) != IM_OK)
        return status;
    if (*factor != 1.0) {
        size_t count = im_field_count(field);
        for (size_t i = 0; i < count; ++i)
            field->data[i] *= *factor;
    }
    return IM_OK;
}

/* Heights to solve on: none missing (or filled, counted in *filled), all finite. */
static int check_heights(const char *path, im_field *field, const im_surface_read_options *options, long *filled)
{
    int status = missing_points(path, field, options && options->fill, filled);
    return status == IM_OK ? formats_check_finite(field, path)
                           : status; /* after the conversion, which could overflow */
}

/* Replaces the field's grid by square pixels of the finer of the spacings delta_x and delta_y. */
static int resample_in_place(const char *path, im_field *field, double delta_x, double delta_y)
{
    im_field *square = NULL;
    int status = im_surface_resample_square(field, delta_x, delta_y, &square);
    if (status != IM_OK)
        return im_fail_context(status, "%s", path);
    im_field stored = *field;
    *field = *square;
    *square = stored;
    im_field_free(square);
    return IM_OK;
}

/* info->assumed: the unit taken for heights whose file states none (merged: after the options, whose
 * height unit, when given, leaves nothing assumed). */
static void note_assumed_height_unit(const surface_stated *merged, char *text, size_t size)
{
    const im_surface_units *u = &merged->units;
    if (merged->unstated_height && u->lateral[0] && !u->height[0])
        snprintf(text, size, "%s: its heights are taken in %s, the lateral unit", merged->unstated_height,
                 u->lateral);
}

int surface_finish(const char *path, im_field *field, const surface_stated *stated,
                   const im_surface_read_options *options, im_surface_read_info *info)
{
    surface_stated merged = merge_overrides(stated, options);
    const int resample = options && options->resample_square;
    const double difference = spacing_difference(&merged.units), tolerance = square_tolerance(&merged);
    double factor = 1.0, ratio = 1.0;
    /* what the file states wrong (a unit that is not a length), then its pixels, then what it leaves unstated */
    int status = apply_units(path, field, &merged, options, &factor, &ratio);
    if (status == IM_OK)
        status = check_square_pixels(path, &merged, difference, tolerance, resample);
    if (status == IM_OK)
        status = check_height_unit_stated(path, &merged);
    long filled = 0;
    if (status == IM_OK && !(options && options->field_values)) /* heights: none missing or filled, all finite */
        status = check_heights(path, field, options, &filled);
    im_surface_units used = merged.units;
    used.delta_x *= ratio;
    used.delta_y *= ratio;
    snprintf(used.lateral, sizeof used.lateral, "%s", field->unit);
    const int stored_nx = field->nx, stored_ny = field->ny;
    const int resampling = status == IM_OK && resample && difference > IM_SQUARE_PIXEL_TOLERANCE;
    if (resampling)
        status = resample_in_place(path, field, used.delta_x, used.delta_y);
    if (status != IM_OK || !info)
        return status;
    *info = (im_surface_read_info){.file = stated->units,
                                   .used = used,
                                   .height_factor = factor,
                                   .filled = filled,
                                   .spacing_difference = difference,
                                   .square_tolerance = tolerance,
                                   .resampled_delta = resampling ? field->delta : 0.0,
                                   .stored_nx = stored_nx,
                                   .stored_ny = stored_ny};
    memcpy(info->conversion, stated->conversion, sizeof info->conversion);
    snprintf(info->resampled, sizeof info->resampled, "%s", resampling ? "bilinear" : "");
    note_assumed_height_unit(&merged, info->assumed, sizeof info->assumed);
    return IM_OK;
}

int surface_read_format(const char *path, surface_raw_reader read, const im_surface_read_options *options,
                        im_field **out, im_surface_read_info *info)
{
    surface_stated stated;
    int status = read(path, out, &stated);
    if (status == IM_OK)
        status = npy_apply_order(path, *out, &stated, options);
    if (status == IM_OK)
        status = surface_finish(path, *out, &stated, options, info);
    if (status != IM_OK) {
        im_field_free(*out);
        *out = NULL;
    }
    return status;
}
