/* An indentation run into its folder (indent_run.h): which files it writes, what an earlier run left,
 * and the steps. */
#include "front/indent_run.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- the files ---- */

/* The number of the step in name after prefix: four or more digits (exactly four with four_digits, as
 * the run names its steps) followed by one of the count suffixes; -1 when name is not such a file. */
static long step_of(const char *name, const char *prefix, const char *const *suffixes, int count, int four_digits)
{
    size_t length = strlen(prefix);
    if (strncmp(name, prefix, length) != 0)
        return -1;
    size_t digits = strspn(name + length, "0123456789");
    if (digits < 4 || (four_digits && digits > 4))
        return -1;
    for (int i = 0; i < count; ++i)
        if (strcmp(name + length + digits, suffixes[i]) == 0)
            return strtol(name + length, NULL, 10);
    return -1;
}

static const char *const FIELD_SUFFIXES[] = {".npy", ".npy.json"};
static const char *const DISTRIBUTION_SUFFIXES[] = {"_gaps.csv", "_patches.csv", "_patch_list.csv"};
static const char *const FRAME_SUFFIXES[] = {".png"};
static const char DISTRIBUTION_PREFIX[] = "distributions_";

/* The step of a field file {force,gap,displacement,plastic}_NNNN.npy or its sidecar among the first
 * fields of STEP_FIELD_PREFIXES; -1 for another name. */
static long field_step(const char *name, int fields, int four_digits)
{
    long step = -1;
    for (int i = 0; i < fields && step < 0; ++i)
        step = step_of(name, STEP_FIELD_PREFIXES[i], FIELD_SUFFIXES, 2, four_digits);
    return step;
}

static long distribution_step(const char *name)
{
    return step_of(name, DISTRIBUTION_PREFIX, DISTRIBUTION_SUFFIXES, 3, 0);
}

/* The files written after the steps: the history figure, the indentation analysis (only when the
 * history unloads) and adhesion's. */
static int is_analysis_file(const char *name)
{
    static const char *const NAMES[] = {"history.png",           "history.pdf",           "indentation.csv",
                                        "load_displacement.png", "load_displacement.pdf", "force_distance.png",
                                        "force_distance.pdf"};
    for (size_t i = 0; i < sizeof NAMES / sizeof *NAMES; ++i)
        if (strcmp(name, NAMES[i]) == 0)
            return 1;
    return 0;
}

int indent_files_claims(const char *name, const void *files)
{
    const indent_files *f = files;
    if (strcmp(name, "history.csv") == 0 || strcmp(name, "run.json") == 0 || strcmp(name, "index.html") == 0 ||
        is_analysis_file(name))
        return 1;
    long step = f->distributions ? distribution_step(name) : -1;
    if (step < 0 && f->fields)
        step = field_step(name, step_field_count(f->hardness), 1);
    return step >= 1 && step <= f->steps;
}

/* Removes the file name in dir unless it is an input; what (e.g. "field file") names it in the message. */
static int remove_earlier(const char *dir, const char *name, const char *what)
{
    char path[PATH_MAX];
    int status = im_path_join(path, sizeof path, dir, name);
    if (status != IM_OK || im_output_check(path) != IM_OK)
        return status; /* an input is kept */
    if (unlink(path) != 0 && errno != ENOENT)
        return im_fail(IM_EIO, "%s: cannot remove the earlier run's %s: %s", path, what, strerror(errno));
    return IM_OK;
}

/* An earlier run's step files and analysis files in dir. */
static int clear_step_files(const char *dir)
{
    DIR *listing = opendir(dir);
    if (!listing)
        return im_fail(IM_EIO, "%s: cannot list: %s", dir, strerror(errno));
    int status = IM_OK;
    for (struct dirent *entry; status == IM_OK && (entry = readdir(listing)) != NULL;) {
        const char *name = entry->d_name; /* the analysis is written again only if the history unloads */
        if (is_analysis_file(name) || field_step(name, STEP_FIELDS_MAX, 0) >= 0 || distribution_step(name) >= 0)
            status = remove_earlier(dir, name, "field file");
    }
    closedir(listing);
    return status;
}

/* An earlier run's DIR/frames/contact_NNNN.png: the viewer page would show them beside this run's. */
static int clear_frames(const char *dir)
{
    char folder[PATH_MAX];
    DIR *listing = im_path_join(folder, sizeof folder, dir, "frames") == IM_OK ? opendir(folder) : NULL;
    if (!listing)
        return IM_OK; /* none there */
    int status = IM_OK;
    for (struct dirent *entry; status == IM_OK && (entry = readdir(listing)) != NULL;)
        if (step_of(entry->d_name, "contact_", FRAME_SUFFIXES, 1, 0) >= 0)
            status = remove_earlier(folder, entry->d_name, "frame");
    closedir(listing);
    return status;
}

int indent_files_clear(const char *dir)
{
    int status = clear_step_files(dir);
    return status == IM_OK ? clear_frames(dir) : status;
}

/* The bytes removing the file name in dir frees (0 when it cannot be read, and for a symbolic link, which
 * frees nothing of its target). */
static double file_bytes(const char *dir, const char *name)
{
    char path[PATH_MAX];
    struct stat info;
    return im_path_join(path, sizeof path, dir, name) == IM_OK && lstat(path, &info) == 0 && S_ISREG(info.st_mode)
               ? (double)info.st_size
               : 0.0;
}

double indent_files_earlier_bytes(const char *dir)
{
    double bytes = 0.0;
    DIR *listing = opendir(dir);
    for (struct dirent *entry; listing && (entry = readdir(listing)) != NULL;) {
        const char *name = entry->d_name;
        if (is_analysis_file(name) || field_step(name, STEP_FIELDS_MAX, 0) >= 0 || distribution_step(name) >= 0)
            bytes += file_bytes(dir, name);
    }
    if (listing)
        closedir(listing);
    char folder[PATH_MAX];
    listing = im_path_join(folder, sizeof folder, dir, "frames") == IM_OK ? opendir(folder) : NULL;
    for (struct dirent *entry; listing && (entry = readdir(listing)) != NULL;)
        if (step_of(entry->d_name, "contact_", FRAME_SUFFIXES, 1, 0) >= 0)
            bytes += file_bytes(folder, entry->d_name);
    if (listing)
        closedir(listing);
    return bytes;
}

/* ---- the steps ---- */

/* The gap and patch-size distributions of the run's last step (front.h: step_distributions_write). */
static int write_distributions(const indent_run_plan *plan, im_indentation *run, int step)
{
    char name[32], prefix[PATH_MAX];
    snprintf(name, sizeof name, "%s%04d", DISTRIBUTION_PREFIX, step);
    int status = im_path_join(prefix, sizeof prefix, plan->dir, name);
    return status == IM_OK ? step_distributions_write(prefix, run, plan->gap_scale) : status;
}

/* Solves step i (0-based; rows[0..i) solved before), measures it, and writes its files and history line. */
static int run_step(const indent_run_plan *plan, im_indentation *run, history_file *history, im_history_row *rows,
                    int i)
{
    int status = im_indentation_step(run, plan->targets[i], &rows[i].result);
    if (status == IM_OK)
        status = im_history_measure(plan->punch, plan->rough, run, plan->tol, rows, i);
    if (status == IM_OK && plan->files.fields) /* first: history.csv lists only steps whose fields are written */
        status = step_fields_write(plan->dir, run, i + 1, &plan->units);
    if (status == IM_OK && plan->files.distributions)
        status = write_distributions(plan, run, i + 1);
    if (status == IM_OK)
        status = history_append(history, &rows[i]);
    if (status == IM_OK && plan->stepped)
        plan->stepped(rows, i, plan->state);
    return status;
}

int indent_run_steps(const indent_run_plan *plan, im_indentation *run, history_file *history, im_history_row *rows,
                     int *done)
{
    int status = IM_OK, i = 0;
    for (; i < plan->count && status == IM_OK; ++i) {
        int signal = plan->stop ? plan->stop(plan->state) : 0; /* between steps: a solve is never cut short */
        status = signal ? im_fail(IM_EINTERRUPTED, "interrupted by signal %d", signal)
                        : run_step(plan, run, history, rows, i);
    }
    *done = status == IM_OK ? i : i - 1;
    if (status != IM_OK) {
        const int kept = *done;
        if (kept == 0)
            im_fail_context(status, "step 1 of %d (%s %g; no step before it was solved)", plan->count,
                            plan->target_name, plan->targets[0]);
        else if (kept == 1)
            im_fail_context(status, "step 2 of %d (%s %g; the step before is in %s/history.csv)", plan->count,
                            plan->target_name, plan->targets[1], plan->dir);
        else
            im_fail_context(status, "step %d of %d (%s %g; the %d steps before are in %s/history.csv)", kept + 1,
                            plan->count, plan->target_name, plan->targets[kept], kept, plan->dir);
    }
    return status;
}
