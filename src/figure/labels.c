/* The colour bar's name of a drawn field, in its units (figure.h: im_figure_colorbar_label): one
 * definition for `indentmap render` and Python's pictures. */
#include "indentmap/figure.h"
#include "indentmap/status.h"

#include <stdio.h>
#include <string.h>

typedef struct quantity_name {
    const char *quantity, *name, *without_unit;
} quantity_name;

static const quantity_name QUANTITIES[] = {{"force", "local force f", "(E* δ²)"},
                                           {"height", "height h", "δ"},
                                           {"gap", "gap g", "δ"},
                                           {"displacement", "displacement u", "δ"},
                                           {"plastic", "plastic depth d", "δ"},
                                           {"tension", "tensile force −f", "(E* δ²)"}};

int im_figure_colorbar_label(const char *quantity, const char *unit, char *text, size_t size)
{
    if (!quantity || !unit || !text)
        return im_fail(IM_EINVAL, "im_figure_colorbar_label: %s is NULL",
                       !quantity ? "quantity"
                       : !unit   ? "unit"
                                 : "text");
    for (size_t i = 0; i < sizeof QUANTITIES / sizeof *QUANTITIES; ++i) {
        const quantity_name *q = &QUANTITIES[i];
        if (strcmp(quantity, q->quantity) != 0)
            continue;
        /* a unit of several factors in parentheses ("Pa µm²" and "E* δ²" as "(E* δ²)"), one alone bare */
        const char *shown = unit[0] ? unit : q->without_unit;
        const int compound = shown[0] != '(' && strchr(shown, ' ');
        int length = snprintf(text, size, compound ? "%s / (%s)" : "%s / %s", q->name, shown);
        if (length < 0 || (size_t)length >= size)
            return im_fail(IM_EINVAL, "im_figure_colorbar_label: size %zu: the label needs %d bytes", size,
                           length + 1);
        return IM_OK;
    }
    return im_fail(IM_EINVAL,
                   "im_figure_colorbar_label: quantity '%s': expected force, height, gap, displacement, "
                   "plastic or tension",
                   quantity);
}
