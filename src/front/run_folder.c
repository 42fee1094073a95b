/* The output folder of a run (run_folder.h): what scenes and `indent` did each their own way. */
#include "front/run_folder.h"
#include "core/error_keep.h"
#include "front/front.h"

#include "indentmap/status.h"
#include "indentmap/viewer.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

/* Two canonical forms of an existing path: with every symlink resolved (realpath), and with only
 * its folder resolved (a symlink named as the input is itself replaced by a rename onto its name).
 * A form that cannot be resolved (the path does not exist) is left empty. */
typedef struct path_forms {
    char full[PATH_MAX], named[PATH_MAX];
} path_forms;

static void locate(const char *path, path_forms *forms)
{
    forms->full[0] = forms->named[0] = '\0';
    if (!realpath(path, forms->full))
        forms->full[0] = '\0';
    char folder[PATH_MAX], resolved[PATH_MAX];
    const char *slash = strrchr(path, '/');
    snprintf(folder, sizeof folder, "%.*s", slash ? (int)(slash - path) + 1 : 1, slash ? path : ".");
    if (realpath(folder, resolved)) {
        int length = snprintf(forms->named, sizeof forms->named, "%s/%s", strcmp(resolved, "/") ? resolved : "",
                              slash ? slash + 1 : path);
        if (length < 0 || (size_t)length >= sizeof forms->named)
            forms->named[0] = '\0';
    }
    if (!forms->full[0])
        forms->named[0] = '\0'; /* a path that does not exist is no input and overwrites none */
}

/* Whether the resolved path `form` lies directly in the resolved folder `dir` under a name the run claims. */
static int folder_claims(const run_folder_rules *rules, const char *dir, const char *form)
{
    const char *slash = strrchr(form, '/');
    if (!form[0] || !slash)
        return 0;
    size_t length = (size_t)(slash - form);
    int in_dir = length ? strlen(dir) == length && strncmp(dir, form, length) == 0 : strcmp(dir, "/") == 0;
    return in_dir && rules->claims(slash + 1, rules->state);
}

/* IM_EINVAL when the run would write over the file at path (an input or its sidecar). */
static int check_not_claimed(const run_folder_rules *rules, const char *dir, const char *path)
{
    path_forms in;
    locate(path, &in);
    const char *hit = folder_claims(rules, dir, in.named)  ? in.named
                      : folder_claims(rules, dir, in.full) ? in.full
                                                           : NULL;
    if (!hit)
        return IM_OK;
    return im_fail(IM_EINVAL, "%s %s would write %s/%s over the input file %s (%s); give another output folder",
                   rules->option, rules->dir, rules->dir, strrchr(hit, '/') + 1, path, in.full);
}

/* The input at path and its sidecar: neither a file the run writes. */
static int check_input_apart(const run_folder_rules *rules, const char *path)
{
    char resolved[PATH_MAX], sidecar[PATH_MAX + 8];
    if (!realpath(rules->dir, resolved))
        return IM_OK; /* a folder that does not exist yet holds no input */
    snprintf(sidecar, sizeof sidecar, "%s.json", path);
    int status = check_not_claimed(rules, resolved, path);
    return status == IM_OK ? check_not_claimed(rules, resolved, sidecar) : status;
}

/* The wisdom file, if any, written by the run: IM_EINVAL. */
static int check_wisdom_apart(const run_folder_rules *rules, const im_solver_options *solver)
{
    int status = im_solver_wisdom_check(solver);
    const char *wisdom = im_solver_wisdom_file(solver);
    char folder[PATH_MAX], file[PATH_MAX];
    if (status != IM_OK || !wisdom || im_path_absolute(rules->dir, folder, sizeof folder) != IM_OK ||
        im_path_absolute(wisdom, file, sizeof file) != IM_OK)
        return status;
    size_t length = strlen(folder);
    if (strncmp(file, folder, length) != 0 || file[length] != '/')
        return IM_OK;
    if (!rules->claims)
        return im_fail(IM_EINVAL, "the FFTW wisdom file %s lies in the output folder %s, where this run writes: %s",
                       wisdom, rules->dir, rules->wisdom_advice);
    if (!rules->claims(file + length + 1, rules->state))
        return IM_OK;
    return im_fail(IM_EINVAL, "the FFTW wisdom file %s would be one of the run's outputs, %s/%s: %s", wisdom,
                   rules->dir, file + length + 1, rules->wisdom_advice);
}

int run_folder_check(const run_folder_rules *rules, const char *const *inputs, int count,
                     const im_solver_options *solver)
{
    int status = IM_OK;
    for (int i = 0; i < count && status == IM_OK; ++i)
        if (inputs[i])
            status = im_output_protect(inputs[i]);
    for (int i = 0; i < count && status == IM_OK && rules->claims; ++i)
        if (inputs[i])
            status = check_input_apart(rules, inputs[i]);
    return status == IM_OK ? check_wisdom_apart(rules, solver) : status;
}

/* The folder itself, else its nearest existing parent (where run_folder_open would make it), into
 * existing; 0 when no part of the path exists (a relative path's "." always does). */
static int nearest_existing(const char *dir, char *existing, size_t size)
{
    int length = snprintf(existing, size, "%s", dir);
    if (length < 0 || (size_t)length >= size)
        return 0;
    for (;;) {
        if (access(existing, F_OK) == 0)
            return 1;
        char *slash = strrchr(existing, '/');
        while (slash && slash > existing && slash[1] == '\0') { /* "a/b/": the trailing slash first */
            *slash = '\0';
            slash = strrchr(existing, '/');
        }
        if (!slash)
            return snprintf(existing, size, ".") > 0;
        slash[slash == existing] = '\0'; /* "/name" is in "/" */
    }
}

int run_folder_probe(const run_folder_rules *rules)
{
    char existing[PATH_MAX];
    struct stat info;
    if (!nearest_existing(rules->dir, existing, sizeof existing))
        return im_fail(IM_EINVAL, "output folder %s: path too long", rules->dir);
    const int exists = strcmp(existing, rules->dir) == 0;
    const char *problem = stat(existing, &info) != 0 || !S_ISDIR(info.st_mode) ? "is not a directory"
                          : access(existing, W_OK | X_OK) != 0                 ? "is not writable"
                                                                               : NULL;
    if (problem && exists)
        return im_fail(IM_EIO, "output folder %s %s", rules->dir, problem);
    if (problem)
        return im_fail(IM_EIO, "output folder %s cannot be made: its nearest existing parent, %s, %s", rules->dir,
                       existing, problem);
    return exists ? im_folder_lock_probe(rules->dir, rules->lock_advice) : IM_OK;
}

int run_folder_open(const run_folder_rules *rules, int depth, run_folder *folder)
{
    *folder = (run_folder){.rules = *rules, .lock = {.fd = -1}};
    int status = im_make_directories(rules->dir);
    if (status == IM_OK)
        status = im_folder_lock_acquire(rules->dir, rules->lock_advice, &folder->lock);
    if (status == IM_OK)
        folder->temporaries_removed = im_folder_remove_temporaries(rules->dir, depth);
    return status;
}

/* What write returns for a run that succeeded; the run's status with its error kept for one that failed,
 * and the file `name` named where it could not be written either (a full disk: the record is not there). */
static int keep_run_error(int status, const kept_error *kept, int written, const char *name)
{
    if (status == IM_OK)
        return written;
    if (written == IM_OK)
        return error_restore(kept, status);
    kept_error reason;
    error_keep(&reason);
    return im_fail(status, "%s; %s was not written either (%s)", kept->message, name, reason.message);
}

/* rules.repair on the folder's file name, if the rules have one. */
static void repair(const run_folder *folder, const char *name)
{
    char path[PATH_MAX];
    if (folder->rules.repair && im_path_join(path, sizeof path, folder->rules.dir, name) == IM_OK)
        folder->rules.repair(path, folder->rules.repair_state);
}

int run_folder_record(const run_folder *folder, json_t *record, int steps_done, int status)
{
    kept_error kept;
    error_keep(&kept);
    repair(folder, "run.json");
    int written = run_record_finish(folder->rules.dir, record, steps_done, status);
    return keep_run_error(status, &kept, written, "run.json");
}

int run_folder_page(const run_folder *folder, const char *title, int embed_images, int status)
{
    kept_error kept;
    error_keep(&kept);
    repair(folder, "index.html");
    const im_viewer_options options = {.embed_images = embed_images};
    int written = im_viewer_write_with(folder->rules.dir, title, &options);
    return keep_run_error(status, &kept, written, "index.html");
}

void run_folder_close(run_folder *folder) { im_folder_lock_release(&folder->lock); }

size_t run_folder_existing_prefix(const char *path)
{
    char copy[PATH_MAX];
    snprintf(copy, sizeof copy, "%s", path);
    size_t n = strlen(copy);
    struct stat info;
    while (n > 0) {
        copy[n] = '\0';
        if (stat(copy, &info) == 0)
            return n;
        char *slash = strrchr(copy, '/');
        if (!slash)
            return 0;
        n = slash == copy ? 1 : (size_t)(slash - copy);
    }
    return 0;
}

void run_folder_existing_ancestor(const char *path, char *out, size_t size)
{
    size_t n = run_folder_existing_prefix(path);
    snprintf(out, size, "%.*s", n ? (int)n : 1, n ? path : ".");
}

double run_folder_free_disk(const char *dir, char *folder, size_t size)
{
    run_folder_existing_ancestor(dir, folder, size);
    struct statvfs info;
    if (statvfs(folder, &info) != 0)
        return -1.0;
    return info.f_blocks == 0 ? -2.0 : (double)info.f_bavail * (double)info.f_frsize;
}
