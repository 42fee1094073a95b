/* The values of a scene's keys: one parser per kind of value (values.h), each storing into the
 * im_scene field its key_spec names, or failing with IM_EFORMAT and a message that names the key
 * (parse.c adds the file and line). */
#include "scene/values.h"
#include "scene/contents.h"

#include "front/front.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "scene/names.h"
#include "core/number.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static void *destination(const key_spec *spec, im_scene *scene) { return (char *)scene + spec->offset; }

static int parse_number(const char *text, double *value)
{
    char *end;
    errno = 0;
    *value = number_parse(text, &end);
    while (*end == ' ' || *end == '\t')
        ++end;
    return end != text && *end == '\0' && errno != ERANGE && isfinite(*value);
}

/* A bound in the fewest digits (six or more) that read back as it: %g alone printed alpha's 90 - 1e-9
 * as "90", and a message refusing 90 named it as allowed. */
static void format_bound(double bound, char *text, size_t size)
{
    for (int digits = 6; digits <= 17; ++digits) {
        snprintf(text, size, "%.*g", digits, bound);
        if (strtod(text, NULL) == bound)
            return;
    }
}

/* "[min, max]" of a numeric key, as its check applies it. */
static const char *range_text(const key_spec *spec, char *text, size_t size)
{
    char lo[32], hi[32];
    format_bound(spec->min, lo, sizeof lo);
    format_bound(spec->max, hi, sizeof hi);
    snprintf(text, size, "[%s, %s]", lo, hi);
    return text;
}

int scene_parse_double(const key_spec *spec, const char *value, im_scene *scene)
{
    double v;
    char range[80];
    if (!parse_number(value, &v) || v < spec->min || v > spec->max)
        return im_fail(IM_EFORMAT, "%s = '%s': expected a number in %s", spec->key, value,
                       range_text(spec, range, sizeof range));
    *(double *)destination(spec, scene) = v;
    return IM_OK;
}

int scene_parse_int(const key_spec *spec, const char *value, im_scene *scene)
{
    double v;
    if (!parse_number(value, &v) || v != floor(v) || v < spec->min || v > spec->max)
        return im_fail(IM_EFORMAT, "%s = '%s': expected an integer in [%g, %g]", spec->key, value, spec->min,
                       spec->max);
    *(int *)destination(spec, scene) = (int)v;
    return IM_OK;
}

int scene_parse_string(const key_spec *spec, const char *value, im_scene *scene)
{
    if (strlen(value) >= spec->capacity || value[0] == '\0')
        return im_fail(IM_EFORMAT, "%s: expected a non-empty value of at most %zu characters", spec->key,
                       spec->capacity - 1);
    strcpy(destination(spec, scene), value);
    return IM_OK;
}

/* [scene] name: the default output folder is output/NAME, so a name is one plain folder name
 * (no '/', not "." or ".."), which cannot lead the outputs outside output/. */
int scene_parse_name(const key_spec *spec, const char *value, im_scene *scene)
{
    if (strchr(value, '/') || strcmp(value, ".") == 0 || strcmp(value, "..") == 0)
        return im_fail(IM_EFORMAT,
                       "name = '%s': expected a plain name without '/' (nor '.' or '..'): the outputs "
                       "go to output/NAME; to write elsewhere, give [scene] output",
                       value);
    return scene_parse_string(spec, value, scene);
}

/* Index of value among "a|b|c" choices, or -1. */
static int choice_index(const char *choices, const char *value)
{
    size_t length = strlen(value);
    int index = 0;
    for (const char *p = choices; *p; ++index) {
        size_t word = strcspn(p, "|");
        if (word == length && strncasecmp(p, value, length) == 0)
            return index;
        p += word + (p[word] == '|');
    }
    return -1;
}

/* scene_parse_choice stores the index of the choice, in the enumerations' order, through an int. */
_Static_assert(sizeof(enum im_detrend) == sizeof(int) && sizeof(enum im_control) == sizeof(int) &&
                   sizeof(im_colormap_id) == sizeof(int) && sizeof(enum im_animation) == sizeof(int) &&
                   sizeof(enum im_npy_order) == sizeof(int),
               "an enumeration scene_parse_choice sets is not an int's size");

int scene_parse_choice(const key_spec *spec, const char *value, im_scene *scene)
{
    int index = choice_index(spec->choices, value);
    if (index < 0)
        return im_fail(IM_EFORMAT, "%s = '%s': expected one of %s", spec->key, value, spec->choices);
    *(int *)destination(spec, scene) = index;
    return IM_OK;
}

int scene_parse_bool(const key_spec *spec, const char *value, im_scene *scene)
{
    int index = choice_index("no|yes|false|true|0|1|off|on", value);
    if (index < 0)
        return im_fail(IM_EFORMAT, "%s = '%s': expected yes or no", spec->key, value);
    *(int *)destination(spec, scene) = index % 2;
    return IM_OK;
}

/* The comma-separated items of a list value, trimmed of blanks, into items[] (pointing into
 * buffer, which it modifies); IM_EFORMAT for an empty list or an empty item ("1,,2", a trailing
 * comma): strtok skipped those silently. */
static int split_list(const char *key, const char *value, char *buffer, size_t buffer_size, char **items,
                      int capacity, int *count)
{
    snprintf(buffer, buffer_size, "%s", value);
    *count = 0;
    for (char *item = buffer; item; ++*count) {
        char *comma = strchr(item, ',');
        if (comma)
            *comma = '\0';
        item += strspn(item, " \t");
        size_t length = strlen(item);
        while (length > 0 && (item[length - 1] == ' ' || item[length - 1] == '\t'))
            item[--length] = '\0';
        if (length == 0)
            return im_fail(IM_EFORMAT, "%s = '%s': %s", key, value,
                           *count == 0 && !comma
                               ? "expected at least one value"
                               : "an empty item (two commas, or a comma at either end): expected values separated by "
                                 "commas");
        if (*count >= capacity)
            return im_fail(IM_EFORMAT, "%s = '%s': more than %d values", key, value, capacity);
        items[*count] = item;
        item = comma ? comma + 1 : NULL;
    }
    return IM_OK;
}

/* IM_EFORMAT when a list repeats a value as %g prints it: each value of a list is one family or
 * sweep point, named by it (labels, folders), so no two may print alike. */
static int check_distinct(const char *key, const char *value, const double *list, int n)
{
    for (int i = 1; i < n; ++i)
        for (int j = 0; j < i; ++j) {
            char a[32], b[32];
            snprintf(a, sizeof a, "%g", list[i]);
            snprintf(b, sizeof b, "%g", list[j]);
            if (strcmp(a, b) == 0)
                return im_fail(IM_EFORMAT,
                               "%s = '%s': %s is given twice (to six digits); each value is one family "
                               "or sweep point, give each once",
                               key, value, a);
        }
    return IM_OK;
}

/* "a, b, c" or "first:last:count" (count values, evenly spaced) into a list of doubles: the step
 * lists' parser (front.h), then this key's capacity and range. */
int scene_parse_double_list(const key_spec *spec, const char *value, im_scene *scene)
{
    double *list = destination(spec, scene), values[STEPS_MAX];
    int *count = (int *)((char *)scene + spec->count_offset), n;
    char name[64], error[512];
    snprintf(name, sizeof name, "%s =", spec->key);
    if (steps_parse(name, value, values, &n, error, sizeof error) != 0)
        return im_fail(IM_EFORMAT, "%s", error);
    if ((size_t)n > spec->capacity)
        return im_fail(IM_EFORMAT, "%s = '%s': %d values where at most %zu fit", spec->key, value, n, spec->capacity);
    char range[80];
    for (int i = 0; i < n; ++i)
        if (values[i] < spec->min || values[i] > spec->max)
            return im_fail(IM_EFORMAT, "%s = '%s': %g is outside %s", spec->key, value, values[i],
                           range_text(spec, range, sizeof range));
    int status = check_distinct(spec->key, value, values, n);
    if (status != IM_OK)
        return status;
    memcpy(list, values, (size_t)n * sizeof *list);
    *count = n;
    return IM_OK;
}

/* The scalar the rest of a scene reads for a sweep list: its first value. */
static double *sweep_scalar(const key_spec *spec, im_scene *scene)
{
    if (strcmp(spec->key, "alpha") == 0)
        return &scene->alpha_degrees;
    return strcmp(spec->key, "hurst") == 0 ? &scene->surface.hurst : &scene->surface.lambda_s;
}

/* [punch] alpha, [surfaces] hurst and lambda_s: one value, or a sweep's list ("a, b" or
 * first:last:count) whose values each name a sweep point and its folder. */
int scene_parse_sweep_list(const key_spec *spec, const char *value, im_scene *scene)
{
    int *count_given = (int *)((char *)scene + spec->count_offset);
    const int list = strpbrk(value, ",:") != NULL; /* else one value, with the message of a plain number */
    int status = list ? scene_parse_double_list(spec, value, scene) : scene_parse_double(spec, value, scene);
    if (status != IM_OK)
        return status;
    if (!list)
        *count_given = 1;
    *sweep_scalar(spec, scene) = ((const double *)destination(spec, scene))[0];
    return IM_OK;
}

/* seeds = a list of distinct non-negative integers. */
static int parse_seed_list(const key_spec *spec, const char *value, im_scene *scene)
{
    double values[IM_SCENE_MAX_FAMILIES];
    char buffer[2048], *items[IM_SCENE_MAX_FAMILIES];
    int count;
    int status = split_list(spec->key, value, buffer, sizeof buffer, items, IM_SCENE_MAX_FAMILIES, &count);
    if (status != IM_OK)
        return status;
    for (int i = 0; i < count; ++i) {
        double v;
        if (!parse_number(items[i], &v) || v < 0 || v != floor(v) || v > 1e15)
            return im_fail(IM_EFORMAT,
                           "seeds = '%s': expected first:last or a list of at most %d non-negative "
                           "integers",
                           value, IM_SCENE_MAX_FAMILIES);
        values[i] = v;
    }
    for (int i = 0; i < count; ++i)
        for (int j = 0; j < i; ++j)
            if (values[j] == values[i]) /* one surface twice: averaged as two, and both written to one file */
                return im_fail(IM_EFORMAT,
                               "seeds = '%s': seed %.0f is given twice; each seed is one surface, give "
                               "each once",
                               value, values[i]);
    scene->seed_count = count;
    for (int i = 0; i < count; ++i)
        scene->seeds[i] = (uint64_t)values[i];
    return IM_OK;
}

/* "first:last" (inclusive) or a list of seeds. */
int scene_parse_seeds(const key_spec *spec, const char *value, im_scene *scene)
{
    unsigned long long first, last;
    int used = 0;
    if (strchr(value, '-')) /* %llu would read "-3:-1" as the seeds 2^64 - 3 .. 2^64 - 1 */
        return im_fail(IM_EFORMAT,
                       "seeds = '%s': a '-' (a negative seed, or a range written first-last?): expected first:last "
                       "or a list of non-negative integers",
                       value);
    if (!(sscanf(value, "%llu : %llu%n", &first, &last, &used) == 2 && value[used] == '\0'))
        return parse_seed_list(spec, value, scene);
    if (last < first)
        return im_fail(IM_EFORMAT, "seeds = '%s': expected first:last with first <= last", value);
    if (last - first >= spec->capacity)
        return im_fail(IM_EFORMAT, "seeds = '%s': expected first:last with at most %zu seeds", value, spec->capacity);
    scene->seed_count = (int)(last - first + 1);
    for (int i = 0; i < scene->seed_count; ++i)
        scene->seeds[i] = first + (unsigned long long)i;
    return IM_OK;
}

int scene_parse_later(const key_spec *spec, const char *value, im_scene *scene)
{
    (void)spec, (void)value, (void)scene;
    return IM_OK;
}

/* [adhesion] law: `indent --adhesion-law`'s names (solver.h: im_adhesion_law_parse). */
int scene_parse_adhesion_law(const key_spec *spec, const char *value, im_scene *scene)
{
    if (im_adhesion_law_parse(value, (int *)destination(spec, scene)) == IM_OK)
        return IM_OK;
    return im_fail(IM_EFORMAT,
                   "law = '%s': expected maugis-dugdale (a constant stress w / range up to the gap range) "
                   "or exponential (the tension (w / range) exp(-gap / range))",
                   value);
}

/* [punch] shape: the punch names of `indent --punch` (indenter.h: im_punch_parse), whose message follows. */
int scene_parse_punch(const key_spec *spec, const char *value, im_scene *scene)
{
    (void)spec;
    if (im_punch_parse(value, &scene->punch) == IM_OK)
        return IM_OK;
    char why[512];
    snprintf(why, sizeof why, "%s", im_last_error());
    return im_fail(IM_EFORMAT, "shape = %s", why);
}

/* [output] plots: figure names separated by commas or blanks, into the bit set. */
int scene_parse_plots(const key_spec *spec, const char *value, im_scene *scene)
{
    (void)spec;
    char copy[512], *save = NULL;
    if (strlen(value) >= sizeof copy)
        return im_fail(IM_EFORMAT, "plots: expected at most %zu characters", sizeof copy - 1);
    snprintf(copy, sizeof copy, "%s", value);
    scene->plots = 0;
    for (char *name = strtok_r(copy, ", \t", &save); name; name = strtok_r(NULL, ", \t", &save)) {
        enum im_scene_plot plot = im_scene_plot_parse(name);
        if (!plot) {
            const char *suggestion = scene_suggest_plot(name);
            return im_fail(IM_EFORMAT,
                           "plots: '%s' is not a figure; %s%s%sexpected fig1, fig2, fig3, fig5, fig6, "
                           "fig7, density, sphere or flat_k",
                           name, suggestion ? "did you mean '" : "", suggestion ? suggestion : "",
                           suggestion ? "'? " : "");
        }
        scene->plots |= (unsigned)plot;
    }
    return IM_OK;
}

/* A quality preset's name (solver.h: im_quality_tolerance); its tolerance is applied after
 * parsing, unless [solver] tol is given. */
int scene_parse_quality(const key_spec *spec, const char *value, im_scene *scene)
{
    double tol;
    if (strlen(value) >= spec->capacity || im_quality_tolerance(value, &tol) != IM_OK)
        return im_fail(IM_EFORMAT, "quality = '%s': expected draft, standard or publication", value);
    strcpy(destination(spec, scene), value);
    return IM_OK;
}
