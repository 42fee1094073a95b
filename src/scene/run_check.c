/* `indentmap run --check` (scene.h: im_scene_check): what a run of a scene would do, told before any work.
 * Whether it would run is decided by the run's own preparation and checks (run.c: scene_prepare_run,
 * scene_check_before_work; limits.c's estimates); the report then says what the run reads, solves and
 * writes. Nothing is solved and nothing written. */
#include "indentmap/scene.h"
#include "scene/contents.h"
#include "scene/run_state.h"
#include "core/args.h"
#include "front/front.h"

#include "indentmap/status.h"
#include "scene/ensemble.h"
#include "scene/frames.h"
#include "scene/histories.h"
#include "scene/periodic.h"
#include "scene/plans.h"
#include "scene/plots.h"
#include "scene/progress.h"
#include "scene/punch.h"
#include "scene/sweep.h"
#include "scene/table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const double MIB = 1048576.0;

/* ---- what the run reads ---- */

static void report_files(FILE *out, const im_scene *scene)
{
    for (int i = 0; i < scene->file_count; ++i) {
        char path[IM_SCENE_PATH];
        im_scene_file_path(scene, i, path, sizeof path);
        fprintf(out, "  file %s: %d x %d, spacing %g %s, h'rms %.6g (%s)%s%s\n", path, scene->surface.nx,
                scene->surface.ny, scene->surface.delta, scene->file_unit[0] ? scene->file_unit : "(no unit given)",
                scene->run->file_slopes[i], slope_definition_name(scene->run->file_slope_definition),
                scene->run->file_resampled[i] ? ", resampled onto square pixels" : "",
                scene->run->file_assumed[i][0] ? ", assumed: " : "");
        if (scene->run->file_assumed[i][0])
            fprintf(out, "    %s\n", scene->run->file_assumed[i]);
    }
}

static void report_inputs(FILE *out, const im_scene *scene)
{
    fprintf(out, "inputs (read as the run reads them):\n  scene %s%s%s\n", scene->path,
            scene->from_record[0] ? ", from the record " : "", scene->from_record);
    report_files(out, scene);
    if (scene->profile_file[0])
        fprintf(out, "  [punch] profile %s\n", scene->profile_file);
    fprintf(out, "surfaces: ");
    if (scene->file_count > 0)
        fprintf(out, "%d file%s, one family\n", scene->file_count, scene->file_count == 1 ? "" : "s");
    else
        fprintf(out, "%d x %d grid, spacing %g, generated (H = %g, lambda_s = %g, lambda_r = %g)\n",
                scene->surface.nx, scene->surface.ny, scene->surface.delta, scene->surface.hurst,
                scene->surface.lambda_s, scene->surface.lambda_r);
    for (int f = 0; f < scene->family_count && scene->file_count == 0; ++f)
        fprintf(out, "  family %02d: h'rms %g, %d surface%s\n", f, scene->slopes[f],
                scene->slopes[f] == 0.0 ? 1 : scene->seed_count,
                scene->slopes[f] == 0.0 || scene->seed_count == 1 ? "" : "s");
}

/* ---- what the run solves ---- */

static const char *control_name(const im_scene *scene)
{
    return scene->control == IM_CONTROL_DISPLACEMENT ? "approaches"
           : scene->control == IM_CONTROL_MEAN_GAP   ? "mean gaps"
           : scene->periodic                         ? "mean pressures"
           : scene_steps_are_loads(scene)            ? "loads N"
                                                     : "N* values";
}

static void report_solves(FILE *out, const im_scene *scene, int members, const scene_limits *limits)
{
    if (limits->window_nx != limits->nx || limits->window_ny != limits->ny)
        fprintf(out, "solves (each on a window of at most %d x %d of the %d x %d grid):\n", limits->window_nx,
                limits->window_ny, limits->nx, limits->ny);
    else
        fprintf(out, "solves (each on the whole %d x %d grid):\n", limits->nx, limits->ny);
    if (scene->table)
        fprintf(out, "  table: %d cold solve%s at N* = %g (two load steps each)\n", members, members == 1 ? "" : "s",
                scene->load_star);
    if (scene_wants_plot(scene, IM_SCENE_PLOT_FLAT_K))
        fprintf(out, "  flat_k: the flat contacts of each rough family\n");
    if (scene->distributions && !scene->periodic)
        fprintf(out, "  distributions: %d cold solve%s at N* = %g (each family's first surface)\n",
                scene->family_count, scene->family_count == 1 ? "" : "s", scene->load_star);
    if (scene_wants_histories(scene))
        fprintf(out, "  histories: %d surface%s x %d step%s (%s%s%s)\n", members, members == 1 ? "" : "s",
                scene->step_count, scene->step_count == 1 ? "" : "s", control_name(scene),
                scene->periodic ? ", periodic cells" : "", scene->adhesion_work > 0 ? ", adhesive" : "");
    if (scene->frames)
        fprintf(out, "  frames: a history of %d load steps to N* = %g on family %02d's first surface\n",
                scene->frame_count, scene->load_star, scene_framed_family(scene));
    if (scene->contact_panels && !scene->periodic)
        fprintf(out,
                "  contact panels: %d state%s at N* = %g (each family's first surface; taken from the table, "
                "a history or the frames where they have it)\n",
                scene->family_count, scene->family_count == 1 ? "" : "s", scene->load_star);
    if (scene_sweep_count(scene) > 1)
        fprintf(out, "  each of the %d sweep points solves the above on its own (see below)\n",
                scene_sweep_count(scene));
}

/* ---- the estimates the run judges (limits.c) ---- */

static void report_estimates(FILE *out, const im_scene *scene, const scene_limits *l,
                             const im_scene_run_options *options)
{
    fprintf(out, "estimates (the run's own, upper bounds of the largest terms: docs/reliability.md, \"Limits, before "
                 "any work\"):\n");
    fprintf(out, "  memory: about %.1f MiB (%d solve%s at once, %.1f MiB each for the %s engine's plan and fields), ",
            l->memory_needed / MIB, l->at_once, l->at_once == 1 ? "" : "s", l->solve_bytes / MIB,
            l->gpu ? "GPU" : "CPU");
    if (l->memory_available > 0)
        fprintf(out, "%.1f MiB available\n", l->memory_available / MIB);
    else
        fprintf(out, "the memory available is unknown\n");
    if (l->address_space > 0)
        fprintf(out, "  address space: about %.1f MiB with %.1f MiB reserved by threads%s, limit %.1f MiB\n",
                (l->memory_needed + l->address_reserved) / MIB, l->address_reserved / MIB,
                scene->contact_panels || scene->frames ? " and the renderer" : "", l->address_space / MIB);
    fprintf(out, "  disk: about %.1f MiB of outputs (the largest, %s, %.1f MiB), ", l->disk_total / MIB,
            l->disk_largest_name ? l->disk_largest_name : "-", l->disk_largest / MIB);
    if (l->disk_free >= 0)
        fprintf(out, "%.1f MiB free on %s%s\n", l->disk_free / MIB, l->disk_folder,
                options->no_space_check ? " (not checked: IM_NO_SPACE_CHECK=1)" : "");
    else
        fprintf(out, "the free space of %s is unknown\n", l->disk_folder);
    fprintf(out, "  time: not estimated (docs/scenes.md, \"Checking a scene\")\n");
}

/* ---- what the run writes ---- */

/* The output lines of one scene (or sweep point) under `prefix` ("" or "POINT/"). */
typedef struct output_list {
    FILE *out;
    const char *prefix;
    const im_scene_run_options *options;
    int resumable; /* 0 when --resume would solve everything again (plans.h: scene_plans_changed) */
    int *status;   /* the first error of a listing (members or sweep points not made), for the report */
} output_list;

/* Keeps the first error of a listing in *o->status. */
static void list_failed(const output_list *o, int status)
{
    if (*o->status == IM_OK)
        *o->status = status;
}

static void list_file(const output_list *o, const char *name, const char *note)
{
    fprintf(o->out, "  %s%s%s%s\n", o->prefix, name, note[0] ? "  " : "", note);
}

static void list_figure(const output_list *o, const char *name)
{
    char file[96];
    snprintf(file, sizeof file, "%s.png", name);
    list_file(o, file, "");
    snprintf(file, sizeof file, "%s.pdf", name);
    list_file(o, file, "");
}

/* Whether --resume would read member m of a stage back (kept: the stage's test of its kept file, whole
 * and of these inputs); what is wrong with a kept one goes to options->log as the run says it. */
typedef int (*member_kept)(const im_scene *scene, const im_scene_run_options *options, scene_member *m);

static const char *resume_note(const output_list *o, const im_scene *scene, member_kept kept, scene_member *m)
{
    return o->resumable && kept(scene, o->options, m) ? "(kept: --resume reuses it)" : "";
}

static void list_members(const output_list *o, const im_scene *scene, const char *folder, member_kept kept)
{
    scene_member *members = NULL;
    int count = 0;
    int status = scene_ensemble_members(scene, &members, &count);
    if (status != IM_OK) {
        list_failed(o, status);
        return;
    }
    for (int i = 0; i < count; ++i) {
        char name[96];
        snprintf(name, sizeof name, "%s/member_%02d_%llu.csv", folder, members[i].family,
                 (unsigned long long)members[i].seed);
        list_file(o, name, resume_note(o, scene, kept, &members[i]));
    }
    scene_members_free(members, count);
}

/* A periodic scene's fields of each step (front.h: step_fields_write's names). */
static void list_step_fields(const output_list *o, const im_scene *scene)
{
    char name[160] = "panels/family_FF/{";
    for (int i = 0; i < step_field_count(scene->hardness); ++i) {
        size_t length = strlen(name);
        snprintf(name + length, sizeof name - length, "%s%.*s", i ? "," : "", (int)strlen(STEP_FIELD_PREFIXES[i]) - 1,
                 STEP_FIELD_PREFIXES[i]); /* without its "_" */
    }
    strncat(name, "}_NNNN.npy{,.json}", sizeof name - strlen(name) - 1);
    list_file(o, name, "(every step of each family's first surface)");
}

static void list_histories(const output_list *o, const im_scene *scene)
{
    list_members(o, scene, "histories", scene_history_member_kept);
    if (scene->periodic && scene->contact_panels) /* periodic.h: scene_periodic_step_files */
        list_step_fields(o, scene);
    if (scene->periodic && scene->distributions)
        list_file(o, "distributions/family_FF_NNNN_{gaps,patches,patch_list}.csv",
                  "(every step of each family's first surface)");
    if (scene_histories_unload(scene))
        list_file(o, "indentation/member_FF_SEED.csv", "(one a surface)");
    if (scene->periodic && scene_periodic_fits_k(scene))
        list_file(o, "k_fit.csv", "");
    static const struct {
        enum im_scene_plot plot;
        const char *name;
    } FIGURES[] = {{IM_SCENE_PLOT_FIG5, "fig5"},
                   {IM_SCENE_PLOT_FIG6, "fig6"},
                   {IM_SCENE_PLOT_FIG7, "fig7"},
                   {IM_SCENE_PLOT_SPHERE, "sphere_regimes"}};
    for (size_t i = 0; i < sizeof FIGURES / sizeof *FIGURES; ++i) {
        if (!scene_wants_plot(scene, FIGURES[i].plot))
            continue;
        if (FIGURES[i].plot == IM_SCENE_PLOT_FIG7)
            list_file(o, "fig7.csv", "");
        list_figure(o, FIGURES[i].name);
    }
}

static void list_rendered(const output_list *o, const im_scene *scene)
{
    if (scene->frames) {
        list_file(o, "frames/contact_NNNN.png, frames/height_NNNN.png", "(NNNN = 0000 to the frame_count's last)");
        if (scene->frames3d)
            list_file(o, "frames/view3d_NNNN.png", "");
        if (scene->animation & IM_ANIMATION_GIF)
            list_file(o, scene->frames3d ? "contact.gif, view3d.gif" : "contact.gif", "");
        if (scene->animation & IM_ANIMATION_MP4)
            list_file(o, scene->frames3d ? "contact.mp4, view3d.mp4" : "contact.mp4", "(when ffmpeg is installed)");
    }
    if (scene->contact_panels && scene->periodic) {
        list_file(o, "panels/family_FF/contact_MMMM.png", "(every step of each family's first surface)");
        return;
    }
    if (scene->contact_panels) {
        list_file(o, "panels/force_FF.npy, panels/force_FF.key", "(one each a family)");
        list_file(o, "results.csv", "");
        list_figure(o, "contact_panels");
        if (scene_wants_plot(scene, IM_SCENE_PLOT_DENSITY) && scene_rough_family_count(scene) > 0)
            list_figure(o, "contact_density"); /* density.c: the maps of the rough families */
    }
}

/* The files of the stages in the order run.c runs them. */
static void list_stages(const output_list *o, const im_scene *scene)
{
    if (scene_wants_plot(scene, IM_SCENE_PLOT_FIG1))
        list_figure(o, "fig1");
    if (scene_wants_plot(scene, IM_SCENE_PLOT_FIG3))
        list_figure(o, "fig3");
    if (scene->table) {
        list_members(o, scene, "table", scene_table_member_kept);
        list_file(o, "table1.csv", "");
        list_file(o, "table1.md", "");
        if (scene_wants_plot(scene, IM_SCENE_PLOT_FIG2) && scene_sweep_count(scene) == 1)
            list_figure(o, "fig2");
    }
    if (scene_wants_plot(scene, IM_SCENE_PLOT_FLAT_K)) {
        list_file(o, "flat/flat_contact.csv", "");
        list_file(o, "flat_k.csv", "");
        list_figure(o, "flat_k");
    }
    if (scene->distributions && !scene->periodic) {
        list_file(o, "distributions/family_FF_{gaps,patches,patch_list}.csv", "(one set a family)");
        list_figure(o, "distributions");
    }
    if (scene_wants_histories(scene))
        list_histories(o, scene);
    list_rendered(o, scene);
}

static void list_sweep(const output_list *o, const im_scene *scene)
{
    im_scene *point = malloc(sizeof *point);
    if (!point)
        list_failed(o, im_fail(IM_ENOMEM, "%s: allocation of a sweep point failed", scene->path));
    for (int i = 0; point && i < scene_sweep_count(scene) && *o->status == IM_OK; ++i) {
        int status = scene_sweep_point(scene, i, point);
        if (status != IM_OK) {
            list_failed(o, status);
            break;
        }
        char prefix[IM_SCENE_PATH];
        snprintf(prefix, sizeof prefix, "%s/", point->output_dir + strlen(scene->output_dir) + 1);
        list_stages(&(output_list){o->out, prefix, o->options, o->resumable, o->status}, point);
    }
    free(point);
    if (scene->table)
        list_file(o, "sweep.csv", "");
    if (scene->table && scene_wants_plot(scene, IM_SCENE_PLOT_FIG2))
        list_figure(o, "fig2");
}

/* IM_OK, or the first error of the listing (members or sweep points that could not be made). */
static int report_outputs(FILE *out, const im_scene *scene, const im_scene_run_options *options)
{
    int status = IM_OK;
    fprintf(out, "outputs under %s/, in the order the run writes them%s:\n", scene->output_dir,
            access(scene->output_dir, F_OK) == 0 ? " (the folder exists)" : " (the folder is made)");
    const output_list o = {out, "", options, !scene_plans_changed(scene, options), &status};
    list_file(&o, "run.json", "");
    if (scene_sweep_count(scene) > 1)
        list_sweep(&o, scene);
    else
        list_stages(&o, scene);
    list_file(&o, "fftw-plans.txt", "");
    list_file(&o, "outputs.txt", "");
    list_file(&o, "index.html", "");
    return status;
}

/* ---- over MPI ranks (ranks.c: member i on rank i % K) ---- */

static void report_ranks(FILE *out, const im_scene *scene, int ranks)
{
    scene_member *members = NULL;
    int count = 0;
    if (ranks <= 1 || (!scene->table && !scene_wants_histories(scene)) ||
        scene_ensemble_members(scene, &members, &count) != IM_OK)
        return;
    fprintf(out, "over %d MPI ranks (each solves its share of the %s%s%s; rank 0 then runs the other stages):\n",
            ranks, scene->table ? "table" : "", scene->table && scene_wants_histories(scene) ? " and the " : "",
            scene_wants_histories(scene) ? "histories" : "");
    for (int rank = 0; rank < ranks; ++rank) {
        fprintf(out, "  rank %d:", rank);
        int mine = 0;
        for (int i = 0; i < count; ++i)
            if (scene_member_rank(i, ranks) == rank)
                fprintf(out, "%s family %02d seed %llu", mine++ ? "," : "", members[i].family,
                        (unsigned long long)members[i].seed);
        fprintf(out, "%s\n", mine ? "" : " nothing");
    }
    scene_members_free(members, count);
}

/* ---- the report ---- */

static void report_sweep_points(FILE *out, const im_scene *scene, const scene_limits *points)
{
    for (int i = 0; i < scene_sweep_count(scene); ++i)
        fprintf(out, "  sweep point %d: memory about %.1f MiB, disk about %.1f MiB\n", i,
                points[i].memory_needed / MIB, points[i].disk_total / MIB);
}

static int write_report(const im_scene *scene, const im_scene_run_options *options, int ranks,
                        const scene_limits *limits, const scene_limits *points, char **report)
{
    size_t length = 0;
    FILE *out = open_memstream(report, &length);
    if (!out)
        return im_fail(IM_ENOMEM, "%s: allocation of the check's report failed", scene->path);
    int members = 0;
    scene_member *list = NULL;
    if (scene_ensemble_members(scene, &list, &members) == IM_OK)
        scene_members_free(list, members);
    fprintf(out, "indentmap run --check: scene %s would run\n", scene->name);
    report_inputs(out, scene);
    report_solves(out, scene, members, limits);
    report_estimates(out, scene, limits, options);
    if (points)
        report_sweep_points(out, scene, points);
    int status = report_outputs(out, scene, options);
    report_ranks(out, scene, ranks);
    if (fclose(out) != 0 && status == IM_OK)
        status = im_fail(IM_ENOMEM, "%s: writing the check's report failed", scene->path);
    if (status != IM_OK) { /* scene.h: *report NULL on an error */
        free(*report);
        *report = NULL;
    }
    return status;
}

/* The run's checks of the prepared scene, and each sweep point's limits into *points (allocated; NULL
 * without a sweep). */
static int check_prepared(const im_scene *measured, const im_scene_run_options *options, int ranks,
                          scene_limits *limits, scene_limits **points)
{
    *points = NULL;
    int status = scene_check_before_work(measured, options, ranks > 1, limits);
    if (status != IM_OK || scene_sweep_count(measured) == 1)
        return status;
    *points = calloc((size_t)scene_sweep_count(measured), sizeof **points);
    if (!*points)
        return im_fail(IM_ENOMEM, "%s: allocation of the sweep's estimates failed", measured->path);
    return scene_sweep_check_points(measured, options, *points);
}

int im_scene_check(const im_scene *scene, const im_scene_run_options *given, int ranks, char **report)
{
    ARG_REQUIRE(report, "report");
    *report = NULL;
    ARG_REQUIRE(scene, "scene");
    ARG_REQUIRE(given, "options");
    if (ranks < 1)
        return im_fail(IM_EINVAL, "im_scene_check: ranks = %d: expected at least 1", ranks);
    scene_callbacks callbacks;
    im_scene_run_options options = scene_callbacks_begin(given, &callbacks);
    im_scene *measured = NULL;
    scene_limits limits, *points = NULL;
    int status = scene_prepare_run(scene, &options, &measured);
    if (status == IM_OK)
        status = check_prepared(measured, &options, ranks, &limits, &points);
    if (status == IM_OK)
        status = write_report(measured, &options, ranks, &limits, points, report);
    free(points);
    scene_prepared_free(measured);
    scene_callbacks_end(&callbacks);
    return status;
}
