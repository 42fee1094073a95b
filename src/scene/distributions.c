/* [output] distributions: the gap and contact-patch size distributions at load_star of each
 * family's first surface (measure.h: im_measure_write_distributions), as CSV under
 * OUTPUT/distributions/, and drawn in distributions.png/pdf. Solved here (a full-grid gap needs the
 * displacement the table and panels do not keep), every time it is asked for. */
#include "indentmap/measure.h"
#include "scene/contents.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"
#include "paper/figures.h"
#include "scene/distributions.h"
#include "scene/labels.h"
#include "scene/outputs.h"
#include "scene/progress.h"
#include "scene/punch.h"
#include "scene/surfaces.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

enum { GAP_BINS = 50 };

/* What the plot draws of each family. */
typedef struct family_curves {
    double gap[GAP_BINS], gap_density[GAP_BINS];
    double patch_area[IM_PATCH_BINS], patch_count[IM_PATCH_BINS];
    char label[64];
} family_curves;

/* Force and full-grid gap of a surface at load n, in load control warm-started at n / 4. */
static int solve_state(const im_scene *scene, const im_scene_run_options *options, const im_field *surface, double n,
                       im_field **force, im_field **gap)
{
    im_indenter punch = scene_punch(scene);
    im_solver_options solver = scene_solver_options(scene);
    im_indentation *run = NULL;
    im_step_result step;
    int status = im_indentation_create(surface, &punch, IM_CONTROL_LOAD, n, &solver, &run);
    if (status == IM_OK)
        status = im_indentation_step(run, 0.25 * n, &step);
    if (status == IM_OK && scene_stop_signal(options))
        status = scene_interrupted(options, "while solving for the distributions (abandoned)");
    if (status == IM_OK)
        status = im_indentation_step(run, n, &step);
    if (status == IM_OK)
        status = im_indentation_fields_full(run, force, gap, NULL);
    im_indentation_free(run);
    return status;
}

/* The gaps' unit: the surface's h_rms, or delta for a smooth one. */
static double gap_scale(const im_field *surface)
{
    im_surface_stats stats;
    int measured = im_surface_statistics(surface, &stats) == IM_OK && stats.height_rms > 0.0;
    return measured ? stats.height_rms : surface->delta;
}

/* The plotted curves: gap density at the bins' centres, patches per octave at its smallest area
 * (NaN where empty: a gap in the log-scaled line). */
static int measure_curves(const im_field *force, const im_field *gap, double scale, family_curves *c)
{
    long counts[GAP_BINS], infinite, patches[IM_PATCH_BINS], cells[IM_PATCH_BINS], edges[IM_PATCH_BINS];
    double width;
    int status = im_measure_gap_distribution(gap, force, scale, GAP_BINS, counts, &width, &infinite);
    for (int b = 0; status == IM_OK && b < GAP_BINS; ++b) {
        c->gap[b] = (b + 0.5) * width;
        c->gap_density[b] = counts[b] > 0 ? counts[b] / ((double)im_field_count(gap) * width) : NAN;
    }
    im_patch *list = NULL;
    long count = 0;
    if (status == IM_OK)
        status = im_measure_patch_list(force, &list, &count);
    if (status == IM_OK)
        status = im_measure_patch_histogram(list, count, patches, cells, edges);
    for (int b = 0; status == IM_OK && b < IM_PATCH_BINS; ++b) {
        c->patch_area[b] = (double)(1L << b) * force->delta * force->delta;
        c->patch_count[b] = patches[b] > 0 ? (double)patches[b] : NAN;
    }
    free(list);
    return status;
}

/* Notes the files im_measure_write_distributions writes under relative (measure.h names them), so
 * that a damaged one is removed with a notice before it is written again: the writer's kind guard
 * would refuse to replace it. */
static int note_family_files(const im_scene *scene, const char *relative)
{
    static const char *const SUFFIXES[] = {"_gaps.csv", "_patches.csv", "_patch_list.csv"};
    int status = IM_OK;
    for (int i = 0; i < 3 && status == IM_OK; ++i) {
        char name[96], path[IM_SCENE_PATH];
        snprintf(name, sizeof name, "%s%s", relative, SUFFIXES[i]);
        status = scene_output_path(scene, name, path, sizeof path);
    }
    return status;
}

static int family_distributions(const im_scene *scene, const im_scene_run_options *options, int family,
                                family_curves *curves)
{
    im_field *surface = NULL, *force = NULL, *gap = NULL;
    int status = scene_surface(scene, family, scene->seeds[0], &surface);
    char relative[64], prefix[IM_SCENE_PATH];
    snprintf(relative, sizeof relative, "distributions/family_%02d", family);
    if (status == IM_OK)
        status = note_family_files(scene, relative);
    if (status == IM_OK)
        status = scene_output_path(scene, relative, prefix, sizeof prefix);
    if (status == IM_OK)
        status = solve_state(scene, options, surface, scene_load_for_load_star(scene, surface->delta), &force, &gap);
    double scale = status == IM_OK ? gap_scale(surface) : 1.0;
    if (status == IM_OK)
        status = im_measure_write_distributions(force, gap, scale, GAP_BINS, prefix);
    if (status == IM_OK)
        status = measure_curves(force, gap, scale, curves);
    scene_family_title(scene, family, curves->label, sizeof curves->label);
    im_field_free(surface);
    im_field_free(force);
    im_field_free(gap);
    return status;
}

static int draw_distributions(const im_scene *scene, const void *families, const paper_file *file)
{
    return paper_figure_distributions(families, scene->family_count, scene->path, file);
}

/* (a) the gap density against g / h_rms of the rough families, (b) patches per octave of size of
 * every family (paper/distribution_figure.c). */
static int plot_distributions(const im_scene *scene, const family_curves *curves)
{
    paper_distribution_family *families = calloc((size_t)scene->family_count, sizeof *families);
    if (!families)
        return im_fail(IM_ENOMEM, "%s: allocation of the distributions' plot failed", scene->path);
    for (int f = 0; f < scene->family_count; ++f)
        families[f] = (paper_distribution_family){.label = curves[f].label,
                                                  .rough = scene_member_slope(scene, f, scene->seeds[0]) > 0.0,
                                                  .gap_bins = GAP_BINS,
                                                  .gap = curves[f].gap,
                                                  .gap_density = curves[f].gap_density,
                                                  .patch_bins = IM_PATCH_BINS,
                                                  .patch_area = curves[f].patch_area,
                                                  .patch_count = curves[f].patch_count};
    int status = scene_write_png_pdf(scene, "distributions", draw_distributions, families);
    free(families);
    return status;
}

int scene_run_distributions(const im_scene *scene, const im_scene_run_options *options)
{
    char folder[IM_SCENE_PATH];
    family_curves *curves = calloc((size_t)scene->family_count, sizeof *curves);
    int status = curves ? scene_output_path(scene, "distributions", folder, sizeof folder)
                        : im_fail(IM_ENOMEM, "%s: allocation of the distributions failed", scene->path);
    if (status == IM_OK)
        status = im_make_directories(folder);
    if (status == IM_OK)
        scene_progress(options, "distributions: gaps and patch sizes of %d surface%s at N* = %g", scene->family_count,
                       scene->family_count == 1 ? "" : "s", scene->load_star);
    for (int f = 0; f < scene->family_count && status == IM_OK; ++f)
        status = family_distributions(scene, options, f, &curves[f]);
    if (status == IM_OK)
        status = plot_distributions(scene, curves);
    free(curves);
    return status;
}
