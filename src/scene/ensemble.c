/* Ensembles: every surface of every family, solved side by side on the available cores. */
#include "indentmap/io.h"
#include "scene/contents.h"
#include "indentmap/status.h"
#include "scene/ensemble.h"
#include "scene/outputs.h"
#include "scene/progress.h"

#include <stdio.h>
#include <stdlib.h>

int scene_ensemble_prepare(const im_scene *scene, const char *folder, scene_member **members, int *count)
{
    char path[IM_SCENE_PATH];
    *members = NULL;
    *count = 0;
    int status = scene_output_path(scene, folder, path, sizeof path);
    if (status == IM_OK)
        status = im_make_directories(path);
    return status == IM_OK ? scene_ensemble_members(scene, members, count) : status;
}

int scene_ensemble_members(const im_scene *scene, scene_member **out, int *count)
{
    scene_member *members = calloc((size_t)(scene->family_count * scene->seed_count), sizeof *members);
    if (!members)
        return im_fail(IM_ENOMEM, "ensemble: allocation failed");
    int n = 0;
    for (int f = 0; f < scene->family_count; ++f) {
        /* A smooth family is one surface whatever the seeds: solve it once. */
        int seeds = scene->slopes[f] == 0.0 && !scene->surface_file[0] ? 1 : scene->seed_count;
        for (int k = 0; k < seeds; ++k, ++n) {
            members[n].family = f;
            members[n].seed = scene->seeds[k];
        }
    }
    *out = members;
    *count = n;
    return IM_OK;
}

static void report_progress(const im_scene_run_options *options, const char *stage, int done, int total)
{
    if (options->progress)
        options->progress(options->user, stage, done, total);
}

/* After an interruption: how many members finished, in the message. */
static int report_interrupted(const im_scene_run_options *options, const scene_member *members, int count)
{
    int finished = 0;
    for (int i = 0; i < count; ++i)
        finished += members[i].status == IM_OK;
    char where[96];
    snprintf(where, sizeof where, "after %d of %d surface%s", finished, count, count == 1 ? "" : "s");
    return scene_interrupted(options, where);
}

/* Member i: solved here, or read back from what the ranks of an MPI run solved. */
static int solve_member(const im_scene *scene, const im_scene_run_options *options, scene_member *members, int i,
                        scene_member_solver solve, const scene_ranks_run *ranks)
{
    if (ranks && ranks->solved(ranks->data, solve, i))
        return ranks->read_back(ranks->data, scene, options, solve, i, &members[i]);
    return solve(scene, options, &members[i]);
}

int scene_ensemble_run(const im_scene *scene, const im_scene_run_options *options, const char *stage,
                       scene_member *members, int count, scene_member_solver solve, const scene_ranks_run *ranks)
{
    int done = 0;
    omp_lock_t counting; /* done counts up in the order of the calls; this ensemble's own lock (progress.h) */
    omp_init_lock(&counting);
#pragma omp parallel for schedule(dynamic, 1)
    for (int i = 0; i < count; ++i) {
        /* Once a signal has asked to stop, the remaining members are skipped, not started. */
        members[i].status = scene_stop_signal(options) ? IM_EINTERRUPTED
                                                       : solve_member(scene, options, members, i, solve, ranks);
        if (members[i].status != IM_OK)
            snprintf(members[i].error, sizeof members[i].error, "%s", im_last_error());
        omp_set_lock(&counting);
        report_progress(options, stage, ++done, count);
        omp_unset_lock(&counting);
    }
    omp_destroy_lock(&counting);
    for (int i = 0; i < count; ++i)
        if (members[i].status != IM_OK && members[i].status != IM_EINTERRUPTED)
            return im_fail(members[i].status, "family %d, seed %llu: %s", members[i].family,
                           (unsigned long long)members[i].seed, members[i].error);
    for (int i = 0; i < count; ++i)
        if (members[i].status == IM_EINTERRUPTED)
            return report_interrupted(options, members, count);
    return IM_OK;
}

int scene_member_rank(int index, int ranks) { return index % ranks; }

void scene_members_free(scene_member *members, int count)
{
    for (int i = 0; members && i < count; ++i) {
        free(members[i].history);
        im_field_free(members[i].force);
    }
    free(members);
}

void scene_reuse_free(scene_reuse *reuse)
{
    scene_members_free(reuse->table, reuse->table_count);
    for (int f = 0; f < IM_SCENE_MAX_FAMILIES; ++f) {
        im_field_free(reuse->force[f]);
        free(reuse->rows[f]);
    }
    *reuse = (scene_reuse){0};
}

int scene_keeps_force(const im_scene *scene, const scene_member *m)
{
    return scene->contact_panels && m->seed == scene->seeds[0];
}

void scene_reuse_take_forces(scene_reuse *reuse, scene_member *members, int count, enum scene_result_kind kind)
{
    for (int i = 0; i < count; ++i) {
        scene_member *m = &members[i];
        if (m->force && !reuse->force[m->family]) {
            reuse->force[m->family] = m->force;
            reuse->force_kind[m->family] = kind;
            m->force = NULL;
        }
    }
}

void scene_report_origin_counts(const im_scene_run_options *options, const char *stage, const int counted[3])
{
    const int total = counted[SCENE_SOLVED] + counted[SCENE_READ_BACK] + counted[SCENE_REUSED];
    scene_progress(options, "%s: %d surface%s: %d solved, %d read back, %d reused from an earlier stage", stage,
                   total, total == 1 ? "" : "s", counted[SCENE_SOLVED], counted[SCENE_READ_BACK],
                   counted[SCENE_REUSED]);
}

void scene_report_origins(const im_scene_run_options *options, const char *stage, const scene_member *members,
                          int count)
{
    int counted[3] = {0};
    for (int i = 0; i < count; ++i)
        ++counted[members[i].origin];
    scene_report_origin_counts(options, stage, counted);
}
