/* [output] distributions: the gap and contact-patch size distributions at load_star of each
 * family's first surface (measure.h: im_measure_write_distributions), as CSV under
 * OUTPUT/distributions/. Solved here (a full-grid gap needs the displacement the table and panels
 * do not keep), every time it is asked for. */
#include "indentmap/measure.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"
#include "scene/scene_internal.h"

#include <stdio.h>

enum { GAP_BINS = 50 };

/* Force and full-grid gap of a surface at load n, in load control warm-started at n / 4. */
static int solve_state(const im_scene *scene, const im_scene_run_options *options, const im_field *surface,
                       double n, im_field **force, im_field **gap)
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

static int family_distributions(const im_scene *scene, const im_scene_run_options *options, int family)
{
    im_field *surface = NULL, *force = NULL, *gap = NULL;
    int status = scene_surface(scene, family, scene->seeds[0], &surface);
    char relative[64], prefix[IM_SCENE_PATH];
    snprintf(relative, sizeof relative, "distributions/family_%02d", family);
    if (status == IM_OK)
        status = scene_output_path(scene, relative, prefix, sizeof prefix);
    if (status == IM_OK)
        status = solve_state(scene, options, surface, scene_load_for_load_star(scene, surface->delta), &force, &gap);
    if (status == IM_OK)
        status = im_measure_write_distributions(force, gap, gap_scale(surface), GAP_BINS, prefix);
    im_field_free(surface);
    im_field_free(force);
    im_field_free(gap);
    return status;
}

int scene_run_distributions(const im_scene *scene, const im_scene_run_options *options)
{
    char folder[IM_SCENE_PATH];
    int status = scene_output_path(scene, "distributions", folder, sizeof folder);
    if (status == IM_OK)
        status = im_make_directories(folder);
    if (status == IM_OK)
        scene_progress(options, "distributions: gaps and patch sizes of %d surfaces at N* = %g", scene->family_count,
                       scene->load_star);
    for (int f = 0; f < scene->family_count && status == IM_OK; ++f)
        status = family_distributions(scene, options, f);
    return status;
}
