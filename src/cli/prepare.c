/* Options that prepare a measured surface (--fill, --crop, --align, --detrend, --window), shared by
 * `surface --stats` and `indent`. */
#include "cli/cli.h"
#include "front/front.h"

#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "core/number.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cli_parse_crop(const char *text, int crop[4])
{
    char tail;
    if (sscanf(text, "%d,%d,%d,%d%c", &crop[0], &crop[1], &crop[2], &crop[3], &tail) != 4 || crop[0] < 0 ||
        crop[1] < 0 || crop[2] < 2 || crop[3] < 2) {
        fprintf(stderr, "indentmap: --crop '%s': expected X0,Y0,NX,NY (corner >= 0, sides >= 2)\n", text);
        return -1;
    }
    return 0;
}

int cli_parse_detrend(const char *text, enum im_detrend *out)
{
    static const char *const NAMES[] = {"none", "plane", "curvature"};
    for (int i = 0; i < 3; ++i)
        if (strcmp(text, NAMES[i]) == 0) {
            *out = (enum im_detrend)i;
            return 0;
        }
    fprintf(stderr, "indentmap: --detrend '%s': expected none, plane or curvature\n", text);
    return -1;
}

int cli_parse_align(const char *text, enum im_row_alignment *out)
{
    static const char *const NAMES[] = {"none", "median", "mean", "line"};
    for (int i = 0; i < 4; ++i)
        if (strcmp(text, NAMES[i]) == 0) {
            *out = (enum im_row_alignment)i;
            return 0;
        }
    fprintf(stderr, "indentmap: --align '%s': expected none, median, mean or line (scan lines: rows)\n", text);
    return -1;
}

int cli_parse_device(const char *text, int *device)
{
    if (im_device_parse(text, device) == IM_OK)
        return 0;
    fprintf(stderr, "indentmap: --device '%s': expected cpu, gpu or auto\n", text);
    return -1;
}

int cli_parse_taper(const char *text, im_taper *out)
{
    if (strcmp(text, "none") == 0 || strcmp(text, "hann") == 0) {
        *out = (im_taper){text[0] == 'h' ? IM_TAPER_HANN : IM_TAPER_NONE, 0.0};
        return 0;
    }
    double alpha = 0.5;
    const char *given = strncmp(text, "tukey:", 6) == 0 ? text + 6 : NULL;
    char *end = NULL;
    if (given)
        alpha = number_parse(given, &end);
    if (strcmp(text, "tukey") == 0 || (given && end != given && !*end && alpha >= 0.0 && alpha <= 1.0)) {
        *out = (im_taper){IM_TAPER_TUKEY, alpha};
        return 0;
    }
    fprintf(stderr, "indentmap: --window '%s': expected none, hann, tukey or tukey:ALPHA (0 <= ALPHA <= 1)\n", text);
    return -1;
}

int cli_apply_surface_file_option(int code, const char *arg, im_surface_read_options *read,
                                  cli_preparation *preparation, int *prepared)
{
    if (prepared)
        *prepared |= code != CLI_OPT_UNIT && code != CLI_OPT_HEIGHT_UNIT && code != CLI_OPT_CHANNEL;
    switch (code) {
    case CLI_OPT_UNIT: return cli_parse_length_unit("--unit", arg, read->set.lateral);
    case CLI_OPT_HEIGHT_UNIT: return cli_parse_length_unit("--height-unit", arg, read->set.height);
    case CLI_OPT_CHANNEL: return cli_parse_channel(arg, read->channel);
    case CLI_OPT_FILL: read->fill = 1; return 0;
    case CLI_OPT_RESAMPLE: read->resample_square = 1; return 0;
    case CLI_OPT_CROP: return cli_parse_crop(arg, preparation->crop);
    case CLI_OPT_NPY_ORDER: return cli_parse_npy_order(arg, &read->npy_order);
    case CLI_OPT_DETREND: return cli_parse_detrend(arg, &preparation->detrend);
    case CLI_OPT_ALIGN: return cli_parse_align(arg, &preparation->align);
    default: return -1;
    }
}

/* The library's preparation (front.h) of the options' (the taper is for spectra only). */
static surface_preparation preparation_of(const cli_preparation *p)
{
    return (surface_preparation){{p->crop[0], p->crop[1], p->crop[2], p->crop[3]}, p->detrend, p->align};
}

int cli_prepare_surface(const cli_preparation *p, im_field **surface)
{
    const surface_preparation preparation = preparation_of(p);
    return surface_prepare(&preparation, surface);
}

void cli_warn_about_reading(const char *path, const im_surface_read_info *info, size_t points)
{
    char warning[8192];
    if (surface_fill_warning(path, info->filled, points, warning, sizeof warning))
        fprintf(stderr, "indentmap: %s\n", warning);
    if (surface_assumption_warning(path, info, warning, sizeof warning))
        fprintf(stderr, "indentmap: %s\n", warning);
}

void cli_describe_preparation(const cli_preparation *p, long filled, char *text, size_t size)
{
    const surface_preparation preparation = preparation_of(p);
    surface_preparation_describe(&preparation, filled, text, size);
}
