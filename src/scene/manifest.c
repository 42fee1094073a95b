/* What a run makes in its output folder (manifest.h): damaged outputs removed before they are made
 * again, and OUTPUT/outputs.txt, whose files a later run removes when its scene no longer makes them. */
#define _GNU_SOURCE /* nftw's FTW_ACTIONRETVAL */
#include "scene/manifest.h"
#include "core/error_keep.h"
#include "scene/contents.h"
#include "scene/run_state.h"

#include "indentmap/io.h"
#include "indentmap/status.h"
#include "scene/outputs.h"
#include "scene/progress.h"

#include <errno.h>
#include <ftw.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

enum { WALK_DEPTH = 4 }; /* OUTPUT/point/panels/family_FF/file: a sweep point's periodic panels are the deepest */

static const char MANIFEST[] = "outputs.txt";
static const char MANIFEST_HEADER[] =
    "# indentmap outputs 1: the files the last run in this folder made; a later run "
    "removes those its scene no longer makes (docs/scenes.md)\n";

typedef struct path_list {
    char **items;
    int count, capacity;
} path_list;

struct scene_outputs {
    const im_scene_run_options *options;
    char root[IM_SCENE_PATH];
    struct timespec start;  /* run.json's time: a file written since was made by this run */
    path_list listed, made; /* outputs.txt's paths, this run's: relative to root */
};

static int list_has(const path_list *list, const char *text)
{
    for (int i = 0; i < list->count; ++i)
        if (strcmp(list->items[i], text) == 0)
            return 1;
    return 0;
}

static int list_add(path_list *list, const char *text)
{
    if (list_has(list, text))
        return IM_OK;
    if (list->count == list->capacity) {
        int capacity = list->capacity ? 2 * list->capacity : 64;
        char **items = realloc(list->items, (size_t)capacity * sizeof *items);
        if (!items)
            return im_fail(IM_ENOMEM, "the list of a run's outputs: allocation failed");
        list->items = items;
        list->capacity = capacity;
    }
    char *copy = strdup(text);
    if (!copy)
        return im_fail(IM_ENOMEM, "the list of a run's outputs: allocation failed");
    list->items[list->count++] = copy;
    return IM_OK;
}

static void list_free(path_list *list)
{
    for (int i = 0; i < list->count; ++i)
        free(list->items[i]);
    free(list->items);
    *list = (path_list){0};
}

/* ---- damaged outputs ---- */

/* The kind a file of this name holds when this program wrote it; IM_KIND_NONE: a name it does not judge. */
static enum im_file_kind kind_by_name(const char *path)
{
    static const struct {
        const char *extension;
        enum im_file_kind kind;
    } KINDS[] = {{".png", IM_KIND_PNG}, {".pdf", IM_KIND_PDF},   {".npy", IM_KIND_NPY},   {".gif", IM_KIND_GIF},
                 {".mp4", IM_KIND_MP4}, {".svg", IM_KIND_SVG},   {".json", IM_KIND_JSON}, {".csv", IM_KIND_TEXT},
                 {".md", IM_KIND_TEXT}, {".html", IM_KIND_TEXT}, {".key", IM_KIND_TEXT},  {".txt", IM_KIND_TEXT}};
    const char *dot = strrchr(path, '.');
    for (size_t i = 0; dot && i < sizeof KINDS / sizeof *KINDS; ++i)
        if (strcmp(dot, KINDS[i].extension) == 0)
            return KINDS[i].kind;
    return IM_KIND_NONE;
}

void scene_output_repair(const im_scene_run_options *options, const char *path)
{
    enum im_file_kind expected = kind_by_name(path), held = IM_KIND_NONE;
    struct stat info;
    if (expected == IM_KIND_NONE || lstat(path, &info) != 0 || !S_ISREG(info.st_mode) || info.st_size == 0 ||
        im_file_kind_of(path, &held) != IM_OK || held == expected || held == IM_KIND_NONE)
        return;
    if (im_output_check(path) != IM_OK) /* an input: its reader or writer names it */
        return;
    if (unlink(path) != 0) {
        scene_warn(options, "%s holds %s, not %s as its name says, and cannot be removed (%s): it is left as it is",
                   path, im_file_kind_name(held), im_file_kind_name(expected), strerror(errno));
        return;
    }
    scene_warn(options, "%s holds %s, not %s as its name says: damaged, removed, and made again", path,
               im_file_kind_name(held), im_file_kind_name(expected));
}

/* ---- noting ---- */

/* path relative to the output folder, or NULL when it is not under it. */
static const char *relative_to(const struct scene_outputs *o, const char *path)
{
    size_t length = strlen(o->root);
    if (strncmp(path, o->root, length) != 0 || path[length] != '/')
        return NULL;
    while (path[length] == '/')
        ++length;
    return path[length] ? path + length : NULL;
}

void scene_outputs_note(const im_scene *scene, const char *path)
{
    struct scene_outputs *o = scene->run ? scene->run->outputs : NULL;
    const char *relative = o ? relative_to(o, path) : NULL;
    if (!relative)
        return;
    int first = 0;
#pragma omp critical(scene_outputs)
    if (!list_has(&o->made, relative)) {
        first = 1;
        list_add(&o->made, relative); /* out of memory: the file is only not listed, so never removed */
    }
    if (first)
        scene_output_repair(o->options, path);
}

/* ---- outputs.txt ---- */

/* A listed path may name only a file under the output folder: relative, without "..". */
static int safe_relative(const char *path)
{
    if (!path[0] || path[0] == '/')
        return 0;
    for (const char *p = path; *p; ++p)
        if ((unsigned char)*p < 0x20 || (p[0] == '.' && p[1] == '.' && (p == path || p[-1] == '/')))
            return 0;
    return 1;
}

/* The lines of outputs.txt into o->listed; 0 when one is not a path under the folder (damaged). */
static int read_listed(struct scene_outputs *o, FILE *stream)
{
    char *line = NULL;
    size_t size = 0;
    ssize_t length;
    int whole = 1;
    while (whole && (length = getline(&line, &size, stream)) > 0) {
        if (line[length - 1] == '\n')
            line[--length] = '\0';
        if (length > 0 && line[0] != '#')
            whole = safe_relative(line) && list_add(&o->listed, line) == IM_OK;
    }
    free(line);
    return whole;
}

static void read_manifest(struct scene_outputs *o)
{
    char path[IM_SCENE_PATH];
    if (im_path_join(path, sizeof path, o->root, MANIFEST) != IM_OK)
        return;
    scene_output_repair(o->options, path);
    FILE *stream = fopen(path, "r");
    if (!stream)
        return;
    if (!read_listed(o, stream)) {
        scene_warn(o->options,
                   "%s is damaged (a line is not a file under %s): the files an earlier run made "
                   "there are not removed",
                   path, o->root);
        list_free(&o->listed);
    }
    fclose(stream);
}

int scene_outputs_open(const im_scene *scene, const im_scene_run_options *options)
{
    struct scene_outputs *o = calloc(1, sizeof *o);
    if (!o)
        return im_fail(IM_ENOMEM, "%s: allocation of the list of outputs failed", scene->path);
    o->options = options;
    snprintf(o->root, sizeof o->root, "%s", scene->output_dir);
    for (size_t n = strlen(o->root); n > 1 && o->root[n - 1] == '/'; --n)
        o->root[n - 1] = '\0';
    char record[IM_SCENE_PATH];
    struct stat info;
    if (im_path_join(record, sizeof record, o->root, "run.json") == IM_OK && stat(record, &info) == 0)
        o->start = info.st_mtim;
    else
        clock_gettime(CLOCK_REALTIME, &o->start);
    read_manifest(o);
    scene->run->outputs = o;
    return IM_OK;
}

static int written_since(const struct stat *info, struct timespec start)
{
    return info->st_mtim.tv_sec > start.tv_sec ||
           (info->st_mtim.tv_sec == start.tv_sec && info->st_mtim.tv_nsec >= start.tv_nsec);
}

/* Removes a listed file this run did not make: one written before this run, and no input. */
static int remove_unmade(const struct scene_outputs *o, const char *relative)
{
    char path[IM_SCENE_PATH];
    struct stat info;
    if (list_has(&o->made, relative) || im_path_join(path, sizeof path, o->root, relative) != IM_OK ||
        lstat(path, &info) != 0 || !S_ISREG(info.st_mode) || written_since(&info, o->start) ||
        im_output_check(path) != IM_OK || unlink(path) != 0)
        return 0;
    rmdir(dirname(path)); /* its folder, when nothing else is left there */
    return 1;
}

static void remove_stale(const struct scene_outputs *o)
{
    int removed = 0;
    char names[256] = "";
    for (int i = 0; i < o->listed.count; ++i) {
        if (!remove_unmade(o, o->listed.items[i]))
            continue;
        size_t used = strlen(names);
        if (++removed <= 3)
            snprintf(names + used, sizeof names - used, "%s%s", used ? ", " : "", o->listed.items[i]);
    }
    if (removed > 0)
        scene_warn(o->options, "removed %d file%s an earlier run made in %s that this scene no longer makes: %s%s",
                   removed, removed == 1 ? "" : "s", o->root, names, removed > 3 ? ", ..." : "");
}

/* The walk of the output folder that lists what this run made (nftw passes no data of its own). */
static _Thread_local struct walk {
    const struct scene_outputs *outputs;
    path_list *made;
    int status;
} * walking;

static int walk_entry(const char *path, const struct stat *info, int type, struct FTW *where)
{
    if (type == FTW_D && where->level >= WALK_DEPTH)
        return FTW_SKIP_SUBTREE;
    const char *relative = relative_to(walking->outputs, path);
    if (type != FTW_F || !relative || path[where->base] == '.' || strcmp(relative, MANIFEST) == 0)
        return FTW_CONTINUE; /* .lock, temporaries */
    if (written_since(info, walking->outputs->start) || list_has(&walking->outputs->made, relative))
        walking->status = list_add(walking->made, relative);
    return walking->status == IM_OK ? FTW_CONTINUE : FTW_STOP;
}

/* What this run made; after a run that did not finish, what outputs.txt listed too. */
static int collect_made(const struct scene_outputs *o, int finished, path_list *made)
{
    struct walk walk = {o, made, IM_OK};
    walking = &walk;
    nftw(o->root, walk_entry, 16, FTW_PHYS | FTW_ACTIONRETVAL);
    walking = NULL;
    for (int i = 0; !finished && walk.status == IM_OK && i < o->listed.count; ++i)
        walk.status = list_add(made, o->listed.items[i]);
    return walk.status;
}

static int compare_paths(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* outputs.txt, its paths sorted: the same for two runs of a scene, whatever the order of the folder. */
static int write_manifest(const struct scene_outputs *o, int finished)
{
    path_list made = {0};
    im_atomic_file file;
    char path[IM_SCENE_PATH];
    int status = collect_made(o, finished, &made);
    if (status == IM_OK && made.count > 1)
        qsort(made.items, (size_t)made.count, sizeof *made.items, compare_paths);
    if (status == IM_OK)
        status = im_path_join(path, sizeof path, o->root, MANIFEST);
    if (status == IM_OK)
        status = im_atomic_open(&file, path);
    if (status == IM_OK) {
        fputs(MANIFEST_HEADER, file.stream);
        for (int i = 0; i < made.count; ++i)
            fprintf(file.stream, "%s\n", made.items[i]);
        status = im_atomic_commit(&file);
    }
    list_free(&made);
    return status;
}

int scene_outputs_close(const im_scene *scene, int status)
{
    struct scene_outputs *o = scene->run->outputs;
    if (!o)
        return status;
    scene->run->outputs = NULL;
    kept_error kept;
    error_keep(&kept);
    if (status == IM_OK)
        remove_stale(o);
    int written = write_manifest(o, status == IM_OK);
    list_free(&o->listed);
    list_free(&o->made);
    free(o);
    if (status == IM_OK)
        return written;
    return error_restore(&kept, status); /* the run's own error stays the one reported */
}
