/* Internal: the output folder of a run, one object for scenes (src/scene/run.c) and `indent`
 * (src/cli/indent.c) alike.
 *
 * Entry points, in the order a run calls them:
 *   run_folder_check   before any work: the inputs protected, none overwritten, the wisdom rule
 *   run_folder_probe   before any work: the folder could be made and locked (nothing written)
 *   run_folder_open    the folder made and locked, a killed run's temporary files removed
 *   run_folder_record  run.json finished with the run's status, the run's error kept
 *   run_folder_page    index.html over what the run left, the run's error kept
 *   run_folder_close   the lock released */
#ifndef INDENTMAP_FRONT_RUN_FOLDER_H
#define INDENTMAP_FRONT_RUN_FOLDER_H

#include "indentmap/io.h"
#include "indentmap/solver.h"

#include <jansson.h>

/* What a run writes into its folder. claims tells the names directly in dir the run writes (state is
 * its argument); NULL: any file anywhere under dir (a scene). */
typedef struct run_folder_rules {
    const char *dir;
    const char *option;        /* how the user gives dir, for messages ("--out") */
    const char *lock_advice;   /* what to do when another run holds the lock */
    const char *wisdom_advice; /* what to do when the wisdom file would be written over */
    int (*claims)(const char *name, const void *state);
    const void *state;
    /* Called on run.json and index.html before they are written (NULL: not called): a scene removes a
     * damaged one. */
    void (*repair)(const char *path, const void *repair_state);
    const void *repair_state;
} run_folder_rules;

typedef struct run_folder {
    run_folder_rules rules;
    im_folder_lock lock;     /* lock.stale_pid: the dead run whose lock was taken over, for a warning */
    int temporaries_removed; /* what a killed run left, for a note */
} run_folder;

/* Before any work: each of the count inputs (NULL entries skipped) becomes an input no write may replace
 * (io.h: the output guard); with claims, none of them or their sidecars (INPUT.json) may be a file the
 * run writes; the solver's FFTW wisdom file must pass im_solver_wisdom_check and may not be written
 * by the run (with claims: one of the claimed names; without: anything under dir). IM_EINVAL naming
 * the file and the folder. */
int run_folder_check(const run_folder_rules *rules, const char *const *inputs, int count,
                     const im_solver_options *solver);

/* Before any work, writing nothing (a run and run --check alike): the folder, or where it does not exist
 * its nearest existing parent, a writable directory, and its lock free (io.h: im_folder_lock_probe).
 * IM_EIO naming the folder otherwise. */
int run_folder_probe(const run_folder_rules *rules);

/* Makes the folder, takes its lock (io.h: im_folder_lock_acquire, with rules->lock_advice) and removes
 * the temporary files of atomic writes a killed run left there, depth levels of subfolders down
 * (io.h: im_folder_remove_temporaries). Close the folder whatever this returns. */
int run_folder_open(const run_folder_rules *rules, int depth, run_folder *folder);

/* Finishes record (repaired first, if rules.repair; record.c: run_record_finish, steps_done steps or -1 for
 * none counted, the run's status and error) into run.json. Returns status, the run's error still the last one, or, for a run that succeeded, whether
 * the record was written (a run without its record did not finish). */
int run_folder_record(const run_folder *folder, json_t *record, int steps_done, int status);

/* Writes index.html (repaired first, if rules.repair) over what the folder holds (viewer.h), also after
 * a failure or an interruption.
 * Returns status, the run's error still the last one, or, for a run that succeeded, whether the page
 * was written. */
int run_folder_page(const run_folder *folder, const char *title, int embed_images, int status);

/* Releases the lock; nothing for a folder not opened. */
void run_folder_close(run_folder *folder);

/* The length of path's longest leading part that exists (0: none; 1 for "/"). */
size_t run_folder_existing_prefix(const char *path);

/* The folder whose file system will hold path: its existing leading part, or ".". */
void run_folder_existing_ancestor(const char *path, char *out, size_t size);

/* The free bytes of the file system that will hold dir (a run's folder, made or not), whose nearest existing
 * folder goes into folder: -1 when it cannot be told (the writes will report a full disk), -2 on a file system
 * that stores no files (no blocks: /proc, /sys). The disk checks before a run (scene/limits.c, front/indent.c). */
double run_folder_free_disk(const char *dir, char *folder, size_t size);

#endif
