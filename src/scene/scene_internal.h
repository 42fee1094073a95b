/* Internal: the pieces of a scene run, shared by run.c, panels.c and frames.c. */
#ifndef INDENTMAP_SCENE_INTERNAL_H
#define INDENTMAP_SCENE_INTERNAL_H

#include "indentmap/indenter.h"
#include "indentmap/io.h"
#include "indentmap/render.h"
#include "indentmap/scene.h"
#include "indentmap/solver.h"
#include "indentmap/theory.h"

/* The punch a scene describes. */
im_indenter scene_punch(const im_scene *scene);

/* The load N whose smooth contact area is load_star delta^2 (N* of the paper for a cone). */
double scene_load_for_load_star(const im_scene *scene, double delta);

/* The surface of one family and seed: flat for slope 0, the file when the scene names one, else
 * generated. */
int scene_surface(const im_scene *scene, int family, uint64_t seed, im_field **out);

/* The h'rms of one member: its file's measured one in a scene over files, else its family's. */
double scene_member_slope(const im_scene *scene, int family, uint64_t seed);

/* Solver options of a scene (its tolerance; everything else default). */
im_solver_options scene_solver_options(const im_scene *scene);

/* A label for a family: "smooth" or "h'rms = 0.08". */
void scene_family_title(const im_scene *scene, int family, char *buffer, size_t size);

/* Columns of a grid of count panels: three when they fill whole rows (Fig. 4's 2 x 3), else two,
 * else a single row. */
int scene_panel_columns(int count);

/* The colour norm of local forces up to `largest`: the scene's colour map, linear from 0 or log
 * over the two decades below `largest`. */
im_colormap scene_force_norm(const im_scene *scene, double largest);

/* Eq. (12)'s A/A_cone for a cone scene and a roughness (NaN for other punches); *rho_c (may be
 * NULL) receives rho_c of eq. (7). */
double scene_eq12(const im_scene *scene, double slope, double *rho_c);

/* The rough interface of the theory columns of a history on a surface of this h'rms: the scene's
 * E*, k = 2 and the PR normalisation (history_theory.c). */
im_theory_interface scene_theory_interface(const im_scene *scene, double slope);
/* The theory columns (theory.h's im_theory_step) of a step at approach w and load N on it. */
int scene_history_theory_row(const im_scene *scene, double slope, double approach, double load,
                             im_theory_step *row);

/* Writes NAME.png and NAME.pdf under the output folder with draw(scene, data, path). */
int scene_write_png_pdf(const im_scene *scene, const char *name,
                        int (*draw)(const im_scene *, const void *, const char *), const void *data);
/* A draw function for scene_write_png_pdf whose data is an im_plot. */
int scene_draw_plot(const im_scene *scene, const void *plot, const char *path);

/* OUTPUT/run.json: program, version, scene path, quality preset and solver tolerance (record.c). */
int scene_write_record(const im_scene *scene);

/* output_dir/relative into buffer; IM_EINVAL if it does not fit. */
int scene_output_path(const im_scene *scene, const char *relative, char *buffer, size_t size);

/* The number of the signal that asked the run to stop, or 0 (checked between solver steps and
 * between surfaces). */
int scene_stop_signal(const im_scene_run_options *options);

/* IM_EINTERRUPTED with a message naming the signal and where the run stopped (`where`). */
int scene_interrupted(const im_scene_run_options *options, const char *where);

/* Before any work (limits.c): the output folder neither is nor contains an input (IM_EINVAL); the
 * smooth contact at load_star (and at the largest N* step) stays inside the surface (IM_EINVAL);
 * the memory (IM_ENOMEM) and disk (IM_EIO; free space of the output folder's file system, and the
 * file-size limit) the outputs need, estimated from above, are there. Messages give the estimate. */
int scene_check_limits(const im_scene *scene);

/* The output folder's lock (io.h: im_folder_lock), with this advice for a folder in use. */
typedef im_folder_lock scene_lock;
int scene_lock_acquire(const im_scene *scene, scene_lock *lock);
void scene_lock_release(scene_lock *lock);

/* Progress line on stderr unless quiet. */
void scene_progress(const im_scene_run_options *options, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* The family whose history is framed: the one whose slope is frames_slope, else the roughest. */
int scene_framed_family(const im_scene *scene);

/* Frames of the framed family's history; *last_force receives its last step's force field (the
 * state at load_star), which the panels reuse instead of solving it again. */
/* The framed history's steps, for the 3-D frames (frames3d.c). */
typedef struct scene_frames3d_input {
    int count;
    im_field *const *deformed, *const *force;  /* per step: h - u and the force per patch */
    const double *load_star;
    const im_colormap *norm;                   /* the contact frames' force norm */
} scene_frames3d_input;

/* frames3d = yes: frames/view3d_NNNN.png, one 3-D view per step (one norm, exaggeration and
 * camera for all), and view3d.gif (dithered to 216 colours) / view3d.mp4 as `animation` asks. */
int scene_write_frames3d(const im_scene *scene, const im_scene_run_options *options, im_render_context *context,
                         const scene_frames3d_input *in);

int scene_run_frames(const im_scene *scene, const im_scene_run_options *options,
                     im_render_context *context, im_field **last_force);

/* Panels of every family at load_star; known_force (may be NULL) is the framed family's force,
 * already solved by the frames; reuse holds what the table or the histories solved. */
struct scene_reuse;
int scene_run_panels(const im_scene *scene, const im_scene_run_options *options,
                     im_render_context *context, const struct scene_reuse *reuse, const im_field *known_force);

/* ---- keys of kept results (key.c) ---- */

/* What a kept result is: the state at load_star (a table member, a panel), or a history. */
enum scene_result_kind { SCENE_RESULT_AT_LOAD_STAR, SCENE_RESULT_HISTORY };

/* A hash of every input that determines the result of family's surface with this seed: the
 * surface (generator parameters, slope, seed, grid; or the file's path, size and time), punch,
 * material, solver options (tolerance, window), and load_star or the loading control and steps. */
uint64_t scene_result_key(const im_scene *scene, int family, uint64_t seed, enum scene_result_kind kind);

/* The index of the load-controlled step at load_star, -1 if none: there a history takes the
 * table's state instead of solving it again. */
int scene_load_star_step(const im_scene *scene);

/* Whether a result kept at path (with key kept; 0 when it could not be read) may be reused; if
 * not, says on stderr why it is solved again (even with --quiet). */
int scene_key_matches(const char *path, uint64_t kept, uint64_t wanted);

/* FNV-1a (64 bits) of length bytes: the checksum a kept history carries of its rows, so that one
 * cut short or edited is solved again rather than drawn. */
uint64_t scene_checksum(const char *bytes, size_t length);

/* Says on stderr (even with --quiet) that the kept result at path is damaged (why) and is solved
 * again; returns 0, for `return scene_kept_damaged(...)` in a reader. */
int scene_kept_damaged(const char *path, const char *why);

/* ---- ensembles ---- */

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
    im_field *force;               /* force at load_star, kept for a panel (first seed), else NULL */
    const struct scene_member *at_load_star; /* histories: the table's member of this surface */
    int step_reused;               /* histories: the step at load_star was the table's */
    /* histories: one row per step that converged (front.h's schema), and the columns the figures
     * draw, spread from them */
    int steps;
    struct history_row *history;
    double *approach, *history_load, *history_load_star, *history_area_ratio;
    long *history_patches;
} scene_member;

/* What earlier stages of a run solved, for later stages to reuse: nothing is solved twice. */
typedef struct scene_reuse {
    scene_member *table;     /* the table's members (owned; NULL without a table) */
    int table_count;
    im_field *force[IM_SCENE_MAX_FAMILIES]; /* force at load_star of each family's first seed (owned),
                                               kept by the table or a load-controlled history */
} scene_reuse;
void scene_reuse_free(scene_reuse *reuse);

/* Whether a solved member keeps its force at load_star for the panels: the scene draws panels and
 * this is the family's first seed, which the panels show. */
int scene_keeps_force(const im_scene *scene, const scene_member *m);
/* Moves the members' kept forces into reuse->force (where a family has none yet). */
void scene_reuse_take_forces(scene_reuse *reuse, scene_member *members, int count);

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
 * thread), with a progress bar on a terminal. IM_OK, or the first failed member's status with its
 * family, seed and message. */
int scene_ensemble_run(const im_scene *scene, const im_scene_run_options *options, scene_member *members,
                       int count, int (*solve)(const im_scene *, const im_scene_run_options *, scene_member *));

/* The member solvers of the ensemble stages (table.c, histories.c): each reads back a member an
 * earlier run kept (options->resume) or solves it, and writes it under the output folder. */
int scene_table_member(const im_scene *scene, const im_scene_run_options *options, scene_member *m);
int scene_history_member(const im_scene *scene, const im_scene_run_options *options, scene_member *m);
/* Points each history member at the table's member of the same surface (reuse->table), whose
 * state at load_star a load-controlled history takes instead of solving it again. */
void scene_link_table(const im_scene *scene, const scene_reuse *reuse, scene_member *members, int count);

/* panels/force_FF.npy and its key (the force of family's first seed at load_star): written after
 * removing the old key, so that the force is read back only beside its own key; read without
 * checking the key (for a force this run wrote). */
int scene_write_panel(const im_scene *scene, int family, const im_field *force);
int scene_read_panel_force(const im_scene *scene, int family, im_field **force);

/* ---- ensembles over MPI ranks (src/mpi/scene_ranks.c; docs/mpi.md) ----
 * im_scene_run_ranks installs this for the length of one run on rank 0: after the lock, the stale
 * temporaries and run.json, run.c calls solve_members (every rank solves its share of the members
 * and writes them; IM_OK or the status the ranks agreed on); the stages then read those members
 * back (scene_ensemble_run), counting each with the origin its rank gave it. */
typedef int (*scene_member_solver)(const im_scene *, const im_scene_run_options *, scene_member *);
typedef struct scene_ranks_run {
    int (*solve_members)(const im_scene *scene, const im_scene_run_options *options, void *data);
    /* member index's origin in solve's stage (enum scene_origin, plus 4 when a history took its
     * step at load_star from the table, plus 8 when its rank kept its force for the panels and
     * wrote it to panels/), or -1 when the ranks did not solve it */
    int (*origin)(void *data, scene_member_solver solve, int index);
    void *data;
} scene_ranks_run;
void scene_set_ranks_run(const scene_ranks_run *run); /* NULL (the default): a single process */
const scene_ranks_run *scene_get_ranks_run(void);

/* The load N whose smooth contact area is n_star delta^2. */
double scene_load_for_n_star(const im_scene *scene, double n_star, double delta);

/* Histories of every member over [loading] steps, for plots fig5, fig6, fig7. A load-controlled
 * step at load_star takes the table's state (reuse->table) instead of solving it again; without a
 * table, that step's force is kept in reuse->force for the panels. */
int scene_run_histories(const im_scene *scene, const im_scene_run_options *options, scene_reuse *reuse);

/* The ensemble table at load_star (the paper's Table 1): table/member_FF_SEED.csv for each
 * surface as soon as it is solved, then table1.csv and table1.md. Its members (and the first
 * seeds' forces, for panels) are left in *reuse. */
int scene_run_table(const im_scene *scene, const im_scene_run_options *options, scene_reuse *reuse);

/* plots = flat_k (flat_k.c): eq. (2)'s k measured on every rough surface in the periodic half-space,
 * fed into eq. (12) beside k = 2 and the table's simulated A/A_cone (reuse, when the table ran). */
int scene_run_flat_k(const im_scene *scene, const im_scene_run_options *options, const scene_reuse *reuse);

/* Plots: whether [output] plots names one of the figures in the bits of plot; IM_EINVAL when a
 * plot lacks what it draws (density: contact_panels, sphere: a sphere, fig2: the table). */
int scene_wants_plot(const im_scene *scene, enum im_scene_plot plot);
int scene_check_plots(const im_scene *scene);
/* Whether a plot needs the ensemble's histories (fig5, fig6, fig7, sphere). */
int scene_wants_histories(const im_scene *scene);

/* fig1 (gamma(r/a) of the scene's roughnesses) and fig3 (the framed family's surface), which need
 * no solution. */
int scene_run_theory_plots(const im_scene *scene, const im_scene_run_options *options);

/* fig2: A/A_cone against rho_c from theory, with the ensemble's points. */
struct im_plot_points;
int scene_plot_area_ratio(const im_scene *scene, const struct im_plot_points *points);

/* Beyond the paper: ring-averaged contact fraction of each rough family's map beside gamma(r/a)
 * (contact_density.png/pdf); forces and load_star per family, as the panels solved them. */
int scene_plot_contact_density(const im_scene *scene, const im_field *const *forces, const double *load_star);

#endif
