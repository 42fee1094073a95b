/* Beyond the paper: the gap and contact-patch size distributions of families at one load, (a) the
 * gap density against g / h_rms and (b) patches per octave of area. */
#include "paper/figures.h"

#include "indentmap/plot.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>

static int check_families(const paper_distribution_family *families, int count, const char *source)
{
    if (count < 1 || count > PAPER_MAX_PANELS)
        return im_fail(IM_EINVAL, "%s: distributions of %d families: expected 1 to %d", source, count,
                       PAPER_MAX_PANELS);
    for (int f = 0; f < count; ++f) {
        const paper_distribution_family *d = &families[f];
        int gaps_missing = d->rough && d->gap_bins > 0 && (!d->gap || !d->gap_density);
        if (gaps_missing || (d->patch_bins > 0 && (!d->patch_area || !d->patch_count)))
            return im_fail(IM_EINVAL, "%s: distributions: family %d's bins come without their arrays", source, f);
    }
    return IM_OK;
}

/* The most patches in any bin (at least 1), for (b)'s y axis. */
static double most_patches(const paper_distribution_family *families, int count)
{
    double most = 1.0;
    for (int f = 0; f < count; ++f)
        for (int b = 0; b < families[f].patch_bins; ++b)
            most = fmax(most, isnan(families[f].patch_count[b]) ? 0.0 : families[f].patch_count[b]);
    return most;
}

/* Fills series[0, rough) with (a)'s gap lines and series[count, 2 count) with (b)'s patch markers;
 * returns rough, the number of rough families. */
static int distribution_series(const paper_distribution_family *families, int count, im_plot_series *series)
{
    int rough = 0;
    for (int f = 0; f < count; ++f) {
        const paper_distribution_family *d = &families[f];
        series[count + f] = (im_plot_series){.x = d->patch_area,
                                             .y = d->patch_count,
                                             .n = d->patch_bins,
                                             .line = IM_PLOT_NO_LINE,
                                             .marker = IM_PLOT_MARKER_CIRCLE,
                                             .label = d->label};
        im_plot_family_color(f, count, series[count + f].color);
        if (!d->rough)
            continue;
        series[rough] = (im_plot_series){.x = d->gap, .y = d->gap_density, .n = d->gap_bins, .label = d->label};
        im_plot_family_color(f, count, series[rough++].color);
    }
    return rough;
}

int paper_figure_distributions(const paper_distribution_family *families, int count, const char *source,
                               const paper_file *file)
{
    int status = check_families(families, count, source);
    if (status != IM_OK)
        return status;
    im_plot_series *series = calloc(2 * (size_t)count, sizeof *series);
    if (!series)
        return im_fail(IM_ENOMEM, "%s: allocation of the distributions' plot failed", source);
    int rough = distribution_series(families, count, series);
    im_plot_panel panels[2] = {
        {.x = {IM_PLOT_LINEAR, 0, 0, "g / h_{rms} outside contact"},
         .y = {IM_PLOT_LOG, 0, 0, "density over all cells"},
         .series = series,
         .series_count = rough,
         .label = "(a)",
         .legend = IM_PLOT_LEGEND_UPPER_RIGHT},
        {.x = {IM_PLOT_LOG, 0, 0, "patch area A_{i} / δ^{2} (octaves)"},
         .y = {IM_PLOT_LOG, 0.5, 2.0 * most_patches(families, count), "patches"},
         .series = series + count,
         .series_count = count,
         .label = "(b)",
         .legend = IM_PLOT_LEGEND_AUTO},
    };
    im_plot plot = im_plot_default();
    plot.columns = rough > 0 ? 2 : 1; /* without a rough family, (b) alone */
    plot.panels = rough > 0 ? panels : panels + 1;
    status = paper_plot_write(&plot, file);
    free(series);
    return status;
}
