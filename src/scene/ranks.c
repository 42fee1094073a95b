/* Ensembles over MPI ranks (scene_ranks.h: im_scene_run_ranks; docs/mpi.md, "Ensembles over ranks").
 * Each rank solves its share of the table's and the histories' members into the shared output
 * folder, with the scene code's own member solvers (which write every member as soon as it is
 * solved, keyed by its inputs); rank 0 then runs the stages alone and reads them back exactly. */
#include "indentmap/scene_ranks.h"
#include "scene/contents.h"
#include "core/args.h"

#include "indentmap/io.h"
#include "indentmap/status.h"
#include "mpi/agree.h"
#include "scene/ensemble.h"
#include "scene/histories.h"
#include "scene/outputs.h"
#include "scene/panels.h"
#include "scene/plots.h"
#include "scene/progress.h"
#include "scene/provenance.h"
#include "scene/table.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

enum { STAGE_TABLE, STAGE_HISTORIES, STAGES };

static const scene_member_solver STAGE_SOLVERS[STAGES] = {scene_table_member, scene_history_member};
static const char *const STAGE_FOLDERS[STAGES] = {"table", "histories"};

typedef struct ranks_state {
    MPI_Comm comm;
    int rank, ranks;
    int started;          /* rank 0: the other ranks were told to start solving */
    int *origins[STAGES]; /* per member of a stage: its origin_code, -1 where no rank solved it */
    int counts[STAGES];
} ranks_state;

/* Waits for a nonblocking collective without spinning: a rank that has finished its share leaves
 * the cores to the ranks still solving (oversubscribed ranks, rank 0 rendering alone). */
static void wait_idle(MPI_Request *request)
{
    const struct timespec pause = {0, 2000000}; /* 2 ms */
    int done = 0;
    MPI_Test(request, &done, MPI_STATUS_IGNORE);
    while (!done) {
        nanosleep(&pause, NULL);
        MPI_Test(request, &done, MPI_STATUS_IGNORE);
    }
}

/* A broadcast from rank 0 that the other ranks wait for idle (every broadcast here is nonblocking:
 * a blocking one may not match it). */
static int broadcast_status(const ranks_state *st, int status)
{
    MPI_Request request;
    MPI_Ibcast(&status, 1, MPI_INT, 0, st->comm, &request);
    wait_idle(&request);
    return status;
}

/* The status every rank goes on with: the lowest failing rank's error, else (all failures being
 * interruptions) the lowest interrupted rank's; its message reaches the others as "rank K: ...". */
static int agree(const ranks_state *st, int status)
{
    int mine = status == IM_OK ? INT_MAX : status == IM_EINTERRUPTED ? st->ranks + st->rank : st->rank, first;
    MPI_Request request;
    MPI_Iallreduce(&mine, &first, 1, MPI_INT, MPI_MIN, st->comm, &request);
    wait_idle(&request);
    if (first == INT_MAX)
        return IM_OK;
    int owner = first % st->ranks, shared = status;
    char message[768] = "";
    if (st->rank == owner)
        snprintf(message, sizeof message, "%s", im_last_error());
    MPI_Bcast(&shared, 1, MPI_INT, owner, st->comm);
    MPI_Bcast(message, sizeof message, MPI_CHAR, owner, st->comm);
    return st->rank == owner ? status : im_fail(shared, "rank %d: %s", owner, message);
}

/* What rank 0's stages need of a member another rank solved, packed in one int for the ranks' MPI_MAX
 * reduction: its enum scene_origin, and the flags below. */
enum { ORIGIN_BITS = 3, STEP_REUSED = 4, KEPT_FORCE = 8 };

static int origin_code(const scene_member *m)
{
    return (int)m->origin | (m->step_reused ? STEP_REUSED : 0) | (m->force ? KEPT_FORCE : 0);
}

/* Every rank's origins of a stage's members, on every rank. */
static int gather_origins(ranks_state *st, int stage, const scene_member *mine, int count)
{
    int *origins = malloc(sizeof *origins * (size_t)(count > 0 ? count : 1));
    int status = agree(st, origins ? IM_OK : im_fail(IM_ENOMEM, "origins of %d members", count));
    if (status != IM_OK) {
        free(origins);
        return status;
    }
    for (int i = 0; i < count; ++i)
        origins[i] = i % st->ranks == st->rank ? origin_code(&mine[i / st->ranks]) : -1;
    MPI_Request request;
    MPI_Iallreduce(MPI_IN_PLACE, origins, count, MPI_INT, MPI_MAX, st->comm, &request);
    wait_idle(&request);
    st->origins[stage] = origins;
    st->counts[stage] = count;
    return IM_OK;
}

/* This rank's members of a stage (scene_member_rank), copied out of the stage's list into *mine. */
static int share_of(const im_scene *scene, const ranks_state *st, int stage, scene_member **mine, int *count, int *n)
{
    scene_member *members = NULL;
    int status = scene_ensemble_prepare(scene, STAGE_FOLDERS[stage], &members, count);
    *mine = status == IM_OK ? calloc((size_t)(*count / st->ranks + 1), sizeof **mine) : NULL;
    if (status == IM_OK && !*mine)
        status = im_fail(IM_ENOMEM, "%s: allocation of %d members failed", STAGE_FOLDERS[stage], *count);
    *n = 0;
    for (int i = 0; status == IM_OK && i < *count; ++i)
        if (scene_member_rank(i, st->ranks) == st->rank)
            (*mine)[(*n)++] = members[i]; /* family and seed: nothing allocated yet */
    scene_members_free(members, status == IM_OK ? *count : 0);
    return status;
}

/* panels/force_FF.npy of the members that kept their force for the panels, for rank 0's panels. */
static int write_kept_forces(const im_scene *scene, const scene_member *mine, int n)
{
    char folder[IM_SCENE_PATH];
    int status = IM_OK, created = 0;
    for (int k = 0; k < n && status == IM_OK; ++k) {
        if (!mine[k].force)
            continue;
        if (!created && (status = scene_output_path(scene, "panels", folder, sizeof folder)) == IM_OK)
            status = im_make_directories(folder);
        created = 1;
        if (status == IM_OK)
            status = scene_write_panel(scene, mine[k].family, mine[k].force);
    }
    return status;
}

/* Solves this rank's members of a stage and writes them (with the panels' forces they keep); the
 * table's members stay in *table for the histories (their step at load_star). */
static int solve_stage(const im_scene *scene, const im_scene_run_options *options, ranks_state *st, int stage,
                       scene_reuse *table, int status)
{
    scene_member *mine = NULL;
    int count = 0, n = 0;
    if (status == IM_OK)
        status = share_of(scene, st, stage, &mine, &count, &n);
    if ((status = agree(st, status)) == IM_OK) {
        if (stage == STAGE_HISTORIES)
            scene_link_table(scene, table, mine, n);
        if (n > 0)
            status = scene_ensemble_run(scene, options, STAGE_FOLDERS[stage], mine, n, STAGE_SOLVERS[stage], NULL);
        if (status == IM_OK)
            status = write_kept_forces(scene, mine, n);
        status = agree(st, status);
    }
    if (status == IM_OK)
        status = gather_origins(st, stage, mine, count);
    if (stage == STAGE_TABLE) {
        table->table = mine;
        table->table_count = n;
    } else {
        scene_members_free(mine, n);
    }
    return status;
}

/* Every rank: its share of the table, then of the histories (quiet: rank 0's stages report). */
static int solve_share(const im_scene *scene, const im_scene_run_options *options, ranks_state *st, int status)
{
    im_scene_run_options quiet = *options;
    quiet.quiet = 1;
    quiet.progress = NULL;
    scene_reuse table = {0};
    if (scene->table)
        status = solve_stage(scene, &quiet, st, STAGE_TABLE, &table, status);
    if (status == IM_OK && scene_wants_histories(scene) && scene->step_count > 0)
        status = solve_stage(scene, &quiet, st, STAGE_HISTORIES, &table, status);
    scene_reuse_free(&table);
    return status;
}

/* Rank 0, called by run.c once the folder is locked and cleaned and run.json written. */
static int rank0_solve_members(const im_scene *scene, const im_scene_run_options *options, void *data)
{
    ranks_state *st = data;
    st->started = 1;
    broadcast_status(st, IM_OK);
    scene_progress(options,
                   "ensembles over %d MPI ranks: rank r solves members r, r + %d, ... of the table "
                   "and the histories",
                   st->ranks, st->ranks);
    double start = MPI_Wtime();
    int status = solve_share(scene, options, st, IM_OK);
    if (status == IM_OK)
        scene_progress(options,
                       "members solved over %d ranks in %.2f s; rank 0 reads them back for the "
                       "stages",
                       st->ranks, MPI_Wtime() - start);
    return status;
}

/* Member index's origin_code in solve's stage, or -1 when no rank solved it. */
static int member_origin(const ranks_state *st, scene_member_solver solve, int index)
{
    for (int s = 0; s < STAGES; ++s)
        if (solve == STAGE_SOLVERS[s] && st->origins[s] && index < st->counts[s])
            return st->origins[s][index];
    return -1;
}

static int member_solved(void *data, scene_member_solver solve, int index)
{
    return member_origin(data, solve, index) >= 0;
}

static int read_member_back(void *data, const im_scene *scene, const im_scene_run_options *options,
                            scene_member_solver solve, int index, scene_member *m)
{
    int origin = member_origin(data, solve, index);
    im_scene_run_options read_back = *options;
    read_back.resume = 1;
    int status = solve(scene, &read_back, m);
    m->origin = (enum scene_origin)(origin & ORIGIN_BITS);
    m->step_reused = (origin & STEP_REUSED) != 0;
    if (status == IM_OK && (origin & KEPT_FORCE) && !m->force)
        status = scene_read_panel_force(scene, m->family, &m->force);
    return status;
}

/* Ranks 1..K-1: wait for rank 0's go, solve their share, wait for rank 0's outcome. */
static int run_worker(ranks_state *st, const im_scene *scene, const im_scene_run_options *options)
{
    im_scene *measured = NULL; /* as im_scene_run: files measured, profile read */
    int status = scene_prepare(scene, &measured);
    int go = broadcast_status(st, IM_OK);
    if (go == IM_OK)
        status = solve_share(measured ? measured : scene, options, st, status);
    scene_prepared_free(measured); /* after the solves that borrowed its profile */
    if (go != IM_OK)
        return im_fail(go, "rank 0 stopped before the members were solved");
    int outcome = broadcast_status(st, IM_OK);
    return status != IM_OK ? status : outcome != IM_OK ? im_fail(outcome, "rank 0 failed") : IM_OK;
}

/* mpi_same_files (agree.h) over each file the scene names, its surface files and profile (run.json's
 * inputs), each named with its scene key. Collective. */
static int same_scene_inputs(MPI_Comm comm, const im_scene *scene)
{
    int count = 0;
    const char *key;
    char path[IM_SCENE_PATH];
    while (scene_input(scene, count, 0, &key, path, sizeof path))
        ++count;
    char *copies = malloc((size_t)count * IM_SCENE_PATH + 1);
    const char **paths = malloc(sizeof *paths * (size_t)(count + 1)),
               **keys = malloc(sizeof *keys * (size_t)(count + 1));
    int status = copies && paths && keys ? IM_OK : im_fail(IM_ENOMEM, "the paths of %d input files", count);
    for (int i = 0; status == IM_OK && i < count; ++i) {
        paths[i] = copies + (size_t)i * IM_SCENE_PATH;
        scene_input(scene, i, 0, &keys[i], copies + (size_t)i * IM_SCENE_PATH, IM_SCENE_PATH);
    }
    if ((status = mpi_collective_status(comm, status)) == IM_OK)
        status = mpi_same_files(comm, "the scene", count, paths, keys);
    free(copies);
    free(paths);
    free(keys);
    return status;
}

/* Rank 0 runs the scene, the other ranks their share of its members. */
static int run_on_rank(ranks_state *st, const im_scene *scene, const im_scene_run_options *options)
{
    int status;
    if (st->rank == 0) {
        const scene_ranks_run run = {rank0_solve_members, member_solved, read_member_back, st};
        status = scene_run(scene, options, &run);
        /* not started: rank 0 failed before the members (bad scene, folder in use), which the other
         * ranks learn from the go; else they wait for the outcome */
        broadcast_status(st, status);
    } else {
        scene_callbacks callbacks; /* as im_scene_run: a worker's warnings come one at a time */
        im_scene_run_options run = scene_callbacks_begin(options, &callbacks);
        status = run_worker(st, scene, &run);
        scene_callbacks_end(&callbacks);
    }
    return status;
}

int im_scene_run_ranks(MPI_Comm comm, const im_scene *scene, const im_scene_run_options *options)
{
    ARG_REQUIRE(scene, "scene");
    ARG_REQUIRE(options, "options");
    ranks_state st = {.comm = comm};
    MPI_Comm_rank(comm, &st.rank);
    MPI_Comm_size(comm, &st.ranks);
    if (st.ranks == 1)
        return im_scene_run(scene, options);
    /* a path may name other files on other nodes: every rank stops before anything is written */
    int status = same_scene_inputs(comm, scene);
    if (status == IM_OK)
        status = run_on_rank(&st, scene, options);
    for (int s = 0; s < STAGES; ++s)
        free(st.origins[s]);
    return status;
}

/* Each rank's preparation of the scene, as run_worker's: its files read and measured there. */
static int prepare_here(const im_scene *scene)
{
    im_scene *measured = NULL;
    int status = scene_prepare(scene, &measured);
    scene_prepared_free(measured);
    return status;
}

int im_scene_check_ranks(MPI_Comm comm, const im_scene *scene, const im_scene_run_options *options, char **report)
{
    ARG_REQUIRE(report, "report");
    *report = NULL;
    ARG_REQUIRE(scene, "scene");
    ARG_REQUIRE(options, "options");
    int rank, ranks;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &ranks);
    if (ranks == 1)
        return im_scene_check(scene, options, 1, report);
    int status = same_scene_inputs(comm, scene);
    if (status == IM_OK)
        status = mpi_collective_status(comm, rank == 0 ? IM_OK : prepare_here(scene));
    if (status == IM_OK)
        status = mpi_collective_status(comm, rank == 0 ? im_scene_check(scene, options, ranks, report) : IM_OK);
    if (status != IM_OK) {
        free(*report);
        *report = NULL;
    }
    return status;
}
