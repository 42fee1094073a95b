/* Internal: ensembles: the members of a stage, what stages reuse, and the members over MPI ranks (ensemble.c). */
#ifndef INDENTMAP_SCENE_ENSEMBLE_H
#define INDENTMAP_SCENE_ENSEMBLE_H

#include "indentmap/field.h"
#include "indentmap/scene.h"
#include "scene/key.h"
#include "scene/limits.h"

#include <stdint.h>

/* Where a stage's result came from, counted in its progress line. */
enum scene_origin { SCENE_SOLVED = 0, SCENE_READ_BACK, SCENE_REUSED };

/* One surface of an ensemble and what was measured on it. */
typedef struct scene_member {
    int family;
    uint64_t seed;
    int status;
    enum scene_origin origin;
    char error[512];
    double height_rms;
    /* the table: the state at load_star */
    double load, load_star, area_ratio, seconds, load_star_approach;
    long contact_patches;
    int iterations;
    im_field *force;                         /* force at load_star, kept for a panel (first seed), else NULL */
    const struct scene_member *at_load_star; /* histories: the table's member of this surface */
    int step_reused;                         /* histories: the step at load_star was the table's */
    /* histories: one row per step that converged (history.h's schema); the figures read their
     * columns from these rows (histories.c) */
    int steps;
    struct im_history_row *history;
} scene_member;

/* ---- ensembles over MPI ranks (ranks.c; docs/mpi.md) ----
 * im_scene_run_ranks runs rank 0's scene with one of these (run.c: scene_run): after the lock, the
 * stale temporaries and run.json, solve_members has every rank solve its share of the members and
 * write them (IM_OK or the status the ranks agreed on); the stages then read those members back
 * (scene_ensemble_run), counting each as its rank did. Passed down in scene_reuse. */
typedef int (*scene_member_solver)(const im_scene *, const im_scene_run_options *, scene_member *);
typedef struct scene_ranks_run {
    int (*solve_members)(const im_scene *scene, const im_scene_run_options *options, void *data);
    /* whether the ranks solved member index of solve's stage */
    int (*solved)(void *data, scene_member_solver solve, int index);
    /* such a member, read back from the files its rank wrote (as --resume would) and counted as its
     * rank counted it, with the force its rank kept for the panels */
    int (*read_back)(void *data, const im_scene *scene, const im_scene_run_options *options,
                     scene_member_solver solve, int index, scene_member *m);
    void *data;
} scene_ranks_run;

/* The rank of K ranks that solves member `index` of a stage's list (ranks.c; `run --check` lists each
 * rank's share). */
int scene_member_rank(int index, int ranks);

/* What earlier stages of a run solved, for later stages to reuse: nothing is solved twice. */
typedef struct scene_reuse {
    scene_member *table; /* the table's members (owned; NULL without a table) */
    int table_count;
    im_field *force[IM_SCENE_MAX_FAMILIES]; /* force at load_star of each family's first seed (owned),
                                               kept by the table or a load-controlled history */
    enum scene_result_kind force_kind[IM_SCENE_MAX_FAMILIES]; /* which of the two made it (key.h) */
    struct im_history_row *rows[IM_SCENE_MAX_FAMILIES];       /* a periodic scene's panels: the history of each
                                                           family's first seed (owned; periodic.h) */
    int row_count[IM_SCENE_MAX_FAMILIES];
    const scene_ranks_run *ranks; /* an MPI run's members, solved by its ranks (not owned; NULL: solved here) */
} scene_reuse;
void scene_reuse_free(scene_reuse *reuse);

/* Whether a solved member keeps its force at load_star for the panels: the scene draws panels and
 * this is the family's first seed, which the panels show. */
int scene_keeps_force(const im_scene *scene, const scene_member *m);
/* Moves the members' kept forces into reuse->force (where a family has none yet), made as kind. */
void scene_reuse_take_forces(scene_reuse *reuse, scene_member *members, int count, enum scene_result_kind kind);

/* The progress line of a finished stage: how many of its results were solved, read back from an
 * earlier run (--resume) and reused from an earlier stage of this run (counted[origin]). */
void scene_report_origin_counts(const im_scene_run_options *options, const char *stage, const int counted[3]);
/* The same for an ensemble stage's members. */
void scene_report_origins(const im_scene_run_options *options, const char *stage, const scene_member *members,
                          int count);

/* Every family's seeds (a smooth family once); *out is freed by the caller (scene_members_free). */
int scene_ensemble_members(const im_scene *scene, scene_member **out, int *count);
void scene_members_free(scene_member *members, int count);
/* Creates output_dir/folder (where the members' files go) and lists the members. */
int scene_ensemble_prepare(const im_scene *scene, const char *folder, scene_member **members, int *count);

/* Runs solve on every member, in parallel over the available cores (each solve then runs on one
 * thread), reporting each finished member to options->progress under the name stage ("table",
 * "histories"); a member that ranks (may be NULL) solved is read back instead. IM_OK, or the first
 * failed member's status with its family, seed and message. */
int scene_ensemble_run(const im_scene *scene, const im_scene_run_options *options, const char *stage,
                       scene_member *members, int count, scene_member_solver solve, const scene_ranks_run *ranks);

/* im_scene_run, with the members of its ensembles from ranks (NULL: a single process solves them). */
int scene_run(const im_scene *scene, const im_scene_run_options *options, const scene_ranks_run *ranks);

/* The copy of a scene that runs, made alike by im_scene_run and by every MPI rank (run.c), with its
 * run state (run_state.h): its surface files measured (surfaces.h: scene_measure_files), its [punch]
 * profile resolved against the scene's folder (the copy's profile_file then holds the resolved path)
 * and read. On IM_OK the caller frees *prepared with scene_prepared_free; on an error (IM_ENOMEM,
 * IM_EINVAL naming the key, the file's IM_EIO / IM_EINVAL / IM_EFORMAT) it is NULL. */
int scene_prepare(const im_scene *scene, im_scene **prepared);
/* scene_prepare, then what a run says of it: the units assumed where a file is silent (warnings) and the
 * files' h'rms (a stage line). */
int scene_prepare_run(const im_scene *scene, const im_scene_run_options *options, im_scene **measured);
/* What a run of the prepared scene checks before it writes anything (run.c): the outputs it can make, the
 * [output] keys that do nothing (warned), a sweep under MPI ranks (ranked), the inputs and wisdom file
 * apart from the output folder, and limits.c's limits (their estimates in *limits). IM_OK or the run's
 * error. */
int scene_check_before_work(const im_scene *scene, const im_scene_run_options *options, int ranked,
                            scene_limits *limits);
/* Frees a copy of scene_prepare and its run state (NULL: nothing). */
void scene_prepared_free(im_scene *prepared);

#endif
