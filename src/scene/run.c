/* A scene run: checks before any work, then the stages in order (the headers beside it have the pieces). */
#include "indentmap/scene.h"
#include "scene/contents.h"
#include "scene/run_state.h"
#include "core/args.h"
#include "front/front.h"
#include "front/run_folder.h"

#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/status.h"
#include "scene/distributions.h"
#include "scene/ensemble.h"
#include "scene/flat_k.h"
#include "scene/frames.h"
#include "scene/frames3d.h"
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
#include "scene/surfaces.h"
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
    const char *need = at_n_star && (scene->contact_panels || scene->frames)
                           ? "[output] contact panels and frames are drawn"
                       : at_n_star && scene->distributions ? "[output] distributions are measured"
                       : steps_at_n_star                   ? "[loading] control = load takes steps"
                                                           : NULL;
    if (!need)
        return IM_OK;
    return im_fail(IM_EINVAL,
                   "%s: %s at N* = A(N) / delta^2, which a 2-D profile does not define (no "
                   "smooth-contact area): use control = displacement and its histories",
                   scene->path, need);
}

/* The [output] keys that shape only an output the scene may not draw. Given without it they do nothing: warned,
 * not refused, so that frames = no for a quick run needs no other key removed. */
typedef enum { SHAPES_FRAMES, SHAPES_ANIMATION, SHAPES_FRAMES3D, SHAPES_PANELS } shaped_output;

static const struct {
    const char *key;
    shaped_output output;
    const char *what;
} SHAPING_KEYS[] = {
    {"frame_count", SHAPES_FRAMES, "the frames (frames = yes)"},
    {"frames_slope", SHAPES_FRAMES, "the frames (frames = yes)"},
    {"frames_clip", SHAPES_FRAMES, "the frames (frames = yes)"},
    {"frame_scale", SHAPES_FRAMES, "the frames (frames = yes)"},
    {"frame_rate", SHAPES_ANIMATION, "the animations (animation = gif, mp4 or both)"},
    {"frame3d_width", SHAPES_FRAMES3D, "the 3-D frames (frames3d = yes)"},
    {"frame3d_height", SHAPES_FRAMES3D, "the 3-D frames (frames3d = yes)"},
    {"contact_panels_clip", SHAPES_PANELS, "the contact panels of the half-space (contact_panels = yes)"},
};

static int draws(const im_scene *scene, shaped_output output)
{
    switch (output) {
    case SHAPES_FRAMES: return scene->frames;
    case SHAPES_ANIMATION: return scene->animation != IM_ANIMATION_NONE;
    case SHAPES_FRAMES3D: return scene->frames3d;
    /* a periodic scene's panels are every step's map, drawn as indent --frames draws them: no clip */
    case SHAPES_PANELS: return scene->contact_panels && !scene->periodic;
    }
    return 0;
}

/* Whether the scene file gave key in section ("[output]\n"): its contents hold each key given as
 * "key = value" under its section's "[section]" line. */
static int key_given(const im_scene *scene, const char *section, const char *key)
{
    const size_t length = strlen(key);
    int in_section = 0;
    for (const char *line = scene->contents; line && *line; line = strchr(line, '\n')) {
        line += *line == '\n';
        if (*line == '[')
            in_section = strncmp(line, section, strlen(section)) == 0;
        else if (in_section && strncmp(line, key, length) == 0 && strncmp(line + length, " = ", 3) == 0)
            return 1;
    }
    return 0;
}

static void warn_unused_output_keys(const im_scene *scene, const im_scene_run_options *options)
{
    for (size_t i = 0; i < sizeof SHAPING_KEYS / sizeof SHAPING_KEYS[0]; ++i)
        if (!draws(scene, SHAPING_KEYS[i].output) && key_given(scene, "[output]\n", SHAPING_KEYS[i].key))
            scene_warn(options, "%s: [output] %s does nothing: it applies to %s, which this scene does not draw",
                       scene->path, SHAPING_KEYS[i].key, SHAPING_KEYS[i].what);
    /* the table, panels, frames and distributions solve at load_star: steps only make histories */
    if (!scene_wants_histories(scene) && key_given(scene, "[loading]\n", "steps"))
        scene_warn(options,
                   "%s: [loading] steps does nothing: the steps are the histories' (plots = fig5, fig6, fig7 or "
                   "sphere, or [punch] periodic = yes), which this scene does not solve; its table, panels, "
                   "frames and distributions are solved at load_star",
                   scene->path);
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
    if (scene->animation != IM_ANIMATION_NONE && !scene->frames)
        return im_fail(IM_EINVAL, "%s: [output] animation animates the frames: set frames = yes too", scene->path);
    if (scene->table && scene->punch != IM_PUNCH_CONE)
        return im_fail(IM_EINVAL, "%s: [output] table compares with eq. (12), which is for a cone", scene->path);
    im_indenter punch = scene_punch(scene);
    int status = punch.kind == IM_PUNCH_PROFILE_2D ? check_without_area(scene) : IM_OK;
    if (status != IM_OK)
        return status;
    status = im_indenter_check(&punch);
    if (status == IM_OK)
        status = scene_check_frames3d(scene);
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
    scene_reuse reuse = {.ranks = reuse_out->ranks};
    int status = scene_run_theory_plots(scene, options);
    if (status == IM_OK && scene->table && (status = check_stop(options, "the table")) == IM_OK)
        status = scene_run_table(scene, options, &reuse);
    if (status == IM_OK && scene_wants_plot(scene, IM_SCENE_PLOT_FLAT_K) &&
        (status = check_stop(options, "the flat contacts")) == IM_OK)
        status = scene_run_flat_k(scene, options, &reuse);
    if (status == IM_OK && scene->distributions && !scene->periodic &&
        (status = check_stop(options, "the distributions")) == IM_OK)
        status = scene_run_distributions(scene, options);
    if (status == IM_OK && scene_wants_histories(scene) && (status = check_stop(options, "the histories")) == IM_OK)
        status = scene_run_histories(scene, options, &reuse);
    if (status == IM_OK && (scene->contact_panels || scene->frames))
        status = run_rendered_stages(scene, options, &reuse);
    *reuse_out = reuse;
    return status;
}

/* The stages of a scene, or of each of its sweep points (a single process: refused with ranks). */
static int run_scene_stages(const im_scene *scene, const im_scene_run_options *options, const scene_ranks_run *ranks)
{
    if (scene_sweep_count(scene) > 1)
        return scene_run_sweep(scene, options, run_stages);
    scene_reuse reuse = {.ranks = ranks};
    int status = run_stages(scene, options, &reuse);
    scene_reuse_free(&reuse);
    return status;
}

/* scene_output_repair for run_folder.h's repair (state: the run options). */
static void repair_output(const char *path, const void *options) { scene_output_repair(options, path); }

/* What a scene writes into its output folder: anything under it (a sweep's points are subfolders). */
static run_folder_rules folder_rules(const im_scene *scene, const im_scene_run_options *options)
{
    return (run_folder_rules){.dir = scene->output_dir,
                              .lock_advice = "give this scene another [scene] output",
                              .wisdom_advice = "keep it elsewhere",
                              .repair = repair_output,
                              .repair_state = options};
}

/* The scene file, its surface files and its profile (resolved by scene_prepare) become inputs no write
 * may replace, the FFTW wisdom file may be neither one of them, nor in the output folder, nor
 * anything but wisdom, and the folder must be one the run can make and lock (run_folder.h). */
static int check_folder(const im_scene *scene, const im_scene_run_options *options)
{
    const char **inputs = calloc((size_t)scene->file_count + 2, sizeof *inputs);
    char(*surfaces)[IM_SCENE_PATH] = malloc(sizeof *surfaces * (size_t)(scene->file_count + 1));
    int status = inputs && surfaces ? IM_OK : im_fail(IM_ENOMEM, "%s: allocation of the inputs failed", scene->path);
    for (int i = 0; i < scene->file_count && status == IM_OK; ++i) {
        status = im_scene_file_path(scene, i, surfaces[i], sizeof surfaces[i]);
        inputs[i + 2] = surfaces[i];
    }
    im_solver_options solver = scene_solver_options(scene);
    const run_folder_rules rules = folder_rules(scene, options);
    if (status == IM_OK) {
        inputs[0] = scene->path;
        inputs[1] = scene->profile_file[0] ? scene->profile_file : NULL;
        status = run_folder_check(&rules, inputs, scene->file_count + 2, &solver);
    }
    if (status == IM_OK)
        status = run_folder_probe(&rules);
    free(surfaces);
    free(inputs);
    return status;
}

/* Locks the output folder (a stale lock taken over is a warning) and removes the temporary files a
 * killed run left in it. */
static int open_folder(const im_scene *scene, const im_scene_run_options *options, run_folder *folder)
{
    const run_folder_rules rules = folder_rules(scene, options);
    /* table/, histories/, ...; a sweep's are one level further down, in its points' folders */
    int status = run_folder_open(&rules, scene_sweep_count(scene) > 1 ? 2 : 1, folder);
    if (folder->lock.stale_pid > 0)
        scene_warn(options, "taking over the stale lock %s of pid %ld, which no longer runs", folder->lock.path,
                   folder->lock.stale_pid);
    int removed = folder->temporaries_removed;
    if (removed > 0)
        scene_progress(options, "removed %d temporary file%s an interrupted run left in %s", removed,
                       removed == 1 ? "" : "s", scene->output_dir);
    return status;
}

/* OUTPUT/index.html over what the run left, even after a failure or an interruption; the run's own
 * error, if any, stays the one returned. */
static int write_viewer_page(const im_scene *scene, const run_folder *folder, int status)
{
    char title[IM_SCENE_PATH + 96];
    snprintf(title, sizeof title, "indentmap run: %s (%s)", scene->name, scene->path);
    return run_folder_page(folder, title, scene->page_embed, status);
}

static int run_measured(const im_scene *scene, const im_scene_run_options *options, const scene_ranks_run *ranks);

/* OUTPUT/run.json as the run starts, "running" (a damaged one removed first; its end: run_folder_record). */
static int start_record(const im_scene *scene, const im_scene_run_options *options, json_t **record)
{
    char path[IM_SCENE_PATH];
    int status = im_path_join(path, sizeof path, scene->output_dir, "run.json");
    if (status == IM_OK)
        scene_output_repair(options, path);
    if (status == IM_OK)
        status = scene_record_create(scene, record);
    if (status == IM_OK && (status = run_record_start(scene->output_dir, *record)) != IM_OK) {
        json_decref(*record);
        *record = NULL;
    }
    return status;
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
        return im_fail(IM_EINVAL,
                       "%s: '%s' is %zu bytes once resolved against the folder of the scene, longer "
                       "than %zu: %s",
                       key, written, length, size - 1, scene->path); /* the key first: a long path is cut */
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

const im_profile *scene_profile(const im_scene *scene) { return scene->run ? scene->run->profile : NULL; }

void scene_prepared_free(im_scene *prepared)
{
    if (prepared && prepared->run) {
        im_profile_free(prepared->run->profile);
        free(prepared->run);
    }
    free(prepared);
}

/* What was taken where a surface file is silent (formats.h: im_surface_read_info.assumed), said as indent
 * and surface --stats say it. */
static void warn_assumed_units(const im_scene *measured, const im_scene_run_options *options)
{
    for (int i = 0; i < measured->file_count; ++i) {
        if (!measured->run->file_assumed[i][0])
            continue;
        char file[IM_SCENE_PATH];
        im_scene_file_path(measured, i, file, sizeof file);
        scene_warn(options, "%s: %s: %s", measured->path, file, measured->run->file_assumed[i]);
    }
}

int scene_prepare(const im_scene *scene, im_scene **prepared)
{
    *prepared = NULL;
    im_scene *copy = malloc(sizeof *copy);
    scene_run_state *state = calloc(1, sizeof *state);
    if (!copy || !state) {
        free(copy);
        free(state);
        return im_fail(IM_ENOMEM, "%s: allocation of the scene's run failed", scene->path);
    }
    *copy = *scene;
    copy->run = state;
    int status = scene_measure_files(copy, state);
    if (status == IM_OK)
        status = read_profile(copy, &state->profile);
    if (status != IM_OK) {
        scene_prepared_free(copy);
        return status;
    }
    *prepared = copy;
    return IM_OK;
}

int im_scene_run(const im_scene *scene, const im_scene_run_options *options)
{
    ARG_REQUIRE(scene, "scene");
    ARG_REQUIRE(options, "options");
    return scene_run(scene, options, NULL);
}

int scene_prepare_run(const im_scene *scene, const im_scene_run_options *options, im_scene **measured)
{
    int status = scene_prepare(scene, measured);
    if (status == IM_OK)
        warn_assumed_units(*measured, options);
    if (status == IM_OK && (*measured)->file_count > 0)
        scene_progress(options, "surface files: h'rms = %.6g (%s, of the surfaces as solved%s)",
                       (*measured)->slopes[0], slope_definition_name((*measured)->run->file_slope_definition),
                       (*measured)->file_count > 1 ? ", root mean square over the files" : "");
    return status;
}

/* Run on the prepared copy: the caller's scene stays as parsed. */
int scene_run(const im_scene *scene, const im_scene_run_options *given, const scene_ranks_run *ranks)
{
    scene_callbacks callbacks;
    im_scene_run_options run = scene_callbacks_begin(given, &callbacks);
    const im_scene_run_options *options = &run;
    im_scene *measured = NULL;
    int status = scene_prepare_run(scene, options, &measured);
    if (status == IM_OK)
        status = run_measured(measured, options, ranks);
    scene_prepared_free(measured);
    scene_callbacks_end(&callbacks);
    return status;
}

/* A scene that renders opens its OpenGL context after every solve: opened and closed here, before any
 * work, so that a machine without one refuses the run (and run --check) at once. */
static int check_renderer(const im_scene *scene, const im_scene_run_options *options)
{
    im_render_context *context = NULL;
    int status = im_scene_renders(scene) ? im_render_open((im_render_backend)options->backend, &context) : IM_OK;
    im_render_close(context);
    return status;
}

int scene_check_before_work(const im_scene *scene, const im_scene_run_options *options, int ranked,
                            scene_limits *limits)
{
    int status = check_runnable(scene);
    if (status == IM_OK)
        warn_unused_output_keys(scene, options);
    if (status == IM_OK && ranked && scene_sweep_count(scene) > 1)
        status = im_fail(IM_EINVAL,
                         "%s: a sweep (a list of alpha, hurst or lambda_s) runs in a single process; "
                         "run it without mpirun",
                         scene->path);
    if (status == IM_OK)
        status = scene_sweep_check_fig2(scene);
    if (status == IM_OK)
        status = check_folder(scene, options);
    if (status == IM_OK)
        status = scene_check_limits(scene, options, limits);
    return status == IM_OK ? check_renderer(scene, options) : status;
}

static int run_measured(const im_scene *scene, const im_scene_run_options *options, const scene_ranks_run *ranks)
{
    scene_limits limits;
    int status = scene_check_before_work(scene, options, ranks != NULL, &limits);
    run_folder folder = {.lock = {.fd = -1}};
    if (status == IM_OK)
        status = open_folder(scene, options, &folder);
    im_scene_run_options checked = *options;
    if (status == IM_OK && checked.resume && scene_plans_changed(scene, options))
        checked.resume = 0; /* the kept results' last bits are not this run's: a fresh run */
    options = &checked;
    json_t *record = NULL;
    if (status == IM_OK)
        status = start_record(scene, options, &record);
    if (status == IM_OK && (status = scene_outputs_open(scene, options)) == IM_OK) {
        if (ranks) /* an MPI run: the ranks solve the members first */
            status = ranks->solve_members(scene, options, ranks->data);
        if (status == IM_OK)
            status = run_scene_stages(scene, options, ranks);
        int recorded = scene_plans_record(scene); /* also after an interruption: what was solved is kept */
        status = scene_outputs_close(scene, status == IM_OK ? recorded : status);
    }
    if (record) { /* its status, the run's error kept; no step count (a scene counts none) */
        status = run_folder_record(&folder, record, -1, status);
        status = write_viewer_page(scene, &folder, status);
        json_decref(record);
    }
    run_folder_close(&folder);
    return status;
}
