/* indentmap/scene.h: scene files, what a user wants to see, in INI (parsed with inih).
 *
 * Entry points:
 *   im_scene_load, im_scene_load_record, im_scene_free       a scene from its file or a run's record
 *   im_scene_path, im_scene_name, im_scene_output_dir         what it is called and where it writes
 *   im_scene_asks_for_output, im_scene_renders, im_scene_recorded_plans   what a run of it needs
 *   im_scene_set_output_dir, im_scene_set_wisdom_path         the caller's settings, not from the file
 *   im_scene_run, im_scene_run_options                        everything the scene asks for, on disk
 *   im_scene_check                                            what a run would do, before any work
 *   im_scene_plot_parse, im_scene_plot_name                   [output] plots' names
 *   im_scene_file_path, im_scene_resolve_path                 paths written in a scene
 *
 * A scene names surfaces (generated families with seeds, or a file), the punch and material, the
 * loading, and the outputs. Example (scenes/ has the paper's):
 *
 *   [scene]
 *   name = fig4                   ; results go to output/NAME (under the working directory) unless
 *                                 ; `output` is given (a path relative to the scene file)
 *   [surfaces]
 *   n = 512                       ; grid (m = rows, default n)
 *   hurst = 0.8
 *   lambda_s = 4
 *   lambda_r = 512
 *   slopes = 0, 0.01, 0.02, 0.04, 0.08, 0.16   ; h'rms of each family; 0 is the smooth surface
 *   seeds = 1:10                  ; first:last, or a list
 *   [punch]
 *   shape = cone
 *   alpha = 80                    ; degrees
 *   [loading]
 *   load_star = 30000             ; N* at which panels are drawn
 *   [output]
 *   contact_panels = yes
 *
 * Errors name the file and line ("fig4.ini:7: ...") and, for an unknown key or section, suggest
 * the nearest valid one. Paths inside a scene are resolved relative to the scene file.
 *
 * Misuse (status.h): IM_EINVAL for a NULL scene, path, record, dir or output; im_scene_free(NULL) does
 * nothing, the readers of a NULL scene give "", -1 or 0 (as each says), im_scene_resolve_path writes "" for a NULL scene or relative path, im_scene_plot_parse
 * (NULL) is 0 and im_scene_suggest_key(section, NULL) NULL.
 * Threads: the functions of a scene are thread-safe on distinct scenes, and the readers (im_scene_path
 * ... im_scene_renders, im_scene_file_path) on one scene from several threads; a setter wants the scene
 * to itself. im_scene_run reads its scene (it runs a copy with a run state of its own), starts OpenMP
 * workers of its own and calls its callbacks one at a time (im_scene_run_options). Two runs may go at
 * once in different threads of one process, each into its own output folder (the folder's lock refuses
 * a second run into one, as a second process): tests/test_scene_threads.c runs two so, their files
 * byte-identical to those of the two run one after the other. What that test does not cover: runs
 * that render at once (contact panels, frames: each opens a GL context, and render.h leaves several
 * contexts drawing at once untested), [solver] device = gpu (solver.h: GPU plans keep to one thread),
 * and a process that calls FFTW's planner itself meanwhile (solver.h).
 */
#ifndef INDENTMAP_SCENE_H
#define INDENTMAP_SCENE_H

#include "indentmap/colormap.h"
#include "indentmap/formats.h"
#include "indentmap/history.h"
#include "indentmap/indenter.h"
#include "indentmap/io.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <signal.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

enum {
    IM_SCENE_MAX_FAMILIES = 64,
    IM_SCENE_MAX_STEPS = IM_HISTORY_MAX_STEPS,
    IM_SCENE_PATH = 4096,
    IM_SCENE_MAX_SWEEP = 16,
    IM_SCENE_MAX_SWEEP_POINTS = 64 /* combinations of a sweep's lists */,
    IM_SCENE_CONTENTS = 16384 /* what a scene file set, as run.json's scene_contents records it: every key
                                  at most once, each line < 200 bytes */
};

enum im_animation { IM_ANIMATION_NONE = 0, IM_ANIMATION_GIF = 1, IM_ANIMATION_MP4 = 2, IM_ANIMATION_BOTH = 3 };

/* The figures [output] plots can name ("plots = fig5, fig7"), one bit each. */
enum im_scene_plot {
    IM_SCENE_PLOT_FIG1 = 1u << 0, /* fig1: gamma(r/a) of the scene's roughnesses */
    IM_SCENE_PLOT_FIG2 = 1u << 1, /* fig2: A/A_cone against rho_c, with the table */
    IM_SCENE_PLOT_FIG3 = 1u << 2, /* fig3: the framed family's surface */
    IM_SCENE_PLOT_FIG5 = 1u << 3, /* fig5, fig6, fig7: the ensemble's histories */
    IM_SCENE_PLOT_FIG6 = 1u << 4,
    IM_SCENE_PLOT_FIG7 = 1u << 5,
    IM_SCENE_PLOT_DENSITY = 1u << 6, /* ring-averaged contact density of the panels */
    IM_SCENE_PLOT_SPHERE = 1u << 7,  /* a sphere's histories against eq. (3) */
    IM_SCENE_PLOT_FLAT_K = 1u << 8   /* eq. (2)'s k measured on the rough surfaces */
};

/* [punch] periodic: the rigid flat or the scene's punch on the whole cell (docs/scenes.md). */
enum { IM_SCENE_PERIODIC_FLAT = 1, IM_SCENE_PERIODIC_PUNCH = 2 };

/* The name of one plot bit ("fig5"), NULL for anything else; the bit named by name, 0 for none. */
const char *im_scene_plot_name(enum im_scene_plot plot);
enum im_scene_plot im_scene_plot_parse(const char *name);

/* A scene: what its file (or a run's record) says, every key it left out at its default. Opaque: made by
 * im_scene_load or im_scene_load_record, read through the functions below, freed by im_scene_free. What a
 * run measures (the files' h'rms, the profile read, what it wrote) belongs to that run, not to the scene. */
typedef struct im_scene im_scene;

/* Parses a scene file into a new scene, *scene (free it with im_scene_free; NULL on an error). IM_EIO
 * if it cannot be read, IM_EFORMAT with "PATH:LINE: message" for a malformed line, an unknown section or
 * key (with a suggestion), or a value out of range (naming the key and what was expected), IM_ENOMEM. */
int im_scene_load(const char *path, im_scene **scene);

/* Rebuilds the scene a run recorded in its run.json (docs/scenes.md, "Provenance"): its
 * scene_contents parsed as im_scene_load parses a file, with paths resolved against the recorded
 * scene file's folder (im_scene_path is that file's absolute path; the file itself need not exist any
 * more), the record kept for the new run's run.json (from_record) and how its FFTW plans were made
 * (im_scene_recorded_plans); *scene as im_scene_load's. Refused (IM_EFORMAT naming the record and
 * what was expected) for a record that is not a scene run's or has no scene_contents (an earlier build's, before issue 31), IM_EINVAL for a record of another
 * version (its numbers may differ in their last bits: rerun with that version) and for an input
 * (a surface or profile file) whose SHA-256 is no longer the recorded one, naming the file. */
int im_scene_load_record(const char *record, im_scene **scene);

/* Frees a scene of im_scene_load or im_scene_load_record; NULL does nothing. */
void im_scene_free(im_scene *scene);

/* The scene file as given (for a scene rebuilt from a record, the recorded file's absolute path), its
 * [scene] name, and the folder im_scene_run writes (output/NAME, [scene] output, or
 * im_scene_set_output_dir's). "" for a NULL scene. */
const char *im_scene_path(const im_scene *scene);
const char *im_scene_name(const im_scene *scene);
const char *im_scene_output_dir(const im_scene *scene);

/* Sets the folder im_scene_run writes: IM_EINVAL for a NULL scene or dir, or a dir of IM_SCENE_PATH
 * bytes or more (naming it; the scene is left as it was). */
int im_scene_set_output_dir(im_scene *scene, const char *dir);

/* The FFTW wisdom file of every solve of the scene's runs (solver.h: wisdom_path), NULL (the default)
 * for none. Not from the scene file, and not copied: path must outlive the scene's runs. Nothing for
 * a NULL scene. */
void im_scene_set_wisdom_path(im_scene *scene, const char *path);

/* For a scene rebuilt from a record (im_scene_load_record): 1 when that run's FFTW plans were measured
 * (a wisdom file), 0 when they were estimated; -1 for a scene file and a NULL scene. */
int im_scene_recorded_plans(const im_scene *scene);

/* 1 when the scene asks for an output (a table, plots, contact panels, frames, distributions, or the
 * histories of a periodic scene), 0 when a run would solve and draw nothing (and for NULL). */
int im_scene_asks_for_output(const im_scene *scene);

/* 1 when a run of the scene renders with OpenGL (contact panels or frames: im_scene_run_options.backend),
 * 0 otherwise (and for NULL). */
int im_scene_renders(const im_scene *scene);

/* How im_scene_run runs. The library prints nothing: what the run has to say goes to the
 * callbacks (status.h), and nowhere when they are NULL (the default of a zeroed struct). */
typedef struct im_scene_run_options {
    int resume;         /* 1: reuse results already on disk under the output folder */
    int quiet;          /* 1: no IM_LOG_INFO lines (the stage lines, "table: 51 surfaces ..."); warnings
                            (a kept result stale or damaged and solved again, a stale lock taken
                            over) are logged in any case, and progress calls are made as without it
                            (a caller that wants none gives no progress callback) */
    int backend;        /* im_render_backend of render.h (0: auto) */
    int no_space_check; /* 1: skip the check of the free disk against the outputs' estimated size
                            (an upper bound; a full disk still stops the run, keeping what it finished) */
    /* Interruption (may be NULL): a signal handler stores the signal's number here. The run
     * checks it between solver steps and between surfaces (a solve itself is never cut short),
     * abandons the surface in progress, keeps every finished one on disk and returns
     * IM_EINTERRUPTED; --resume then continues from there. */
    const volatile sig_atomic_t *stop;
    /* Log lines (NULL: dropped) and the ensembles' progress (NULL: none), both with `user`. Calls
     * come from the thread of im_scene_run or from its OpenMP workers, one at a time (serialised by
     * a lock of this run's own), so a callback needs no lock of its own; it may call the library,
     * another im_scene_run included (whose callbacks have their own lock). The
     * indentmap program's callbacks print the lines on stderr and draw a progress bar there when it
     * is a terminal. */
    im_log_fn log;
    im_progress_fn progress;
    void *user;
} im_scene_run_options;

/* Runs a scene: derives the least work its outputs need, solves it, and writes under
 * im_scene_output_dir(scene):
 *   contact_panels: panels/force_FAMILY.npy (force per patch at load_star, one per family, first
 *     seed), results.csv (one row per family: measured n_p and A/A_cone beside eq. (12)), and
 *     contact_panels.{png,pdf}: the panels in a grid of three columns with one shared colour bar
 *     and the smooth contact circle, like the paper's Fig. 4. Each panel is solved in load
 *     control at its load, warm-started by one step at a quarter of it.
 *   frames: frames/contact_NNNN.png and frames/height_NNNN.png for frame_count load steps up to
 *     load_star on one family (the deformed surface with its contact outline), frame_scale pixels
 *     a patch, and the animations contact.gif (and contact.mp4 when ffmpeg is installed,
 *     animation = mp4|both) at frame_rate frames a second: both show the annotated contact frames
 *     themselves (N*, colour bar, scale bar, the smooth contact circle; figure.h).
 *     The history's last step is that family's panel: it is not solved twice.
 *   frames3d (with frames): frames/view3d_NNNN.png, the deformed surface of every step in 3-D
 *     (render.h's im_render_view3d, frame3d_width x frame3d_height: one force norm, one vertical
 *     exaggeration, stated in each title, and one camera for all), and view3d.gif / view3d.mp4 of
 *     those annotated frames as `animation` asks (the GIF with one 256-colour palette).
 *   page_embed: index.html (viewer.h, written by every run) carries its images as data URIs, one
 *     file that travels alone (default no: images referenced by relative paths).
 *   distributions: distributions/family_FF_{gaps,patches,patch_list}.csv, the gap (in the surface's
 *     h_rms) and contact-patch size distributions of each family's first surface at load_star
 *     (measure.h: im_measure_write_distributions), solved for them each time (not kept for --resume).
 *   periodic: histories/member_FF_SEED.csv at the mean pressures of steps and, with the rigid flat and no
 *     hardness, k_fit.csv: k of eq. (2) fitted to each rough member's history (as `indent --periodic`);
 *     with contact_panels, at every step of each family's first surface, its fields
 *     panels/family_FF/{force,gap,displacement[,plastic]}_NNNN.npy and contact map
 *     panels/family_FF/contact_MMMM.png (MMMM = step - 1), with distributions
 *     distributions/family_FF_NNNN_{gaps,patches,patch_list}.csv: `indent --periodic --fields --frames
 *     --distributions`' files; those surfaces are solved by every run (not read back on --resume).
 *   histories that unload (steps going down, with a hardness, not periodic): indentation/member_FF_SEED.csv,
 *     each member's indentation analysis (`indent`'s indentation.csv).
 * Nothing is solved twice within a run (but for the distributions): a load-controlled history's step at load_star takes the
 * table's state, and a panel takes the force of the table, of such a history, or of the frames'
 * last step. Each stage's line says how many surfaces it solved, read back and reused.
 * Every file is written atomically as soon as it is complete, with a key (a hash of every input
 * that determines it: surface parameters, slope, seed and grid, punch, material, solver tolerance
 * and window, load_star or the loading control and steps): a `key` column in the table's member
 * files, a header line in the histories, panels/force_FF.key beside a panel's forces. With options->resume, a kept result whose key is the scene's is read back
 * instead of solved; one whose key differs is solved again, with a warning to options->log.
 * Before any work: the output folder is locked (OUTPUT/.lock holds the pid; IM_EIO naming the
 * folder and the other pid while another live run holds it; a lock left by a dead process is
 * taken over with a warning to options->log; removed when the run ends, however it ends), and the run is refused
 * (IM_ENOMEM / IM_EIO with the estimate) when its memory or disk needs exceed what the machine
 * has, or when the output folder is or contains an input (the scene or its surface file). */
int im_scene_run(const im_scene *scene, const im_scene_run_options *options);

/* What im_scene_run(scene, options) would do, told without solving or writing anything (`indentmap run
 * --check`): the run's own preparation and checks before any work (its input files read, the outputs the
 * scene can make, the output folder's and the wisdom file's rules, the smooth contact inside the surface,
 * the memory and disk estimates against the machine's), then *report, a text the caller frees with free():
 * the inputs, the solves, the estimates, every output in the order the run writes it (with whether
 * --resume would reuse a kept member) and, for ranks > 1, each MPI rank's share of the ensembles. Returns
 * the error the run would stop with (*report NULL), IM_EINVAL for a NULL argument or ranks < 1. Notices
 * (a kept result damaged, a unit assumed) go to options->log, as the run's. Writes nothing: its inputs
 * join the process's output guard (io.h: im_output_protect) as a run's do, the output folder's lock is
 * only probed (a folder a run holds: that run's IM_EIO), and a scene that renders opens and closes an
 * OpenGL context, as the run does before any work. */
int im_scene_check(const im_scene *scene, const im_scene_run_options *options, int ranks, char **report);

/* The path of file i of a scene's `file` list, resolved relative to the scene file (as
 * im_scene_resolve_path); IM_EINVAL when i is out of range. */
int im_scene_file_path(const im_scene *scene, int i, char *out, size_t size);

/* Resolves a path written in a scene relative to the scene file's directory (absolute paths are
 * kept). Writes at most size bytes to out, which may not overlap relative. */
void im_scene_resolve_path(const im_scene *scene, const char *relative, char *out, size_t size);

/* The valid key nearest to an unknown word (Levenshtein distance), for suggestions; NULL if none
 * is close (distance > half the word's length). section may be NULL to search section names. */
const char *im_scene_suggest_key(const char *section, const char *word);

#ifdef __cplusplus
}
#endif

#endif
