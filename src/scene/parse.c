#include "indentmap/scene.h"
#include "core/args.h"

#include "front/front.h"

#include "indentmap/formats.h"
#include "indentmap/io.h"

#include "indentmap/solver.h"
#include "indentmap/status.h"

#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* ---- value parsers: each returns 0 or writes a message into error ---- */
typedef struct key_spec key_spec;
typedef int (*value_parser)(const key_spec *spec, const char *value, im_scene *scene, char *error,
                            size_t error_size);

struct key_spec {
    const char *section, *key;
    value_parser parse;
    size_t offset;           /* of the destination in im_scene */
    double min, max;         /* numeric range (inclusive) */
    const char *choices;     /* "a|b|c" for enumerations */
    size_t capacity;         /* string size or list capacity */
    size_t count_offset;     /* of the list's count */
};

#define FIELD(name) offsetof(im_scene, name)

static void *destination(const key_spec *spec, im_scene *scene) { return (char *)scene + spec->offset; }

static int parse_number(const char *text, double *value)
{
    char *end;
    errno = 0;
    *value = strtod(text, &end);
    while (*end == ' ' || *end == '\t')
        ++end;
    return end != text && *end == '\0' && errno != ERANGE && isfinite(*value);
}

static int parse_double(const key_spec *spec, const char *value, im_scene *scene, char *error, size_t size)
{
    double v;
    if (!parse_number(value, &v) || v < spec->min || v > spec->max) {
        snprintf(error, size, "%s = '%s': expected a number in [%g, %g]", spec->key, value, spec->min, spec->max);
        return -1;
    }
    *(double *)destination(spec, scene) = v;
    return 0;
}

static int parse_int(const key_spec *spec, const char *value, im_scene *scene, char *error, size_t size)
{
    double v;
    if (!parse_number(value, &v) || v != floor(v) || v < spec->min || v > spec->max) {
        snprintf(error, size, "%s = '%s': expected an integer in [%g, %g]", spec->key, value, spec->min, spec->max);
        return -1;
    }
    *(int *)destination(spec, scene) = (int)v;
    return 0;
}

static int parse_string(const key_spec *spec, const char *value, im_scene *scene, char *error, size_t size)
{
    if (strlen(value) >= spec->capacity || value[0] == '\0') {
        snprintf(error, size, "%s: expected a non-empty value of at most %zu characters", spec->key,
                 spec->capacity - 1);
        return -1;
    }
    strcpy(destination(spec, scene), value);
    return 0;
}

/* [scene] name: the default output folder is output/NAME, so a name is one plain folder name
 * (no '/', not "." or ".."), which cannot lead the outputs outside output/. */
static int parse_name(const key_spec *spec, const char *value, im_scene *scene, char *error, size_t size)
{
    if (strchr(value, '/') || strcmp(value, ".") == 0 || strcmp(value, "..") == 0) {
        snprintf(error, size, "name = '%s': expected a plain name without '/' (nor '.' or '..'): the outputs go to "
                 "output/NAME; to write elsewhere, give [scene] output", value);
        return -1;
    }
    return parse_string(spec, value, scene, error, size);
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

/* parse_choice stores the index of the choice, in the enumerations' order, through an int. */
_Static_assert(sizeof(enum im_detrend) == sizeof(int) && sizeof(enum im_control) == sizeof(int) &&
               sizeof(im_colormap_id) == sizeof(int) && sizeof(enum im_animation) == sizeof(int) &&
               sizeof(enum im_npy_order) == sizeof(int),
               "an enumeration parse_choice sets is not an int's size");

static int parse_choice(const key_spec *spec, const char *value, im_scene *scene, char *error, size_t size)
{
    int index = choice_index(spec->choices, value);
    if (index < 0) {
        snprintf(error, size, "%s = '%s': expected one of %s", spec->key, value, spec->choices);
        return -1;
    }
    *(int *)destination(spec, scene) = index;
    return 0;
}

static int parse_bool(const key_spec *spec, const char *value, im_scene *scene, char *error, size_t size)
{
    int index = choice_index("no|yes|false|true|0|1|off|on", value);
    if (index < 0) {
        snprintf(error, size, "%s = '%s': expected yes or no", spec->key, value);
        return -1;
    }
    *(int *)destination(spec, scene) = index % 2;
    return 0;
}

/* The comma-separated items of a list value, trimmed of blanks, into items[] (pointing into
 * buffer, which it modifies); -1 with a message for an empty list or an empty item ("1,,2", a
 * trailing comma): strtok skipped those silently. */
static int split_list(const char *key, const char *value, char *buffer, size_t buffer_size, char **items,
                      int capacity, int *count, char *error, size_t size)
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
        if (length == 0) {
            snprintf(error, size, "%s = '%s': %s", key, value, *count == 0 && !comma ? "expected at least one value"
                     : "an empty item (two commas, or a comma at either end): expected values separated by commas");
            return -1;
        }
        if (*count >= capacity) {
            snprintf(error, size, "%s = '%s': more than %d values", key, value, capacity);
            return -1;
        }
        items[*count] = item;
        item = comma ? comma + 1 : NULL;
    }
    return 0;
}

/* Whether a list repeats a value as %g prints it: each value of a list is one family or sweep
 * point, named by it (labels, folders), so no two may print alike. */
static int repeated_value(const char *key, const char *value, const double *list, int n, char *error, size_t size)
{
    for (int i = 1; i < n; ++i)
        for (int j = 0; j < i; ++j) {
            char a[32], b[32];
            snprintf(a, sizeof a, "%g", list[i]);
            snprintf(b, sizeof b, "%g", list[j]);
            if (strcmp(a, b) == 0) {
                snprintf(error, size, "%s = '%s': %s is given twice (to six digits); each value is one family or "
                         "sweep point, give each once", key, value, a);
                return 1;
            }
        }
    return 0;
}

/* "a, b, c" or "first:last:count" (count values, evenly spaced) into a list of doubles: the step
 * lists' parser (front.h), then this key's capacity and range. */
static int parse_double_list(const key_spec *spec, const char *value, im_scene *scene, char *error, size_t size)
{
    double *list = destination(spec, scene), values[STEPS_MAX];
    int *count = (int *)((char *)scene + spec->count_offset), n;
    char name[64];
    snprintf(name, sizeof name, "%s =", spec->key);
    if (steps_parse(name, value, values, &n, error, size) != 0)
        return -1;
    if ((size_t)n > spec->capacity) {
        snprintf(error, size, "%s = '%s': %d values where at most %zu fit", spec->key, value, n, spec->capacity);
        return -1;
    }
    for (int i = 0; i < n; ++i)
        if (values[i] < spec->min || values[i] > spec->max) {
            snprintf(error, size, "%s = '%s': %g is outside [%g, %g]", spec->key, value, values[i], spec->min,
                     spec->max);
            return -1;
        }
    if (repeated_value(spec->key, value, values, n, error, size))
        return -1;
    memcpy(list, values, (size_t)n * sizeof *list);
    *count = n;
    return 0;
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
static int parse_sweep_list(const key_spec *spec, const char *value, im_scene *scene, char *error, size_t size)
{
    int *count_given = (int *)((char *)scene + spec->count_offset);
    if (!strpbrk(value, ",:")) { /* one value: the message of a plain number */
        if (parse_double(spec, value, scene, error, size) != 0)
            return -1;
        *count_given = 1;
    } else if (parse_double_list(spec, value, scene, error, size) != 0) {
        return -1;
    }
    *sweep_scalar(spec, scene) = ((const double *)destination(spec, scene))[0];
    return 0;
}

/* "first:last" (inclusive) or a list of seeds. */
static int parse_seeds(const key_spec *spec, const char *value, im_scene *scene, char *error, size_t size)
{
    unsigned long long first, last;
    int used = 0;
    if (sscanf(value, "%llu : %llu%n", &first, &last, &used) == 2 && value[used] == '\0') {
        if (last < first || last - first >= spec->capacity) {
            snprintf(error, size, "seeds = '%s': expected first:last with at most %zu seeds", value, spec->capacity);
            return -1;
        }
        scene->seed_count = (int)(last - first + 1);
        for (int i = 0; i < scene->seed_count; ++i)
            scene->seeds[i] = first + (unsigned long long)i;
        return 0;
    }
    double values[IM_SCENE_MAX_FAMILIES];
    char buffer[2048], *items[IM_SCENE_MAX_FAMILIES];
    int count;
    if (split_list("seeds", value, buffer, sizeof buffer, items, IM_SCENE_MAX_FAMILIES, &count, error, size) != 0)
        return -1;
    for (int i = 0; i < count; ++i) {
        double v;
        if (!parse_number(items[i], &v) || v < 0 || v != floor(v) || v > 1e15) {
            snprintf(error, size, "seeds = '%s': expected first:last or a list of at most %d non-negative "
                     "integers", value, IM_SCENE_MAX_FAMILIES);
            return -1;
        }
        values[i] = v;
    }
    for (int i = 0; i < count; ++i)
        for (int j = 0; j < i; ++j)
            if (values[j] == values[i]) { /* one surface twice: averaged as two, and both written to one file */
                snprintf(error, size, "seeds = '%s': seed %.0f is given twice; each seed is one surface, give each "
                         "once", value, values[i]);
                return -1;
            }
    scene->seed_count = count;
    for (int i = 0; i < count; ++i)
        scene->seeds[i] = (uint64_t)values[i];
    return 0;
}

/* [loading] steps: the step list of `indent --approach` (front.h: steps_parse_signed), below 0 with
 * [adhesion] only, as `indent` takes negative approaches with --adhesion-work only: so it is parsed once
 * every key is known. */
static int parse_steps(const key_spec *spec, const char *value, im_scene *scene, char *error, size_t size)
{
    (void)spec, (void)value, (void)scene, (void)error, (void)size;
    return 0; /* kept by handle_key, parsed once every key is known (parse_kept_steps) */
}

/* [adhesion] law: `indent --adhesion-law`'s names (solver.h: im_adhesion_law_parse). */
static int parse_adhesion_law(const key_spec *spec, const char *value, im_scene *scene, char *error, size_t size)
{
    if (im_adhesion_law_parse(value, (int *)destination(spec, scene)) == IM_OK)
        return 0;
    snprintf(error, size, "law = '%s': expected maugis-dugdale (a constant stress w / range up to the gap range) or "
             "exponential (the tension (w / range) exp(-gap / range))", value);
    return -1;
}

/* [punch] shape: the punch names of `indent --punch` (indenter.h: im_punch_parse). */
static int parse_punch(const key_spec *spec, const char *value, im_scene *scene, char *error, size_t size)
{
    (void)spec;
    if (im_punch_parse(value, &scene->punch) == IM_OK)
        return 0;
    snprintf(error, size, "shape = %s", im_last_error());
    return -1;
}

static size_t edit_distance(const char *a, const char *b);

/* The plot name nearest to an unknown one, NULL if none is close. */
static const char *suggest_plot(const char *word)
{
    const char *best = NULL;
    size_t best_distance = strlen(word) / 2 + 1;
    for (unsigned bit = 1; im_scene_plot_name((enum im_scene_plot)bit); bit <<= 1) {
        size_t distance = edit_distance(word, im_scene_plot_name((enum im_scene_plot)bit));
        if (distance < best_distance) {
            best_distance = distance;
            best = im_scene_plot_name((enum im_scene_plot)bit);
        }
    }
    return best;
}

/* [output] plots: figure names separated by commas or blanks, into the bit set. */
static int parse_plots(const key_spec *spec, const char *value, im_scene *scene, char *error, size_t size)
{
    (void)spec;
    char copy[512], *save = NULL;
    if (strlen(value) >= sizeof copy) {
        snprintf(error, size, "plots: expected at most %zu characters", sizeof copy - 1);
        return -1;
    }
    snprintf(copy, sizeof copy, "%s", value);
    scene->plots = 0;
    for (char *name = strtok_r(copy, ", \t", &save); name; name = strtok_r(NULL, ", \t", &save)) {
        enum im_scene_plot plot = im_scene_plot_parse(name);
        if (!plot) {
            const char *suggestion = suggest_plot(name);
            snprintf(error, size, "plots: '%s' is not a figure; %s%s%sexpected fig1, fig2, fig3, fig5, fig6, fig7, "
                     "density, sphere or flat_k", name, suggestion ? "did you mean '" : "", suggestion ? suggestion : "",
                     suggestion ? "'? " : "");
            return -1;
        }
        scene->plots |= (unsigned)plot;
    }
    return 0;
}

/* A quality preset's name (solver.h: im_quality_tolerance); its tolerance is applied after
 * parsing, unless [solver] tol is given. */
static int parse_quality(const key_spec *spec, const char *value, im_scene *scene, char *error, size_t size)
{
    double tol;
    if (strlen(value) >= spec->capacity || im_quality_tolerance(value, &tol) != IM_OK) {
        snprintf(error, size, "quality = '%s': expected draft, standard or publication", value);
        return -1;
    }
    strcpy(destination(spec, scene), value);
    return 0;
}

static const key_spec KEYS[] = {
    {"scene", "name", parse_name, FIELD(name), 0, 0, NULL, sizeof(((im_scene *)0)->name), 0},
    {"scene", "output", parse_string, FIELD(output_dir), 0, 0, NULL, IM_SCENE_PATH, 0},
    {"scene", "quality", parse_quality, FIELD(quality), 0, 0, NULL, sizeof(((im_scene *)0)->quality), 0},
    {"surfaces", "n", parse_int, FIELD(surface.nx), 8, IM_FIELD_MAX_SIDE, NULL, 0, 0},
    {"surfaces", "m", parse_int, FIELD(surface.ny), 8, IM_FIELD_MAX_SIDE, NULL, 0, 0},
    {"surfaces", "hurst", parse_sweep_list, FIELD(hursts), 0.01, 0.99, NULL, IM_SCENE_MAX_SWEEP, FIELD(hurst_count)},
    {"surfaces", "lambda_s", parse_sweep_list, FIELD(lambda_ss), 2, 1e9, NULL, IM_SCENE_MAX_SWEEP,
     FIELD(lambda_s_count)},
    {"surfaces", "lambda_r", parse_double, FIELD(surface.lambda_r), 2, 1e9, NULL, 0, 0},
    {"surfaces", "lambda_0", parse_double, FIELD(surface.lambda_0), 2, 1e9, NULL, 0, 0},
    {"surfaces", "slope_definition", parse_choice, FIELD(surface.slope_definition), 0, 0, "spectral|fd", 0, 0},
    {"surfaces", "slopes", parse_double_list, FIELD(slopes), 0, 10, NULL, IM_SCENE_MAX_FAMILIES, FIELD(family_count)},
    {"surfaces", "seeds", parse_seeds, FIELD(seeds), 0, 0, NULL, IM_SCENE_MAX_FAMILIES, 0},
    {"surfaces", "file", parse_string, FIELD(surface_file), 0, 0, NULL, IM_SCENE_PATH, 0},
    {"surfaces", "detrend", parse_choice, FIELD(detrend), 0, 0, "none|plane|curvature", 0, 0},
    {"surfaces", "align", parse_choice, FIELD(align), 0, 0, "none|median|mean|line", 0, 0},
    {"surfaces", "fill", parse_bool, FIELD(fill), 0, 0, NULL, 0, 0},
    {"surfaces", "npy_order", parse_choice, FIELD(npy_order), 0, 0, "sidecar|yx|xy", 0, 0},
    {"surfaces", "channel", parse_string, FIELD(channel), 0, 0, NULL, 64, 0},
    {"surfaces", "resample_square", parse_bool, FIELD(resample_square), 0, 0, NULL, 0, 0},
    {"punch", "shape", parse_punch, FIELD(punch), 0, 0, NULL, 0, 0},
    {"punch", "profile", parse_string, FIELD(profile_file), 0, 0, NULL, IM_SCENE_PATH, 0},
    {"punch", "alpha", parse_sweep_list, FIELD(alphas), 1e-9, 90 - 1e-9, NULL, IM_SCENE_MAX_SWEEP, FIELD(alpha_count)},
    {"punch", "radius", parse_double, FIELD(radius), 1e-9, 1e12, NULL, 0, 0},
    {"punch", "periodic", parse_bool, FIELD(periodic), 0, 0, NULL, 0, 0},
    {"material", "modulus", parse_double, FIELD(modulus), 1e-300, 1e300, NULL, 0, 0},
    {"material", "hardness", parse_double, FIELD(hardness), 1e-300, 1e300, NULL, 0, 0},
    {"loading", "control", parse_choice, FIELD(control), 0, 0, "displacement|load|mean_gap", 0, 0},
    {"loading", "load_star", parse_double, FIELD(load_star), 0, 1e15, NULL, 0, 0},
    {"loading", "steps", parse_steps, FIELD(steps), 0, 0, NULL, 0, 0},
    {"output", "contact_panels", parse_bool, FIELD(contact_panels), 0, 0, NULL, 0, 0},
    {"output", "frames", parse_bool, FIELD(frames), 0, 0, NULL, 0, 0},
    {"output", "frames3d", parse_bool, FIELD(frames3d), 0, 0, NULL, 0, 0},
    {"output", "page_embed", parse_bool, FIELD(page_embed), 0, 0, NULL, 0, 0},
    {"output", "table", parse_bool, FIELD(table), 0, 0, NULL, 0, 0},
    {"output", "distributions", parse_bool, FIELD(distributions), 0, 0, NULL, 0, 0},
    {"output", "animation", parse_choice, FIELD(animation), 0, 0, "none|gif|mp4|both", 0, 0},
    {"output", "colormap", parse_choice, FIELD(colormap), 0, 0, "viridis|cividis|magma|inferno|grey", 0, 0},
    {"output", "log_norm", parse_bool, FIELD(log_norm), 0, 0, NULL, 0, 0},
    {"output", "frames_slope", parse_double, FIELD(frames_slope), 0, 10, NULL, 0, 0},
    {"output", "frame_count", parse_int, FIELD(frame_count), 1, 10000, NULL, 0, 0},
    {"output", "frame_rate", parse_double, FIELD(frame_rate), 0.01, 100, NULL, 0, 0},
    {"output", "frame_scale", parse_int, FIELD(frame_scale), 1, 16, NULL, 0, 0},
    {"output", "frame3d_width", parse_int, FIELD(frame3d_width), 64, 7680, NULL, 0, 0},
    {"output", "frame3d_height", parse_int, FIELD(frame3d_height), 64, 4320, NULL, 0, 0},
    {"adhesion", "work", parse_double, FIELD(adhesion_work), 1e-300, 1e300, NULL, 0, 0},
    {"adhesion", "range", parse_double, FIELD(adhesion_range), 1e-300, 1e300, NULL, 0, 0},
    {"adhesion", "law", parse_adhesion_law, FIELD(adhesion_law), 0, 0, "maugis-dugdale|exponential", 0, 0},
    {"solver", "tol", parse_double, FIELD(tol), 1e-14, 1e-1, NULL, 0, 0},
    {"solver", "device", parse_choice, FIELD(device), 0, 0, "cpu|gpu|auto", 0, 0},
    {"output", "plots", parse_plots, FIELD(plots), 0, 0, NULL, 0, 0},
};
static const int KEY_COUNT = (int)(sizeof KEYS / sizeof KEYS[0]);

void im_scene_defaults(im_scene *scene)
{
    ARG_REQUIRE_OR(scene, "scene", );
    memset(scene, 0, sizeof *scene);
    snprintf(scene->name, sizeof scene->name, "scene");
    snprintf(scene->quality, sizeof scene->quality, "%s", IM_QUALITY_DEFAULT);
    scene->surface = im_surface_params_default();
    scene->slopes[0] = scene->surface.slope_rms;
    scene->family_count = 1;
    scene->seeds[0] = 1;
    scene->seed_count = 1;
    scene->punch = IM_PUNCH_CONE;
    scene->alpha_degrees = 80.0;
    scene->radius = 100.0;
    scene->modulus = 1.0;
    scene->tol = im_quality_default_tolerance();
    scene->frames_slope = -1.0;
    scene->frame_count = 24;
    scene->frame_rate = 4.0;
    scene->frame_scale = 1;
    scene->frame3d_width = 960;
    scene->frame3d_height = 540;
    scene->colormap = IM_COLORMAP_MAGMA; /* forces as every front end draws them (front.h: frame_force_norm) */
    scene->log_norm = 1;
    scene->recorded_plans = -1;
}

static size_t edit_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b), row[64];
    if (lb >= 64)
        return (size_t)-1;
    for (size_t j = 0; j <= lb; ++j)
        row[j] = j;
    for (size_t i = 1; i <= la; ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= lb; ++j) {
            size_t above = row[j];
            size_t substitute = diagonal + (a[i - 1] != b[j - 1]);
            size_t best = above + 1 < row[j - 1] + 1 ? above + 1 : row[j - 1] + 1;
            row[j] = substitute < best ? substitute : best;
            diagonal = above;
        }
    }
    return row[lb];
}

const char *im_scene_suggest_key(const char *section, const char *word)
{
    ARG_REQUIRE_OR(word, "word", NULL);
    const char *best = NULL;
    size_t best_distance = strlen(word) / 2 + 1;
    for (int i = 0; i < KEY_COUNT; ++i) {
        if (section && strcmp(KEYS[i].section, section) != 0)
            continue;
        const char *candidate = section ? KEYS[i].key : KEYS[i].section;
        size_t distance = edit_distance(word, candidate);
        if (distance < best_distance) {
            best_distance = distance;
            best = candidate;
        }
    }
    return best;
}

typedef struct parse_context {
    im_scene *scene;
    FILE *stream;
    int line;        /* physical lines read so far, counted by read_line */
    int error_line;  /* the first line refused by read_line or handle_key, 0 if none */
    int key_line[sizeof KEYS / sizeof KEYS[0]]; /* the line of each key given, 0 if none */
    char sections[16][32]; /* the sections opened so far, to refuse one opened twice */
    int section_lines[16], section_count;
    char steps[INI_MAX_LINE]; /* [loading] steps as written (a line of inih's buffer fits) */
    char contents_section[32]; /* the section of the last key noted in the scene's contents */
    char error[512];
} parse_context;

/* The line of [section] key in the scene, 0 if it was not given. */
static int key_line(const parse_context *context, const char *section, const char *key)
{
    for (int i = 0; i < KEY_COUNT; ++i)
        if (strcmp(KEYS[i].section, section) == 0 && strcmp(KEYS[i].key, key) == 0)
            return context->key_line[i];
    return 0;
}

/* Stops parsing at the line being read with a message; inih then sees the end of the file. */
static char *refuse_line(parse_context *context, const char *format, ...) __attribute__((format(printf, 2, 3)));
static char *refuse_line(parse_context *context, const char *format, ...)
{
    va_list arguments;
    va_start(arguments, format);
    vsnprintf(context->error, sizeof context->error, format, arguments);
    va_end(arguments);
    context->error_line = context->line + 1;
    return NULL;
}

/* 0 with the error recorded when the line opens a [section] opened before (inih would merge the
 * two silently, the later keys replacing the earlier); 1 otherwise. */
static int check_section_once(parse_context *context, const char *line)
{
    const char *open = line + strspn(line, " \t");
    const char *close = *open == '[' ? strchr(open, ']') : NULL;
    if (!close)
        return 1;
    char name[32];
    snprintf(name, sizeof name, "%.*s", (int)(close - open - 1), open + 1);
    for (int i = 0; i < context->section_count; ++i) {
        if (strcmp(context->sections[i], name) == 0) {
            --context->line; /* refuse_line names the line being read */
            refuse_line(context, "[%s] is opened twice (first on line %d): expected each section once", name,
                        context->section_lines[i]);
            return 0;
        }
    }
    if (context->section_count < (int)(sizeof context->sections / sizeof context->sections[0])) {
        snprintf(context->sections[context->section_count], sizeof context->sections[0], "%s", name);
        context->section_lines[context->section_count++] = context->line;
    }
    return 1;
}

/* inih's line reader: one physical line per call, counted so that errors know their line.
 * Debian's libinih hands it a fixed buffer of INI_MAX_LINE (200) bytes; fgets would cut a longer
 * line in two and inih would parse the tail as a line of its own, silently when it begins with a
 * blank (a continuation that replaces the value, e.g. half a `slopes` list). So a line that does
 * not fit, or a NUL byte (which would end the line early for inih), stops parsing with an error. */
static char *read_line(char *buffer, int size, void *user)
{
    parse_context *context = user;
    if (context->error_line)
        return NULL; /* the first error is reported; nothing after it matters */
    int length = 0, c;
    while ((c = getc(context->stream)) != EOF) {
        if (c == '\0')
            return refuse_line(context, "a NUL byte: expected a text file");
        if (c == '\n' && length == size - 1)
            break; /* the newline itself need not be kept */
        if (length == size - 1)
            return refuse_line(context, "line longer than %d characters, the INI reader's limit "
                               "(for long lists of values use first:last:count)", size - 1);
        buffer[length++] = (char)c;
        if (c == '\n')
            break;
    }
    if (length == 0)
        return NULL; /* end of file, or a read error that im_scene_load reports */
    buffer[length] = '\0';
    ++context->line;
    return check_section_once(context, buffer) ? buffer : NULL;
}

static int section_exists(const char *section)
{
    for (int i = 0; i < KEY_COUNT; ++i)
        if (strcmp(KEYS[i].section, section) == 0)
            return 1;
    return 0;
}

static void unknown_name(parse_context *context, const char *section, const char *name)
{
    int known_section = section_exists(section);
    const char *suggestion = known_section ? im_scene_suggest_key(section, name)
                                           : im_scene_suggest_key(NULL, section);
    if (known_section)
        snprintf(context->error, sizeof context->error, "unknown key '%s' in [%s]%s%s%s", name, section,
                 suggestion ? "; did you mean '" : "", suggestion ? suggestion : "", suggestion ? "'?" : "");
    else
        snprintf(context->error, sizeof context->error, "unknown section [%s]%s%s%s", section,
                 suggestion ? "; did you mean [" : "", suggestion ? suggestion : "", suggestion ? "]?" : "");
}

/* Every key given fits in im_scene.contents: each once, its line within inih's buffer, and each
 * section's header once. */
_Static_assert(sizeof KEYS / sizeof KEYS[0] * (INI_MAX_LINE + 4) + 16 * 32 < IM_SCENE_CONTENTS,
               "im_scene.contents holds every key a scene can give");

/* Appends a key accepted to the scene's contents, under its section's header when the section
 * changes (each section is opened once: check_section_once). */
static void note_contents(parse_context *context, const char *section, const char *name, const char *value)
{
    char *contents = context->scene->contents;
    size_t used = strlen(contents), size = sizeof context->scene->contents;
    if (strcmp(context->contents_section, section) != 0) {
        snprintf(context->contents_section, sizeof context->contents_section, "%s", section);
        used += (size_t)snprintf(contents + used, size - used, "[%s]\n", section);
    }
    snprintf(contents + used, size - used, "%s = %s\n", name, value);
}

/* inih calls this for every key; returning 0 stops parsing and makes ini_parse return the line. */
static int handle_key(void *user, const char *section, const char *name, const char *value)
{
    parse_context *context = user;
    if (context->error_line)
        return 0; /* keep the first error */
    int accepted = 0, known = 0;
    for (int i = 0; i < KEY_COUNT && !known; ++i) {
        if (strcmp(KEYS[i].section, section) == 0 && strcmp(KEYS[i].key, name) == 0) {
            known = 1;
            if (context->key_line[i]) {
                snprintf(context->error, sizeof context->error, "[%s] %s is given twice (first on line %d): "
                         "expected each key once", section, name, context->key_line[i]);
                context->error_line = context->line;
                return 0;
            }
            context->key_line[i] = context->line;
            if (KEYS[i].parse == parse_steps)
                snprintf(context->steps, sizeof context->steps, "%s", value);
            accepted = KEYS[i].parse(&KEYS[i], value, context->scene, context->error,
                                     sizeof context->error) == 0;
            if (accepted)
                note_contents(context, section, name, value);
        }
    }
    if (!known)
        unknown_name(context, section, name);
    if (!accepted)
        context->error_line = context->line;
    return accepted;
}

/* A scene over surface files: they are the ensemble (seeds[i] = i picks file i) and each has its
 * own h'rms, measured when the scene runs; `slopes` or `seeds` beside them would contradict that
 * (reliability finding 4: `slopes` labelled the file and chose the theory, `seeds = 1:3` solved
 * one file three times). Returns the line at fault, 0 if none. */
static int check_files(parse_context *context)
{
    im_scene *scene = context->scene;
    int slopes = key_line(context, "surfaces", "slopes"), seeds = key_line(context, "surfaces", "seeds");
    int file = key_line(context, "surfaces", "file");
    if (slopes || seeds) {
        snprintf(context->error, sizeof context->error, "%s beside `file` (line %d): %s", slopes ? "slopes" : "seeds",
                 file, slopes ? "a file's h'rms is measured from the file, not given; remove `slopes`"
                              : "the files listed in `file` are the ensemble, and seeds would only solve the "
                                "same file again; remove `seeds`");
        return slopes ? slopes : seeds;
    }
    int count = 1;
    for (const char *c = scene->surface_file; *c; ++c)
        count += *c == ',';
    char path[IM_SCENE_PATH];
    for (int i = 0; i < count; ++i) {
        if (i >= IM_SCENE_MAX_FAMILIES || im_scene_file_path(scene, i, path, sizeof path) != IM_OK) {
            snprintf(context->error, sizeof context->error, "file: expected a comma-separated list of at most %d "
                     "non-empty paths", IM_SCENE_MAX_FAMILIES);
            return file;
        }
    }
    scene->file_count = count;
    scene->family_count = 1;
    scene->slopes[0] = NAN; /* measured when the scene runs */
    scene->seed_count = count;
    for (int i = 0; i < count; ++i)
        scene->seeds[i] = (uint64_t)i;
    return 0;
}

/* A key the punch does not have: a cone's radius (indent refuses --radius with a cone alike). */
static int check_punch_keys(parse_context *context)
{
    const im_scene *scene = context->scene;
    int radius = key_line(context, "punch", "radius");
    if (radius && (scene->punch == IM_PUNCH_CONE || scene->punch == IM_PUNCH_PROFILE)) {
        snprintf(context->error, sizeof context->error, "radius applies to shape = sphere or flat; a %s's shape is "
                 "its %s", im_punch_name(scene->punch), scene->punch == IM_PUNCH_CONE ? "alpha" : "profile");
        return radius;
    }
    return 0;
}

/* What a periodic scene cannot take, each key with its section and why: all is solved at a mean pressure
 * on the whole cell, where there is no smooth contact on a half-space (its area N*, circle or theory).
 * Its contact panels and distributions are taken at every step instead (periodic_maps.c). */
static const struct {
    const char *section, *key;
    size_t flag; /* offsetof the yes/no it sets (refused when yes), 0: refused whenever given */
    const char *why;
} PERIODIC_REFUSED[] = {
    {"loading", "load_star", 0, "N* = A(N) / delta^2 is a smooth punch's contact area on a half-space, which the "
                             "periodic cell does not have"},
    {"output", "frames", FIELD(frames),
     "the frames are a history of their own up to load_star N*; a periodic scene draws the contact map of "
     "every step of its histories with contact_panels = yes"},
    {"output", "table", FIELD(table), "the table compares A/A_cone at load_star N* with eq. (12)"},
};

/* The plots a periodic scene draws: the surfaces' own (fig3) and k's flat contacts (flat_k); the others
 * set a punch's contact on a half-space against its theory (Love's, Hertz's, eq. (12), gamma(r/a)). */
static const unsigned PERIODIC_PLOTS = IM_SCENE_PLOT_FIG3 | IM_SCENE_PLOT_FLAT_K;

/* A plot a periodic scene cannot draw, NULL if none. */
static const char *periodic_refused_plot(const im_scene *scene)
{
    for (unsigned bit = 1; im_scene_plot_name((enum im_scene_plot)bit); bit <<= 1)
        if ((scene->plots & bit) && !(bit & PERIODIC_PLOTS))
            return im_scene_plot_name((enum im_scene_plot)bit);
    return NULL;
}

/* [punch] periodic: sets which punch presses the cell (the rigid flat unless shape is given) and load
 * control, and refuses what does not apply. Returns the line at fault, 0 if none. */
static int check_periodic(parse_context *context)
{
    im_scene *scene = context->scene;
    if (!scene->periodic)
        return 0;
    const int shape = key_line(context, "punch", "shape");
    scene->periodic = shape ? IM_SCENE_PERIODIC_PUNCH : IM_SCENE_PERIODIC_FLAT;
    const int control = key_line(context, "loading", "control");
    if (control && scene->control != IM_CONTROL_MEAN_GAP) {
        snprintf(context->error, sizeof context->error, "[loading] control beside [punch] periodic: a periodic scene's "
                 "steps are mean pressures p_m (units of E*), or mean gaps with control = mean_gap");
        return control;
    }
    if (!control)
        scene->control = IM_CONTROL_LOAD; /* mean pressures */
    for (size_t i = 0; i < sizeof PERIODIC_REFUSED / sizeof *PERIODIC_REFUSED; ++i) {
        const int line = key_line(context, PERIODIC_REFUSED[i].section, PERIODIC_REFUSED[i].key);
        const size_t flag = PERIODIC_REFUSED[i].flag;
        if (line && (!flag || *(const int *)((const char *)scene + flag))) {
            snprintf(context->error, sizeof context->error, "[%s] %s beside [punch] periodic: %s",
                     PERIODIC_REFUSED[i].section, PERIODIC_REFUSED[i].key, PERIODIC_REFUSED[i].why);
            return line;
        }
    }
    const char *const punch_keys[] = {"alpha", "radius", "profile"};
    for (int i = 0; !shape && i < 3; ++i)
        if (key_line(context, "punch", punch_keys[i])) {
            snprintf(context->error, sizeof context->error, "[punch] %s beside periodic without shape: a rigid flat "
                     "is pressed on the whole cell, which has no %s; give shape for a punch repeated with the "
                     "cell", punch_keys[i], punch_keys[i]);
            return key_line(context, "punch", punch_keys[i]);
        }
    const char *plot = periodic_refused_plot(scene);
    if (plot) {
        snprintf(context->error, sizeof context->error, "plots = %s beside [punch] periodic: it sets a punch's "
                 "contact on a half-space against its smooth theory; a periodic scene draws fig3 and flat_k", plot);
        return key_line(context, "output", "plots");
    }
    if (scene->step_count < 1) {
        snprintf(context->error, sizeof context->error, "[punch] periodic needs [loading] steps: the mean "
                 "pressures p_m (units of E*) of each surface's history");
        return key_line(context, "punch", "periodic");
    }
    return 0;
}

/* Sweep lists that a scene cannot run: a list of angles for another punch, a list of generator
 * parameters beside surface files. Returns the line at fault, 0 if none. */
static int check_sweeps(parse_context *context)
{
    const im_scene *scene = context->scene;
    if (scene->alpha_count > 1 && scene->punch != IM_PUNCH_CONE) {
        snprintf(context->error, sizeof context->error, "alpha: a list of angles sweeps a cone's half-angle; "
                 "[punch] shape is not cone");
        return key_line(context, "punch", "alpha");
    }
    int points = 1, last = 0;
    const char *keys[][2] = {{"punch", "alpha"}, {"surfaces", "hurst"}, {"surfaces", "lambda_s"}};
    const int counts[] = {scene->alpha_count, scene->hurst_count, scene->lambda_s_count};
    for (int i = 0; i < 3; ++i) {
        points *= counts[i] > 1 ? counts[i] : 1;
        int line = key_line(context, keys[i][0], keys[i][1]);
        last = line > last ? line : last;
    }
    if (points > IM_SCENE_MAX_SWEEP_POINTS) {
        snprintf(context->error, sizeof context->error, "the lists of alpha, hurst and lambda_s make %d sweep "
                 "points: expected at most %d", points, IM_SCENE_MAX_SWEEP_POINTS);
        return last;
    }
    int hurst = scene->hurst_count > 1 ? key_line(context, "surfaces", "hurst") : 0;
    int lambda_s = scene->lambda_s_count > 1 ? key_line(context, "surfaces", "lambda_s") : 0;
    if (scene->surface_file[0] && (hurst || lambda_s)) {
        snprintf(context->error, sizeof context->error, "%s: a list sweeps the generated surfaces' parameter, but "
                 "the surfaces are the files of `file`", hurst ? "hurst" : "lambda_s");
        return hurst ? hurst : lambda_s;
    }
    return 0;
}

/* The largest lambda_s of a sweep (the scalar when there is no list). */
static double largest_lambda_s(const im_scene *scene)
{
    double largest = scene->surface.lambda_s;
    for (int i = 0; i < scene->lambda_s_count; ++i)
        largest = fmax(largest, scene->lambda_ss[i]);
    return largest;
}

/* The line of the first [adhesion] key given, 0 if none. */
static int adhesion_line(const parse_context *context)
{
    const char *keys[] = {"work", "range", "law"};
    for (int i = 0; i < 3; ++i)
        if (key_line(context, "adhesion", keys[i]))
            return key_line(context, "adhesion", keys[i]);
    return 0;
}

/* What [adhesion] cannot take, NULL if nothing. */
static const char *adhesion_conflict(const im_scene *scene)
{
    if (!(scene->adhesion_work > 0))
        return NULL;
    if (!(scene->adhesion_range > 0))
        return "[adhesion] work and range go together: expected both";
    if (scene->hardness > 0)
        return "[adhesion] with [material] hardness: adhesion with plasticity is not available";
    if (scene->contact_panels || scene->frames || scene->table || scene->distributions)
        return "[adhesion] with [output] contact_panels, frames, table or distributions: those are solved under "
               "load control at load_star, which an adhesive contact does not take (its histories, plots = fig5, "
               "fig6, fig7 or sphere, do)";
    if (scene->plots & (IM_SCENE_PLOT_FIG7 | IM_SCENE_PLOT_SPHERE))
        return "[adhesion] with plots = fig7 or sphere: they set repulsive contact against N* on log axes, which a "
               "pulled (negative) load leaves (fig5 and fig6 draw adhesive histories)";
    if (scene->periodic)
        return "[adhesion] with [punch] periodic: the periodic half-space has no adhesion";
    if (scene->plots & IM_SCENE_PLOT_FLAT_K)
        return "[adhesion] with plots = flat_k: its flat panels are solved in the periodic half-space, which has "
               "no adhesion";
    return NULL;
}

/* [adhesion]'s consistency: a message in context->error and the line of the [adhesion] key (or of
 * [loading] steps), 0 if consistent. */
static int check_adhesion(parse_context *context)
{
    const im_scene *scene = context->scene;
    const int given = adhesion_line(context);
    const char *conflict = given && !(scene->adhesion_work > 0) ? "[adhesion] work and range go together: expected both"
                                                                 : adhesion_conflict(scene);
    if (!conflict)
        return 0;
    snprintf(context->error, sizeof context->error, "%s", conflict);
    int line = given ? given : key_line(context, "loading", "steps");
    return line > 0 ? line : 1;
}

/* [loading] steps (kept by handle_key) into the scene: below 0 with [adhesion] only. 0, or the line of the
 * key with the message in context->error. */
static int parse_kept_steps(parse_context *context)
{
    im_scene *scene = context->scene;
    const int line = key_line(context, "loading", "steps");
    if (line && steps_parse_signed("steps", context->steps, scene->adhesion_work > 0, scene->steps, &scene->step_count,
                                   context->error, sizeof context->error) != 0)
        return line;
    return 0;
}

/* Fig. 7 draws A / A_cone against N* over the range a family's surfaces share, which one step is
 * not. Returns the line of plots at fault, 0 if none. */
static int check_fig7_steps(parse_context *context)
{
    const im_scene *scene = context->scene;
    if (!(scene->plots & IM_SCENE_PLOT_FIG7) || scene->step_count >= 2)
        return 0;
    snprintf(context->error, sizeof context->error, "plots = fig7 needs at least two [loading] steps (%d given): it "
             "draws A / A_cone against N* over the range of N* the surfaces share", scene->step_count);
    return key_line(context, "output", "plots");
}

/* Settings that contradict each other: a message citing the line of the key at fault (the later
 * of two), in context->error; returns that line (1 if no key was given), 0 if consistent. */
static int check_consistency(parse_context *context)
{
    const im_scene *scene = context->scene;
    int adhesion_line = check_adhesion(context); /* first: whether steps may go below 0 */
    if (adhesion_line)
        return adhesion_line;
    int steps_line = parse_kept_steps(context);
    if (steps_line)
        return steps_line;
    int periodic_line = check_periodic(context);
    if (periodic_line)
        return periodic_line;
    int sweep_line = check_sweeps(context);
    if (sweep_line)
        return sweep_line;
    int punch_line = check_punch_keys(context);
    if (punch_line)
        return punch_line;
    int fig7_line = check_fig7_steps(context);
    if (fig7_line)
        return fig7_line;
    if (scene->surface.lambda_r <= largest_lambda_s(scene)) {
        int r = key_line(context, "surfaces", "lambda_r"), s = key_line(context, "surfaces", "lambda_s");
        int n = key_line(context, "surfaces", "n"), m = key_line(context, "surfaces", "m");
        int r_from = r ? r : n > m ? n : m; /* a default lambda_r is the box's side: n (or m) made it */
        snprintf(context->error, sizeof context->error, "lambda_r = %g must exceed lambda_s = %g%s",
                 scene->surface.lambda_r, largest_lambda_s(scene), r ? "" : " (lambda_r defaults to the box's side)");
        int line = r_from > s ? r_from : s;
        return line > 0 ? line : 1;
    }
    if (scene->surface_file[0]) {
        int line = check_files(context);
        if (line)
            return line;
    }
    if (scene->control == IM_CONTROL_MEAN_GAP && !scene->periodic) {
        snprintf(context->error, sizeof context->error, "control = mean_gap needs [punch] periodic: the half-space "
                 "has no mean gap");
        return key_line(context, "loading", "control");
    }
    /* a history that unloads needs the cap's memory (or adhesion's); without one, unloading only
     * retraces loading and a list out of order is more likely a slip. Mean gaps load as they fall. */
    const double sense = scene->control == IM_CONTROL_MEAN_GAP ? -1 : 1;
    for (int i = 1; i < scene->step_count && !(scene->hardness > 0) && !(scene->adhesion_work > 0); ++i) {
        if (!(sense * scene->steps[i] > sense * scene->steps[i - 1])) {
            snprintf(context->error, sizeof context->error, "steps must %s: %g follows %g (a history that "
                     "unloads needs [material] hardness: without one unloading retraces loading)",
                     sense > 0 ? "increase" : "decrease (mean gaps)", scene->steps[i], scene->steps[i - 1]);
            return key_line(context, "loading", "steps");
        }
    }
    return 0;
}

/* Settings that follow from others unless given: the tolerance from the quality preset, rows =
 * columns, lambda_r = the box, output dir
 * (output/NAME under the working directory; a given one is relative to the scene file). */
static void complete(im_scene *scene, int tol_given, int ny_given, int lambda_r_given, int output_given)
{
    im_surface_params *p = &scene->surface;
    if (!tol_given)
        im_quality_tolerance(scene->quality, &scene->tol); /* validated by parse_quality */
    if (!ny_given)
        p->ny = p->nx;
    if (!lambda_r_given)
        p->lambda_r = p->nx > p->ny ? p->nx : p->ny;
    if (p->lambda_0 < p->lambda_r)
        p->lambda_0 = p->lambda_r;
    if (!output_given) {
        snprintf(scene->output_dir, sizeof scene->output_dir, "output/%s", scene->name);
    } else {
        /* like every path written in a scene, relative to the scene file (resolved from a copy:
         * the input and output of im_scene_resolve_path may not overlap) */
        char written[IM_SCENE_PATH];
        memcpy(written, scene->output_dir, sizeof written);
        im_scene_resolve_path(scene, written, scene->output_dir, sizeof scene->output_dir);
    }
}

/* A scene is a few kilobytes; a larger file is not one (and is not read whole). */
enum { SCENE_MAX_BYTES = 1 << 20 };

static int any_key_given(const parse_context *context)
{
    for (int i = 0; i < KEY_COUNT; ++i)
        if (context->key_line[i])
            return 1;
    return 0;
}

/* The defaults, and what complete() fills unless the scene gives it. */
static void begin_scene(im_scene *scene, const char *path)
{
    im_scene_defaults(scene);
    snprintf(scene->path, sizeof scene->path, "%s", path);
    scene->surface.ny = -1;
    scene->surface.lambda_r = -1;
    scene->output_dir[0] = '\0';
    scene->tol = -1;
}

/* Parses an open scene into *scene (set up by its caller) and closes the stream. */
static int parse_stream(const char *path, FILE *stream, im_scene *scene)
{
    parse_context context = {.scene = scene, .stream = stream};
    int line = ini_parse_stream(read_line, &context, handle_key, &context);
    int read_failed = ferror(context.stream), read_errno = errno;
    fclose(context.stream);
    if (line == -2)
        return im_fail(IM_ENOMEM, "%s: out of memory while parsing", path);
    /* inih's own error (a malformed line) precedes any error of ours, else it is the same line */
    if (line > 0 && line != context.error_line)
        return im_fail(IM_EFORMAT, "%s:%d: malformed line: expected [section], key = value or a comment",
                       path, line);
    if (context.error_line)
        return im_fail(IM_EFORMAT, "%s:%d: %s", path, context.error_line, context.error);
    if (read_failed)
        return im_fail(IM_EIO, "%s:%d: cannot read: %s", path, context.line + 1, strerror(read_errno));
    if (!any_key_given(&context))
        return im_fail(IM_EFORMAT, "%s: no settings: a scene asks for its outputs with keys such as [output] "
                       "plots (see docs/scenes.md)", path);
    complete(scene, scene->tol != -1, scene->surface.ny != -1, scene->surface.lambda_r != -1,
             scene->output_dir[0] != '\0');
    int inconsistent = check_consistency(&context);
    if (inconsistent)
        return im_fail(IM_EFORMAT, "%s:%d: %s", path, inconsistent, context.error);
    return IM_OK;
}

int im_scene_load(const char *path, im_scene *scene)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(scene, "scene");
    begin_scene(scene, path);
    FILE *stream;
    long long size;
    int opened = im_read_open(path, "r", IM_READ_REGULAR, &stream, &size);
    if (opened != IM_OK)
        return opened;
    if (size > SCENE_MAX_BYTES) {
        fclose(stream);
        return im_fail(IM_EINVAL, "%s: %lld bytes: expected a scene file of at most %d bytes", path, size,
                       SCENE_MAX_BYTES);
    }
    return parse_stream(path, stream, scene);
}

int scene_load_text(const char *text, const char *path, im_scene *scene)
{
    begin_scene(scene, path);
    FILE *stream = fmemopen((void *)text, strlen(text), "r");
    if (!stream)
        return im_fail(IM_ENOMEM, "%s: cannot read the scene's contents: %s", path, strerror(errno));
    return parse_stream(path, stream, scene);
}

int im_scene_file_path(const im_scene *scene, int i, char *out, size_t size)
{
    ARG_REQUIRE(scene, "scene");
    ARG_REQUIRE(out, "out");
    const char *item = scene->surface_file;
    for (int k = 0; k < i && item; ++k) {
        item = strchr(item, ',');
        item = item ? item + 1 : NULL;
    }
    if (i < 0 || !item)
        return im_fail(IM_EINVAL, "%s: file %d: the scene lists fewer files", scene->path, i);
    item += strspn(item, " \t");
    size_t length = strcspn(item, ",");
    while (length > 0 && (item[length - 1] == ' ' || item[length - 1] == '\t'))
        --length;
    if (length == 0 || length >= IM_SCENE_PATH)
        return im_fail(IM_EINVAL, "%s: file %d: an empty or overlong path", scene->path, i);
    char relative[IM_SCENE_PATH];
    memcpy(relative, item, length);
    relative[length] = '\0';
    im_scene_resolve_path(scene, relative, out, size);
    return IM_OK;
}

void im_scene_resolve_path(const im_scene *scene, const char *relative, char *out, size_t size)
{
    ARG_REQUIRE_OR(out, "out", );
    if (size > 0)
        out[0] = '\0'; /* a NULL scene or relative path gives "" */
    ARG_REQUIRE_OR(scene, "scene", );
    ARG_REQUIRE_OR(relative, "relative", );
    const char *slash = strrchr(scene->path, '/');
    size_t directory = relative[0] == '/' || !slash ? 0 : (size_t)(slash - scene->path) + 1;
    size_t length = strlen(relative);
    if (size == 0)
        return;
    /* truncated to size - 1 bytes like snprintf (scene paths are at most IM_SCENE_PATH) */
    if (directory > size - 1)
        directory = size - 1;
    if (length > size - 1 - directory)
        length = size - 1 - directory;
    memmove(out + directory, relative, length); /* relative may be out itself */
    memcpy(out, scene->path, directory);
    out[directory + length] = '\0';
}
