/* Contact-map panels at one load for every family (the paper's Fig. 4, drawn by
 * paper/map_figures.c), and their table. */
#include "front/front.h"
#include "indentmap/io.h"
#include "scene/contents.h"
#include "indentmap/formats.h"
#include "indentmap/status.h"
#include "paper/figures.h"
#include "scene/density.h"
#include "scene/ensemble.h"
#include "scene/frames.h"
#include "scene/key.h"
#include "scene/labels.h"
#include "scene/outputs.h"
#include "scene/panels.h"
#include "scene/plots.h"
#include "scene/progress.h"
#include "scene/punch.h"
#include "scene/surfaces.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct panel_result {
    im_field *force;
    double load, load_star, area_ratio, area_ratio_eq12;
    long contact_patches;
    enum scene_origin origin;
} panel_result;

/* Solves one family at load n in load control, warm-started by a step at n / 4. */
static int solve_panel(const im_scene *scene, const im_scene_run_options *run_options, const im_field *surface,
                       double n, im_field **force)
{
    im_indenter punch = scene_punch(scene);
    im_solver_options options = scene_solver_options(scene);
    options.wisdom_path = NULL; /* two steps on a window of its own size: measuring its plans would not pay
                                  * (docs/solver.md, "FFTW wisdom") */
    im_indentation *run = NULL;
    int status = im_indentation_create(surface, &punch, IM_CONTROL_LOAD, n, &options, &run);
    im_step_result step;
    if (status == IM_OK)
        status = im_indentation_step(run, 0.25 * n, &step);
    if (status == IM_OK && scene_stop_signal(run_options))
        status = scene_interrupted(run_options, "while solving a panel (abandoned)");
    if (status == IM_OK)
        status = im_indentation_step(run, n, &step);
    if (status == IM_OK)
        status = im_indentation_fields(run, force, NULL, NULL);
    im_indentation_free(run);
    return status;
}

/* Solves the first seed of a family at load_star. */
static int solve_family(const im_scene *scene, const im_scene_run_options *options, int family, im_field **force)
{
    im_field *surface = NULL;
    int status = scene_surface(scene, family, scene->seeds[0], &surface);
    if (status == IM_OK) {
        double n = scene_load_for_load_star(scene, surface->delta);
        scene_progress(options, "family %d (h'rms = %g): solving at N = %.6g", family, scene->slopes[family], n);
        status = solve_panel(scene, options, surface, n, force);
    }
    im_field_free(surface);
    return status;
}

/* Load, contact patches and ratios measured on a force field. */
static void measure_panel(const im_scene *scene, panel_result *r)
{
    const im_field *f = r->force;
    double load = 0.0;
    long patches = 0;
    for (size_t i = 0; i < im_field_count(f); ++i) {
        load += f->data[i];
        patches += f->data[i] > 0.0;
    }
    im_indenter punch = scene_punch(scene);
    double area = im_indenter_area_for_load(&punch, scene->modulus, load);
    r->load = load;
    r->contact_patches = patches;
    r->load_star = area / (f->delta * f->delta);
    r->area_ratio = area > 0.0 ? patches * f->delta * f->delta / area : NAN;
}

/* panels/force_FF.npy and panels/force_FF.key (the key of the inputs that made it). */
static int panel_paths(const im_scene *scene, int family, char *npy, char *key, size_t size)
{
    char relative[64];
    snprintf(relative, sizeof relative, "panels/force_%02d.npy", family);
    int status = scene_output_path(scene, relative, npy, size);
    snprintf(relative, sizeof relative, "panels/force_%02d.key", family);
    return status == IM_OK ? scene_output_path(scene, relative, key, size) : status;
}

/* The key of a panel made as kind: the state at load_star solved in two steps (by the table or
 * here), a history's state there, or the last of the frames' steps. */
static uint64_t panel_key(const im_scene *scene, int family, enum scene_result_kind kind)
{
    return scene_result_key(scene, family, scene->seeds[0], kind);
}

/* The checksum of a force field: its grid, spacing and values. */
static uint64_t force_checksum(const im_field *force)
{
    char text[96];
    uint64_t values = scene_checksum((const char *)force->data, sizeof(double) * im_field_count(force));
    int length = snprintf(text, sizeof text, "%d %d %.17g %016" PRIx64, force->nx, force->ny, force->delta, values);
    return scene_checksum(text, (size_t)length);
}

/* force_FF.npy, then force_FF.key: the key of what made it and the checksum of the force. */
static int write_panel(const im_scene *scene, int family, const im_field *force, enum scene_result_kind kind)
{
    char npy[IM_SCENE_PATH], key[IM_SCENE_PATH], text[48];
    int status = panel_paths(scene, family, npy, key, sizeof npy);
    int length = snprintf(text, sizeof text, "%016" PRIx64 " %016" PRIx64 "\n", panel_key(scene, family, kind),
                          force_checksum(force));
    if (status == IM_OK && unlink(key) != 0 && errno != ENOENT)
        status = im_fail(IM_EIO, "%s: cannot remove the stale key: %s", key, strerror(errno));
    if (status == IM_OK)
        status = im_npy_write(npy, force, IM_NPY_FLOAT64);
    return status == IM_OK ? im_write_file_atomic(key, text, (size_t)length) : status;
}

int scene_write_panel(const im_scene *scene, int family, const im_field *force)
{
    return write_panel(scene, family, force, SCENE_RESULT_AT_LOAD_STAR);
}

int scene_read_panel_force(const im_scene *scene, int family, im_field **force)
{
    char npy[IM_SCENE_PATH], key[IM_SCENE_PATH];
    int status = panel_paths(scene, family, npy, key, sizeof npy);
    return status == IM_OK ? im_npy_read(npy, force) : status;
}

/* What a fresh run takes as a panel that is not framed: the table's state, else a load-controlled
 * history's at load_star, else the panel's own two-step solve. */
static enum scene_result_kind fresh_panel_kind(const im_scene *scene)
{
    int from_history = !scene->table && scene_wants_histories(scene) && scene_load_star_step(scene) >= 0;
    return from_history ? SCENE_RESULT_HISTORY : SCENE_RESULT_AT_LOAD_STAR;
}

/* A force file an earlier run wrote, if its key is the one a fresh run would make and its checksum
 * holds; 0 if none (or stale, or damaged: then with a notice). */
static int read_panel(const im_scene *scene, const im_scene_run_options *options, int family, im_field **force)
{
    char npy[IM_SCENE_PATH], key_path[IM_SCENE_PATH];
    if (panel_paths(scene, family, npy, key_path, sizeof npy) != IM_OK)
        return 0;
    FILE *stream = fopen(key_path, "r");
    if (!stream)
        return 0;
    uint64_t key = 0, checksum = 0;
    int found = fscanf(stream, "%" SCNx64 " %" SCNx64, &key, &checksum) == 2;
    fclose(stream);
    if (!scene_key_matches(options, npy, found ? key : 0, panel_key(scene, family, fresh_panel_kind(scene))))
        return 0;
    if (im_npy_read(npy, force) != IM_OK)
        return scene_kept_damaged(options, npy, im_last_error());
    if (force_checksum(*force) != checksum) {
        im_field_free(*force);
        *force = NULL;
        return scene_kept_damaged(options, npy, "its values do not match the checksum in its .key file: edited");
    }
    scene_progress(options, "family %d: reusing %s", family, npy);
    return 1;
}

/* The force field of a family at load_star: reused from the frames, the table or a history of
 * this run, read back on --resume, or solved; then written at once with the key of what made it. */
static int panel_force(const im_scene *scene, const im_scene_run_options *options, int family,
                       const scene_reuse *reuse, const im_field *known_force, panel_result *r)
{
    int framed = known_force && family == scene_framed_family(scene);
    const im_field *known = framed ? known_force : reuse->force[family];
    enum scene_result_kind kind = framed  ? SCENE_RESULT_FRAMED
                                  : known ? reuse->force_kind[family]
                                          : SCENE_RESULT_AT_LOAD_STAR;
    int status = IM_OK;
    r->origin = SCENE_REUSED;
    if (known)
        status = im_field_clone(known, &r->force);
    else if (options->resume && read_panel(scene, options, family, &r->force)) {
        r->origin = SCENE_READ_BACK;
        return IM_OK;
    } else {
        r->origin = SCENE_SOLVED;
        status = solve_family(scene, options, family, &r->force);
    }
    return status == IM_OK ? write_panel(scene, family, r->force, kind) : status;
}

/* Every family's force, solved side by side, one thread each (inside the parallel loop the solver plans
 * and iterates single-threaded): on 2 cores that scales better than two threads on each solve in turn
 * (docs/benchmarks.md), and a panel is the same whatever the thread count. The roughest families, the
 * dearest, go first so that the threads finish together. A stop signal skips the panels not yet started. */
static int panel_forces(const im_scene *scene, const im_scene_run_options *options, const scene_reuse *reuse,
                        const im_field *known_force, panel_result *results)
{
    int count = scene->family_count, statuses[IM_SCENE_MAX_FAMILIES];
    char errors[IM_SCENE_MAX_FAMILIES][256];
#pragma omp parallel for schedule(dynamic, 1)
    for (int k = 0; k < count; ++k) {
        int i = count - 1 - k;
        statuses[i] = scene_stop_signal(options) ? IM_EINTERRUPTED
                                                 : panel_force(scene, options, i, reuse, known_force, &results[i]);
        if (statuses[i] != IM_OK)
            snprintf(errors[i], sizeof errors[i], "%s", im_last_error());
    }
    int finished = 0;
    for (int i = 0; i < count; ++i)
        finished += statuses[i] == IM_OK;
    for (int i = 0; i < count; ++i)
        if (statuses[i] != IM_OK && statuses[i] != IM_EINTERRUPTED)
            return im_fail(statuses[i], "%s", errors[i]);
    if (finished == count)
        return IM_OK;
    char where[64];
    snprintf(where, sizeof where, "after %d of %d panels", finished, count);
    return scene_interrupted(options, where);
}

static int write_results_csv(const im_scene *scene, const panel_result *results)
{
    im_atomic_file file;
    int status = scene_open_output(scene, "results.csv", &file);
    if (status != IM_OK)
        return status;
    fprintf(file.stream, "family,slope,seed,load,load_star,contact_patches,area_ratio,area_ratio_eq12\n");
    for (int i = 0; i < scene->family_count; ++i) {
        const panel_result *r = &results[i];
        fprintf(file.stream, "%d,%.17g,%llu,%.17g,%.17g,%ld,%.17g,%.17g\n", i, scene->slopes[i],
                (unsigned long long)scene->seeds[0], r->load, r->load_star, r->contact_patches, r->area_ratio,
                r->area_ratio_eq12);
    }
    return im_atomic_commit(&file);
}

/* The panels' forces (values IM_COLORMAP_FORCES) or their tensions (IM_COLORMAP_TENSIONS), each of which
 * the panels share as one norm. */
static im_colormap_range shared_range(const panel_result *results, int count, im_colormap_values values)
{
    im_colormap_range range = im_colormap_range_empty(values);
    for (int i = 0; i < count; ++i)
        im_colormap_range_add(&range, results[i].force);
    return range;
}

/* The panels' one force range: all their forces, or with [output] contact_panels_clip P the top P percent cut
 * (render --clip's, as frames_clip cuts the frames'), a needle asperity's force no longer making every other
 * patch one colour. */
static int panels_force_range(const im_scene *scene, const panel_result *results, im_colormap_range *forces)
{
    *forces = shared_range(results, scene->family_count, IM_COLORMAP_FORCES);
    if (!(scene->contact_panels_clip > 0.0))
        return IM_OK;
    im_field *fields[IM_SCENE_MAX_FAMILIES];
    for (int i = 0; i < scene->family_count; ++i)
        fields[i] = results[i].force;
    return im_colormap_range_clipped(IM_COLORMAP_FORCES, fields, scene->family_count, scene->contact_panels_clip,
                                     forces);
}

/* The panels' norms: one shared force norm and one tension norm (norms[0], norms[1]), and whether some
 * panel's forces lie below or above the force norm (*under, *over: the colour bar's triangles). */
static int panels_norms(const im_scene *scene, const panel_result *results, im_colormap norms[2], int *under,
                        int *over)
{
    im_colormap_range forces;
    const im_colormap_range tensions = shared_range(results, scene->family_count, IM_COLORMAP_TENSIONS);
    int status = panels_force_range(scene, results, &forces);
    norms[0] = scene_force_norm(scene, &forces);
    norms[1] = im_colormap_range_norm(&tensions, IM_COLORMAP_TENSION, NAN, NAN, 0);
    *under = scene->log_norm, *over = 0; /* a log norm's under colour holds the forces two decades down */
    for (int i = 0; i < scene->family_count; ++i)
        frame_extends(results[i].force, &norms[0], 1, under, over);
    return status;
}

/* Renders every panel with the norms (panels_norms) and the smooth contact circle. */
static int render_panels(const im_scene *scene, im_render_context *context, const panel_result *results,
                         im_image *images, const im_colormap norms[2])
{
    int status = IM_OK;
    for (int i = 0; i < scene->family_count && status == IM_OK; ++i) {
        const im_field *f = results[i].force;
        im_contact_style style = im_contact_style_default(f);
        style.colormap = norms[0];
        style.tension = norms[1];
        style.pixels_per_patch = f->nx <= 256 ? 2 : 1;
        style.circle_radius = sqrt(results[i].load_star / M_PI); /* A_smooth = N* delta^2 */
        status = im_render_contact_map(context, f, &style, &images[i]);
    }
    return status;
}

static int draw_figure(const im_scene *scene, const void *panels, const paper_file *file)
{
    (void)scene;
    return paper_figure_contact_panels(panels, file);
}

/* tension: the tension's norm, NULL where no panel has tension; extends: the force bar's triangles. */
static int write_panel_figure(const im_scene *scene, const im_image *images, const im_colormap *norm,
                              const im_colormap *tension, const int extends[2])
{
    char titles[IM_SCENE_MAX_FAMILIES][64];
    const char *title_of[IM_SCENE_MAX_FAMILIES];
    for (int i = 0; i < scene->family_count; ++i) {
        scene_family_title(scene, i, titles[i], sizeof titles[i]);
        title_of[i] = titles[i];
    }
    char norm_text[128];
    run_figure_norm_text(norm, norm_text, sizeof norm_text);
    paper_contact_panels panels = {.count = scene->family_count,
                                   .images = images,
                                   .titles = title_of,
                                   .norm = norm,
                                   .tension = tension,
                                   .extend_under = extends[0],
                                   .extend_over = extends[1],
                                   .norm_text = norm_text,
                                   .source = scene->path,
                                   .load_star = scene->load_star};
    return scene_write_png_pdf(scene, "contact_panels", draw_figure, &panels);
}

static int plot_density(const im_scene *scene, const panel_result *results)
{
    const im_field *forces[IM_SCENE_MAX_FAMILIES];
    double load_star[IM_SCENE_MAX_FAMILIES];
    for (int i = 0; i < scene->family_count; ++i) {
        forces[i] = results[i].force;
        load_star[i] = results[i].load_star;
    }
    return scene_plot_contact_density(scene, forces, load_star);
}

/* The panels' figure and the density plot, side by side (each is CPU work for one thread: layout, PNG
 * and PDF encoding); their errors are kept per output, as either may run on another thread. */
static int write_panel_outputs(const im_scene *scene, const panel_result *results, const im_image *images,
                               const im_colormap *norm, const im_colormap *tension, const int extends[2])
{
    int statuses[2] = {IM_OK, IM_OK};
    char errors[2][256] = {"", ""};
#pragma omp parallel for schedule(dynamic, 1)
    for (int k = 0; k < 2; ++k) {
        if (k == 0)
            statuses[k] = write_panel_figure(scene, images, norm, tension, extends);
        else if (scene_wants_plot(scene, IM_SCENE_PLOT_DENSITY))
            statuses[k] = plot_density(scene, results);
        if (statuses[k] != IM_OK)
            snprintf(errors[k], sizeof errors[k], "%s", im_last_error());
    }
    for (int k = 0; k < 2; ++k)
        if (statuses[k] != IM_OK)
            return im_fail(statuses[k], "%s", errors[k]);
    return IM_OK;
}

/* How many panels were solved, read back and reused. */
static void report_panels(const im_scene_run_options *options, const panel_result *results, int count)
{
    int counted[3] = {0};
    for (int i = 0; i < count; ++i)
        ++counted[results[i].origin];
    scene_report_origin_counts(options, "panels", counted);
}

int scene_run_panels(const im_scene *scene, const im_scene_run_options *options, im_render_context *context,
                     const scene_reuse *reuse, const im_field *known_force)
{
    char folder[IM_SCENE_PATH];
    int status = scene_output_path(scene, "panels", folder, sizeof folder);
    if (status == IM_OK)
        status = im_make_directories(folder);
    panel_result results[IM_SCENE_MAX_FAMILIES] = {0};
    im_image images[IM_SCENE_MAX_FAMILIES] = {0};
    if (status == IM_OK)
        status = panel_forces(scene, options, reuse, known_force, results);
    for (int i = 0; i < scene->family_count && status == IM_OK; ++i) {
        measure_panel(scene, &results[i]);
        results[i].area_ratio_eq12 = scene_eq12(scene, scene->slopes[i], NULL);
        scene_progress(options, "family %d: n_p = %ld, A/A_cone = %.4f (eq. 12: %.4f)", i, results[i].contact_patches,
                       results[i].area_ratio, results[i].area_ratio_eq12);
    }
    if (status == IM_OK)
        report_panels(options, results, scene->family_count);
    if (status == IM_OK)
        status = write_results_csv(scene, results);
    im_colormap norms[2];
    int extends[2] = {0, 0};
    if (status == IM_OK)
        status = panels_norms(scene, results, norms, &extends[0], &extends[1]);
    if (status == IM_OK)
        status = render_panels(scene, context, results, images, norms);
    int has_tension = status == IM_OK && shared_range(results, scene->family_count, IM_COLORMAP_TENSIONS).hi > 0.0;
    if (status == IM_OK)
        status = write_panel_outputs(scene, results, images, &norms[0], has_tension ? &norms[1] : NULL, extends);
    for (int i = 0; i < scene->family_count; ++i) {
        im_field_free(results[i].force);
        im_image_release(&images[i]);
    }
    return status;
}
