#include "indentmap/colormap.h"
#include "core/args.h"

#include "colormap/colormap_tables.h"
#include "indentmap/status.h"

#include <math.h>
#include <string.h>

static const char *const MAP_NAMES[IM_COLORMAP_COUNT] = {"viridis", "cividis", "magma", "inferno", "grey", "tension"};

const uint8_t (*im_colormap_table(im_colormap_id map))[3]
{
    switch (map) {
    case IM_COLORMAP_CIVIDIS: return im_colormap_table_cividis;
    case IM_COLORMAP_MAGMA: return im_colormap_table_magma;
    case IM_COLORMAP_INFERNO: return im_colormap_table_inferno;
    case IM_COLORMAP_GREY: return im_colormap_table_grey;
    case IM_COLORMAP_TENSION: return im_colormap_table_tension;
    default: return im_colormap_table_viridis;
    }
}

im_colormap im_colormap_make(im_colormap_id map, double lo, double hi)
{
    im_colormap colormap = {.map = map, .lo = lo, .hi = hi, .logarithmic = 0, .bad = {128, 128, 128}};
    const uint8_t(*table)[3] = im_colormap_table(map);
    memcpy(colormap.under, table[0], 3);
    memcpy(colormap.over, table[255], 3);
    return colormap;
}

int im_colormap_from_name(const char *name, im_colormap_id *map)
{
    ARG_REQUIRE(name, "name");
    ARG_REQUIRE(map, "map");
    for (int i = 0; i < IM_COLORMAP_TENSION; ++i) { /* the maps a user may choose */
        if (strcmp(name, MAP_NAMES[i]) == 0 || (i == IM_COLORMAP_GREY && strcmp(name, "gray") == 0)) {
            *map = (im_colormap_id)i;
            return IM_OK;
        }
    }
    return im_fail(IM_EINVAL, "colour map '%s': expected viridis, cividis, magma, inferno or grey", name);
}

const char *im_colormap_name(im_colormap_id map)
{
    return map >= 0 && map < IM_COLORMAP_COUNT ? MAP_NAMES[map] : "unknown";
}

int im_colormap_check(const im_colormap *c)
{
    ARG_REQUIRE(c, "colormap");
    if (!isfinite(c->lo) || !isfinite(c->hi) || !(c->hi > c->lo))
        return im_fail(IM_EINVAL, "colour norm [%g, %g]: expected finite lo < hi", c->lo, c->hi);
    if (c->logarithmic && !(c->lo > 0.0))
        return im_fail(IM_EINVAL, "logarithmic colour norm with lo = %g: expected lo > 0", c->lo);
    return IM_OK;
}

int im_colormap_index(const im_colormap *c, double value)
{
    ARG_REQUIRE_OR(c, "colormap", -2);
    if (isnan(value))
        return -2;
    if (value < c->lo)
        return -1;
    if (value > c->hi)
        return 256;
    double t = c->logarithmic ? log(value / c->lo) / log(c->hi / c->lo) : (value - c->lo) / (c->hi - c->lo);
    int index = (int)floor(256.0 * t);
    return index > 255 ? 255 : (index < 0 ? 0 : index);
}

void im_colormap_rgb(const im_colormap *c, double value, uint8_t rgb[3])
{
    ARG_REQUIRE_OR(c, "colormap", );
    ARG_REQUIRE_OR(rgb, "rgb", );
    int index = im_colormap_index(c, value);
    const uint8_t *colour = index == -2    ? c->bad
                            : index == -1  ? c->under
                            : index == 256 ? c->over
                                           : im_colormap_table(c->map)[index];
    memcpy(rgb, colour, 3);
}

void im_colormap_field_image(const im_colormap *c, const im_field *field, uint8_t *rgb)
{
    ARG_REQUIRE_OR(c, "colormap", );
    ARG_VIEW_OR(field, "field", );
    ARG_REQUIRE_OR(rgb, "rgb", );
#pragma omp parallel for schedule(static)
    for (int row = 0; row < field->ny; ++row) {
        const double *values = field->data + (size_t)(field->ny - 1 - row) * field->nx;
        uint8_t *pixels = rgb + (size_t)row * field->nx * 3;
        for (int ix = 0; ix < field->nx; ++ix)
            im_colormap_rgb(c, values[ix], pixels + 3 * ix);
    }
}
