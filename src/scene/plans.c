/* The FFTW plans of a scene's kept results (plans.h). A measured plan is fixed by the wisdom line
 * of its transform, and FFTW writes wisdom a line per plan: the kept results' plans can still be had
 * while the wisdom file holds every line it held when they were solved. */
#include "scene/plans.h"
#include "scene/contents.h"

#include "indentmap/io.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "scene/key.h"
#include "scene/outputs.h"
#include "scene/progress.h"

#include <inttypes.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

enum { MAX_RECORD_BYTES = 1 << 20, MAX_WISDOM_BYTES = 64 << 20 };
static const char RECORD[] = "fftw-plans.txt";
static const char HEADER[] = "# indentmap fftw plans 1: how the kept results' FFTW plans were made, and the "
                             "checksums of the wisdom lines they were measured with (docs/scenes.md)";
static const char ESTIMATED[] = "estimated", MEASURED[] = "measured";

/* Sorted checksums of the lines of a text, blanks skipped. */
typedef struct line_sums {
    uint64_t *items;
    size_t count;
} line_sums;

static int compare_sums(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

static int sum_lines(const char *text, line_sums *out)
{
    size_t capacity = 1;
    for (const char *c = text; *c; ++c)
        capacity += *c == '\n';
    out->count = 0;
    out->items = malloc(capacity * sizeof *out->items);
    if (!out->items)
        return im_fail(IM_ENOMEM, "the checksums of %zu wisdom lines: allocation failed", capacity);
    for (const char *line = text; *line;) {
        size_t length = strcspn(line, "\n"), indent = strspn(line, " \t");
        if (length > indent)
            out->items[out->count++] = scene_checksum(line + indent, length - indent);
        line += length + (line[length] == '\n');
    }
    qsort(out->items, out->count, sizeof *out->items, compare_sums);
    return IM_OK;
}

/* The wisdom file's line checksums now; none for a file not written yet. */
static int wisdom_sums(const char *wisdom, line_sums *out)
{
    struct stat info;
    if (stat(wisdom, &info) != 0) {
        *out = (line_sums){0};
        return IM_OK;
    }
    char *text = NULL;
    int status = im_read_text_file(wisdom, MAX_WISDOM_BYTES, &text, NULL);
    if (status == IM_OK)
        status = sum_lines(text, out);
    free(text);
    return status;
}

static const char *run_wisdom(const im_scene *scene)
{
    im_solver_options solver = {.wisdom_path = scene->wisdom_path};
    return im_solver_wisdom_file(&solver);
}

/* Whether every checksum of kept is in now (both sorted). */
static int holds_all(const line_sums *now, const uint64_t *kept, size_t count)
{
    if (now->count == 0) /* no wisdom now (items NULL: bsearch must not see it) */
        return count == 0;
    for (size_t i = 0; i < count; ++i)
        if (!bsearch(&kept[i], now->items, now->count, sizeof *kept, compare_sums))
            return 0;
    return 1;
}

/* The record's kind and checksums; 0 when it does not read as one. */
static int parse_record(char *text, const char **kind, line_sums *kept)
{
    char *save = NULL; /* strtok_r: strtok's one hidden cursor is shared by every thread of the process */
    char *line = strtok_r(text, "\n", &save);
    if (!line || strcmp(line, HEADER) != 0 || !(line = strtok_r(NULL, "\n", &save)))
        return 0;
    *kind = strcmp(line, MEASURED) == 0 ? MEASURED : strcmp(line, ESTIMATED) == 0 ? ESTIMATED : NULL;
    kept->count = 0;
    while ((line = strtok_r(NULL, "\n", &save)) != NULL) {
        char *end;
        kept->items[kept->count++] = strtoull(line, &end, 16);
        if (end == line || *end)
            return 0;
    }
    return *kind != NULL;
}

/* Why the recorded plans cannot be had now, or NULL when they can. */
static const char *plans_differ(const im_scene *scene, char *record_text, line_sums *kept, line_sums *now)
{
    const char *kind;
    if (!parse_record(record_text, &kind, kept))
        return "the record cannot be read";
    const char *wisdom = run_wisdom(scene);
    if ((kind == MEASURED) != (wisdom != NULL))
        return kind == MEASURED ? "they were measured with FFTW wisdom, and this run estimates its plans"
                                : "they were estimated, and this run measures its plans with FFTW wisdom";
    if (!wisdom || (wisdom_sums(wisdom, now) == IM_OK && holds_all(now, kept->items, kept->count)))
        return NULL;
    return "the wisdom file no longer holds every plan they were measured with: it was removed, replaced or "
           "measured anew";
}

int scene_plans_changed(const im_scene *scene, const im_scene_run_options *options)
{
    char path[IM_SCENE_PATH];
    struct stat info;
    if (im_path_join(path, sizeof path, scene->output_dir, RECORD) != IM_OK || stat(path, &info) != 0)
        return 0;
    char *text = NULL;
    size_t size = 0;
    line_sums kept = {0}, now = {0};
    const char *why = "the record cannot be read";
    if (im_read_text_file(path, MAX_RECORD_BYTES, &text, &size) == IM_OK &&
        (kept.items = malloc((size / 2 + 1) * sizeof *kept.items)) != NULL)
        why = plans_differ(scene, text, &kept, &now);
    free(text);
    free(kept.items);
    free(now.items);
    if (why)
        scene_warn(options,
                   "%s: the kept results were solved with other FFTW plans than this run's (%s), and "
                   "plans change the last bits: solving everything again",
                   path, why);
    return why != NULL;
}

int scene_plans_record(const im_scene *scene)
{
    const char *wisdom = run_wisdom(scene);
    line_sums now = {0};
    int status = wisdom ? wisdom_sums(wisdom, &now) : IM_OK;
    im_atomic_file file;
    if (status == IM_OK)
        status = scene_open_output(scene, RECORD, &file);
    if (status != IM_OK) {
        free(now.items);
        return status;
    }
    fprintf(file.stream, "%s\n%s\n", HEADER, wisdom ? MEASURED : ESTIMATED);
    for (size_t i = 0; i < now.count; ++i)
        fprintf(file.stream, "%016" PRIx64 "\n", now.items[i]);
    free(now.items);
    return im_atomic_commit(&file);
}
