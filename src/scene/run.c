/* A scene run: checks before any work, then the stages in order (the headers beside it have the pieces). */
#include "indentmap/scene.h"
#include "core/args.h"

#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/status.h"
#include "indentmap/viewer.h"
#include "scene/distributions.h"
#include "scene/ensemble.h"
#include "scene/flat_k.h"
#include "scene/frames.h"
#include "scene/histories.h"
#include "scene/limits.h"
#include "scene/manifest.h"
#include "scene/outputs.h"
#include "scene/panels.h"
#include "scene/periodic.h"
#include "scene/plans.h"
#include "scene/plots.h"
#include "scene/progress.h"
#include "scene/punch.h"
#include "scene/record.h"
#include "scene/sweep.h"
#include "scene/table.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* What a punch without a smooth-contact area (a 2-D profile) cannot run: everything given as
 * N* = A(N) / delta^2, which needs that area to find its load. */
static int check_without_area(const im_scene *scene)
{
    const int at_n_star = !scene->periodic; /* a periodic scene's panels and distributions are at its steps */
    const int steps_at_n_star = scene->control == IM_CONTROL_LOAD && !scene_steps_are_loads(scene);
    const char *need = at_n_star && (scene->contact_panels || scene->frames) ? "[output] contact panels and frames are drawn"
                       : at_n_star && scene->distributions                   ? "[output] distributions are measured"
                       : steps_at_n_star                                     ? "[loading] control = load takes steps"
                                                                             : NULL;
    if (!need)
        return IM_OK;
    return im_fail(IM_EINVAL, "%s: %s at N* = A(N) / delta^2, which a 2-D profile does not define (no "
                   "smooth-contact area): use control = displacement and its histories", scene->path, need);
}

static int check_runnable(const im_scene *scene)
{
    if ((scene->contact_panels || scene->frames || scene->table || scene->distributions) && !scene->periodic &&
        !(scene->load_star > 0.0))
        return im_fail(IM_EINVAL, "%s: contact panels, frames, tables and distributions need [loading] load_star > 0",
                       scene->path);
    if (scene->frames3d && !scene->frames)
        return im_fail(IM_EINVAL, "%s: [output] frames3d draws the frames' history in 3-D: set frames = yes too",
                       scene->path);
    if (scene->table && scene->punch != IM_PUNCH_CONE)
        return im_fail(IM_EINVAL, "%s: [output] table compares with eq. (12), which is for a cone", scene->path);
    im_indenter punch = scene_punch(scene);
    int status = punch.kind == IM_PUNCH_PROFILE_2D ? check_without_area(scene) : IM_OK;
    if (status != IM_OK)
        return status;
    status = im_indenter_check(&punch);
    return status == IM_OK ? scene_check_plots(scene) : status;
}

/* Between stages: IM_EINTERRUPTED once a signal has asked to stop. */
static int check_stop(const im_scene_run_options *options, const char *next_stage)
{
    char where[96];
    snprintf(where, sizeof where, "before %s", next_stage);
    return scene_stop_signal(options) ? scene_interrupted(options, where) : IM_OK;
}

/* Frames and panels, which need an OpenGL context. */
static int run_rendered_stages(const im_scene *scene, const im_scene_run_options *options, const scene_reuse *reuse)
{
    int status = check_stop(options, "the frames and panels");
    if (status != IM_OK)
        return status;
    im_render_context *context = NULL;
    status = im_render_open((im_render_backend)options->backend, &context);
    if (status != IM_OK)
        return status;
    scene_progress(options, "rendering with %s (%s)", im_render_backend_name(context),
                   im_render_gl_renderer(context));
    im_field *framed_force = NULL;
    if (scene->frames)
        status = scene_run_frames(scene, options, context, &framed_force);
    if (status == IM_OK && scene->contact_panels && scene->periodic)
        status = scene_periodic_draw_panels(scene, reuse, context);
    else if (status == IM_OK && scene->contact_panels)
        status = scene_run_panels(scene, options, context, reuse, framed_force);
    im_field_free(framed_force);
    im_render_close(context);
    return status;
}

/* The stages in order; what one solves at load_star, a later one reuses (nothing solved twice).
 * What they solved is left in *reuse for a sweep (sweep.c); the caller frees it. */
static int run_stages(const im_scene *scene, const im_scene_run_options *options, scene_reuse *reuse_out)
{
    scene_reuse reuse = {0};
    int status = scene_run_theory_plots(scene, options);
    if (status == IM_OK && scene->table && (status = check_stop(options, "the table")) == IM_OK)
        status = scene_run_table(scene, options, &reuse);
    if (status == IM_OK && scene_wants_plot(scene, IM_SCENE_PLOT_FLAT_K) && (status = check_stop(options, "the flat contacts")) == IM_OK)
        status = scene_run_flat_k(scene, options, &reuse);
    if (status == IM_OK && scene->distributions && !scene->periodic && (status = check_stop(options, "the distributions")) == IM_OK)
        status = scene_run_distributions(scene, options);
    if (status == IM_OK && scene_wants_histories(scene) && (status = check_stop(options, "the histories")) == IM_OK)
        status = scene_run_histories(scene, options, &reuse);
    if (status == IM_OK && (scene->contact_panels || scene->frames))
        status = run_rendered_stages(scene, options, &reuse);
    *reuse_out = reuse;
    return status;
}

/* The stages of a scene, or of each of its sweep points. */
static int run_scene_stages(const im_scene *scene, const im_scene_run_options *options)
{
    if (scene_sweep_count(scene) > 1)
        return scene_run_sweep(scene, options, run_stages);
    scene_reuse reuse = {0};
    int status = run_stages(scene, options, &reuse);
    scene_reuse_free(&reuse);
    return status;
}

/* The scene file and its surface files become inputs no write may replace (io.h: the output
 * guard), and the FFTW wisdom file (scene->wisdom_path) may be neither one of them, nor in the output
 * folder, nor anything but wisdom. */
static int protect_inputs(const im_scene *scene)
{
    int status = im_output_protect(scene->path);
    char surface[IM_SCENE_PATH];
    for (int i = 0; i < scene->file_count && status == IM_OK; ++i) {
        status = im_scene_file_path(scene, i, surface, sizeof surface);
        if (status == IM_OK)
            status = im_output_protect(surface);
    }
    im_solver_options solver = scene_solver_options(scene);
    if (status == IM_OK)
        status = im_solver_wisdom_check(&solver);
    const char *wisdom = im_solver_wisdom_file(&solver);
    char folder[PATH_MAX], file[PATH_MAX];
    int resolved = wisdom && im_path_absolute(scene->output_dir, folder, sizeof folder) == IM_OK &&
                   im_path_absolute(wisdom, file, sizeof file) == IM_OK;
    size_t length = resolved ? strlen(folder) : 0;
    if (status == IM_OK && resolved && strncmp(file, folder, length) == 0 && file[length] == '/')
        status = im_fail(IM_EINVAL, "the FFTW wisdom file %s lies in the output folder %s, where this run writes: "
                         "keep it elsewhere", wisdom, scene->output_dir);
    return status;
}

/* Temporary files a killed run left in the (locked) output folder. */
static void remove_stale_temporaries(const im_scene *scene, const im_scene_run_options *options)
{
    /* table/, histories/, ...; a sweep's are one level further down, in its points' folders */
    int removed = im_folder_remove_temporaries(scene->output_dir, scene_sweep_count(scene) > 1 ? 2 : 1);
    if (removed > 0)
        scene_progress(options, "removed %d temporary file%s an interrupted run left in %s", removed,
                       removed == 1 ? "" : "s", scene->output_dir);
}

/* OUTPUT/index.html over what the run left (viewer.h), even after a failure or an interruption;
 * the run's own error, if any, stays the one returned. */
static int write_viewer_page(const im_scene *scene, const im_scene_run_options *options, int status)
{
    char message[1024], title[IM_SCENE_PATH + 96], page[IM_SCENE_PATH];
    snprintf(message, sizeof message, "%s", im_last_error());
    if (im_path_join(page, sizeof page, scene->output_dir, "index.html") == IM_OK)
        scene_output_repair(options, page);
    snprintf(title, sizeof title, "indentmap run: %s (%s)", scene->name, scene->path);
    const im_viewer_options page_options = {.embed_images = scene->page_embed};
    int written = im_viewer_write_with(scene->output_dir, title, &page_options);
    if (status == IM_OK)
        return written;
    im_fail(status, "%s", message);
    return status;
}

static int run_measured(im_scene *scene, const im_scene_run_options *options);

/* OUTPUT/run.json (a damaged one removed first), then the noting of the run's outputs from its time. */
static int write_record(im_scene *scene, const im_scene_run_options *options)
{
    char record[IM_SCENE_PATH];
    int status = im_path_join(record, sizeof record, scene->output_dir, "run.json");
    if (status == IM_OK)
        scene_output_repair(options, record);
    if (status == IM_OK)
        status = scene_write_record(scene);
    return status == IM_OK ? scene_outputs_open(scene, options) : status;
}

/* A path written under key resolved against the scene file's folder into out (size bytes):
 * IM_EINVAL naming the key when it does not fit (im_scene_resolve_path would cut it short). Both
 * the scene's path and the written one are shorter than IM_SCENE_PATH, so `whole` holds any. */
static int resolve_key_path(const im_scene *scene, const char *key, const char *written, char *out, size_t size)
{
    char whole[2 * IM_SCENE_PATH];
    im_scene_resolve_path(scene, written, whole, sizeof whole);
    size_t length = strlen(whole);
    if (length >= size)
        return im_fail(IM_EINVAL, "%s: '%s' is %zu bytes once resolved against the folder of the scene, longer "
                       "than %zu: %s", key, written, length, size - 1, scene->path); /* the key first: a long path is cut */
    memcpy(out, whole, length + 1);
    return IM_OK;
}

/* [punch] profile, resolved once (the copy's profile_file then holds the resolved path, which the
 * input protection and run.json use) and read on the scene's grid (a 2-D profile takes its
 * spacing): shape = profile and a profile file go together. */
static int read_profile(im_scene *scene, im_profile **out)
{
    if ((scene->punch == IM_PUNCH_PROFILE) != (scene->profile_file[0] != '\0'))
        return im_fail(IM_EINVAL, "%s: [punch] shape = profile and profile = FILE go together", scene->path);
    if (!scene->profile_file[0])
        return IM_OK;
    char path[IM_SCENE_PATH];
    int status = resolve_key_path(scene, "[punch] profile", scene->profile_file, path, sizeof path);
    if (status != IM_OK)
        return status;
    memcpy(scene->profile_file, path, sizeof path);
    status = im_profile_read(scene->profile_file, scene->surface.delta, out);
    return status == IM_OK ? IM_OK : im_fail_context(status, "%s: [punch] profile", scene->path);
}

int scene_prepare(const im_scene *scene, im_scene **prepared, im_profile **profile)
{
    *prepared = NULL;
    *profile = NULL;
    im_scene *copy = malloc(sizeof *copy);
    if (!copy)
        return im_fail(IM_ENOMEM, "%s: allocation of the scene failed", scene->path);
    *copy = *scene;
    int status = im_scene_measure_files(copy);
    if (status == IM_OK)
        status = read_profile(copy, profile);
    if (status != IM_OK) {
        free(copy);
        return status;
    }
    copy->profile = *profile;
    copy->outputs = NULL;
    *prepared = copy;
    return IM_OK;
}

static int run_measured(im_scene *scene, const im_scene_run_options *options);

/* Run on the prepared copy: the caller's scene stays as parsed. */
int im_scene_run(const im_scene *scene, const im_scene_run_options *given)
{
    ARG_REQUIRE(scene, "scene");
    ARG_REQUIRE(given, "options");
    scene_callbacks callbacks;
    im_scene_run_options run = scene_callbacks_begin(given, &callbacks);
    const im_scene_run_options *options = &run;
    im_scene *measured = NULL;
    im_profile *profile = NULL;
    int status = scene_prepare(scene, &measured, &profile);
    if (status == IM_OK && measured->file_count > 0)
        scene_progress(options, "surface files: h'rms = %.6g (forward differences of the surfaces as solved%s)",
                       measured->slopes[0], measured->file_count > 1 ? ", root mean square over the files" : "");
    if (status == IM_OK)
        status = run_measured(measured, options);
    free(measured);
    im_profile_free(profile); /* after the run that borrowed it */
    scene_callbacks_end(&callbacks);
    return status;
}

static int run_measured(im_scene *scene, const im_scene_run_options *options)
{
    int status = check_runnable(scene);
    if (status == IM_OK)
        status = protect_inputs(scene);
    if (status == IM_OK && scene->profile_file[0]) /* resolved by scene_prepare */
        status = im_output_protect(scene->profile_file);
    if (status == IM_OK)
        status = scene_check_limits(scene, options);
    if (status == IM_OK)
        status = im_make_directories(scene->output_dir);
    scene_lock lock = {.fd = -1};
    if (status == IM_OK)
        status = scene_lock_acquire(scene, options, &lock);
    if (status == IM_OK)
        remove_stale_temporaries(scene, options);
    im_scene_run_options checked = *options;
    if (status == IM_OK && checked.resume && scene_plans_changed(scene, options))
        checked.resume = 0; /* the kept results' last bits are not this run's: a fresh run */
    options = &checked;
    if (status == IM_OK)
        status = write_record(scene, options);
    const scene_ranks_run *ranks = scene_get_ranks_run(); /* an MPI run: the ranks solve the members first */
    if (status == IM_OK && ranks && scene_sweep_count(scene) > 1)
        status = im_fail(IM_EINVAL, "%s: a sweep (a list of alpha, hurst or lambda_s) runs in a single process; "
                         "run it without mpirun", scene->path);
    if (status == IM_OK) {
        if (ranks)
            status = ranks->solve_members(scene, options, ranks->data);
        if (status == IM_OK)
            status = run_scene_stages(scene, options);
        int recorded = scene_plans_record(scene); /* also after an interruption: what was solved is kept */
        status = scene_outputs_close(scene, status == IM_OK ? recorded : status);
        status = write_viewer_page(scene, options, status);
    }
    scene_lock_release(&lock);
    return status;
}
