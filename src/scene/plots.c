/* The paper's line figures that a scene asks for in [output] plots. */
#include "indentmap/plot.h"
#include "indentmap/status.h"
#include "scene/frames.h"
#include "scene/outputs.h"
#include "scene/plots.h"
#include "scene/progress.h"
#include "scene/surfaces.h"

#include <stdio.h>
#include <string.h>

int scene_wants_plot(const im_scene *scene, const char *name)
{
    size_t length = strlen(name);
    for (const char *p = scene->plots; (p = strstr(p, name)) != NULL; p += length) {
        int starts = p == scene->plots || p[-1] == ',' || p[-1] == ' ';
        int ends = p[length] == '\0' || p[length] == ',' || p[length] == ' ';
        if (starts && ends)
            return 1;
    }
    return 0;
}

int scene_wants_histories(const im_scene *scene)
{
    return scene_wants_plot(scene, "fig5") || scene_wants_plot(scene, "fig6") || scene_wants_plot(scene, "fig7") ||
           scene_wants_plot(scene, "sphere");
}

int scene_check_plots(const im_scene *scene)
{
    static const char *const KNOWN[] = {"fig1", "fig2", "fig3", "fig5", "fig6", "fig7", "density", "sphere",
                                        "flat_k"};
    char copy[sizeof scene->plots];
    snprintf(copy, sizeof copy, "%s", scene->plots);
    for (char *name = strtok(copy, ", "); name; name = strtok(NULL, ", ")) {
        int known = 0;
        for (size_t i = 0; i < sizeof KNOWN / sizeof *KNOWN; ++i)
            known |= strcmp(name, KNOWN[i]) == 0;
        if (!known)
            return im_fail(IM_EINVAL, "%s: [output] plots: '%s' is not a figure; expected fig1, fig2, fig3, "
                           "fig5, fig6, fig7, density, sphere or flat_k", scene->path, name);
    }
    if (scene_wants_plot(scene, "density") && !scene->contact_panels)
        return im_fail(IM_EINVAL, "%s: plots = density measures the maps of [output] contact_panels = yes",
                       scene->path);
    if (scene_wants_plot(scene, "sphere") && scene->punch != IM_PUNCH_SPHERE)
        return im_fail(IM_EINVAL, "%s: plots = sphere compares with eq. (3): it needs [punch] shape = sphere",
                       scene->path);
    if (scene_wants_plot(scene, "fig2") && !scene->table)
        return im_fail(IM_EINVAL, "%s: plots = fig2 draws the ensemble of [output] table = yes", scene->path);
    return IM_OK;
}

static int draw_fig1(const im_scene *scene, const void *data, const char *path)
{
    (void)data;
    double slopes[IM_SCENE_MAX_FAMILIES];
    int count = 0;
    for (int i = 0; i < scene->family_count; ++i)
        if (scene->slopes[i] > 0.0)
            slopes[count++] = scene->slopes[i];
    return im_plot_figure_contact_density(scene->alpha_degrees, slopes, count, NULL, path);
}

static int draw_fig2(const im_scene *scene, const void *data, const char *path)
{
    (void)scene;
    return im_plot_figure_area_ratio(data, NULL, path);
}

static int draw_fig3(const im_scene *scene, const void *data, const char *path)
{
    return im_plot_figure_surface(data, &scene->surface, 101, NULL, path);
}

int scene_plot_area_ratio(const im_scene *scene, const im_plot_points *points)
{
    return scene_write_png_pdf(scene, "fig2", draw_fig2, points);
}

int scene_run_theory_plots(const im_scene *scene, const im_scene_run_options *options)
{
    int status = IM_OK;
    if (scene_wants_plot(scene, "fig1")) {
        scene_progress(options, "fig1: local contact density gamma(r/a)");
        status = scene_write_png_pdf(scene, "fig1", draw_fig1, NULL);
    }
    if (status == IM_OK && scene_wants_plot(scene, "fig3")) {
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
