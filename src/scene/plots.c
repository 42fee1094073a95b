/* The paper's line figures that a scene asks for in [output] plots. */
#include "indentmap/paper.h"
#include "scene/contents.h"
#include "indentmap/status.h"
#include "scene/frames.h"
#include "scene/outputs.h"
#include "scene/plots.h"
#include "scene/progress.h"
#include "scene/surfaces.h"

#include <stdio.h>

int scene_wants_plot(const im_scene *scene, enum im_scene_plot plot) { return (scene->plots & plot) != 0; }

int scene_wants_histories(const im_scene *scene)
{
    return scene->periodic || scene_wants_plot(scene, IM_SCENE_PLOT_FIG5 | IM_SCENE_PLOT_FIG6 | IM_SCENE_PLOT_FIG7 |
                                                          IM_SCENE_PLOT_SPHERE);
}

int scene_rough_family_count(const im_scene *scene)
{
    int count = 0;
    for (int f = 0; f < scene->family_count; ++f)
        count += scene->slopes[f] > 0.0;
    return count;
}

/* The names are checked by the parser (parse.c); here what each plot needs beside it, before any work
 * (the run's, and --check's). */
int scene_check_plots(const im_scene *scene)
{
    if (scene_wants_plot(scene, IM_SCENE_PLOT_DENSITY) && !scene->contact_panels)
        return im_fail(IM_EINVAL, "%s: plots = density measures the maps of [output] contact_panels = yes",
                       scene->path);
    if (scene_wants_plot(scene, IM_SCENE_PLOT_SPHERE) && scene->punch != IM_PUNCH_SPHERE)
        return im_fail(IM_EINVAL, "%s: plots = sphere compares with eq. (3): it needs [punch] shape = sphere",
                       scene->path);
    if (scene_wants_plot(scene, IM_SCENE_PLOT_SPHERE) && scene_rough_family_count(scene) == 0)
        return im_fail(IM_EINVAL, "%s: plots = sphere needs a rough family", scene->path);
    if (scene_wants_plot(scene, IM_SCENE_PLOT_FIG7) && scene_rough_family_count(scene) == 0)
        return im_fail(IM_EINVAL, "%s: plots = fig7 draws the rough families: give a slope > 0", scene->path);
    if (scene_wants_plot(scene, IM_SCENE_PLOT_FLAT_K) && scene_rough_family_count(scene) == 0)
        return im_fail(IM_EINVAL, "%s: plots = flat_k measures k on rough surfaces: give a slope > 0", scene->path);
    if (scene_wants_plot(scene, IM_SCENE_PLOT_FIG2) && !scene->table)
        return im_fail(IM_EINVAL, "%s: plots = fig2 draws the ensemble of [output] table = yes", scene->path);
    return IM_OK;
}

static int draw_fig1(const im_scene *scene, const void *data, const paper_file *file)
{
    (void)data;
    double slopes[IM_SCENE_MAX_FAMILIES];
    int count = 0;
    for (int i = 0; i < scene->family_count; ++i)
        if (scene->slopes[i] > 0.0)
            slopes[count++] = scene->slopes[i];
    const im_plot style = paper_file_style(file);
    return im_paper_fig1_contact_density(scene->alpha_degrees, slopes, count, &style, file->path);
}

static int draw_fig2(const im_scene *scene, const void *data, const paper_file *file)
{
    (void)scene;
    const im_plot style = paper_file_style(file);
    return im_paper_fig2_area_ratio(data, &style, file->path);
}

static int draw_fig3(const im_scene *scene, const void *data, const paper_file *file)
{
    const im_plot style = paper_file_style(file);
    return im_paper_fig3_surface(data, &scene->surface, 101, &style, file->path);
}

int scene_plot_area_ratio(const im_scene *scene, const im_paper_points *points)
{
    return scene_write_png_pdf(scene, "fig2", draw_fig2, points);
}

int scene_run_theory_plots(const im_scene *scene, const im_scene_run_options *options)
{
    int status = IM_OK;
    if (scene_wants_plot(scene, IM_SCENE_PLOT_FIG1)) {
        scene_progress(options, "fig1: local contact density gamma(r/a)");
        status = scene_write_png_pdf(scene, "fig1", draw_fig1, NULL);
    }
    if (status == IM_OK && scene_wants_plot(scene, IM_SCENE_PLOT_FIG3)) {
        int family = scene_framed_family(scene);
        scene_progress(options, "fig3: statistics of the h'rms = %g surface", scene->slopes[family]);
        im_field *surface = NULL;
        status = scene_surface(scene, family, scene->seeds[0], &surface);
        if (status == IM_OK)
            status = scene_write_png_pdf(scene, "fig3", draw_fig3, surface);
        im_field_free(surface);
    }
    return status;
}
