/* The keys a scene file may give: one table, section by section, with each key's parser, destination,
 * range and capacity; the defaults of the keys not given, and the settings that follow from others. */
#include "scene/keys.h"
#include "scene/contents.h"
#include "core/args.h"
#include "indentmap/solver.h"
#include "scene/names.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#define FIELD(name) offsetof(im_scene, name)

static const key_spec KEYS[] = {
    {"scene", "name", scene_parse_name, FIELD(name), 0, 0, NULL, sizeof(((im_scene *)0)->name), 0},
    {"scene", "output", scene_parse_string, FIELD(output_dir), 0, 0, NULL, IM_SCENE_PATH, 0},
    {"scene", "quality", scene_parse_quality, FIELD(quality), 0, 0, NULL, sizeof(((im_scene *)0)->quality), 0},
    {"surfaces", "n", scene_parse_int, FIELD(surface.nx), 8, IM_FIELD_MAX_SIDE, NULL, 0, 0},
    {"surfaces", "m", scene_parse_int, FIELD(surface.ny), 8, IM_FIELD_MAX_SIDE, NULL, 0, 0},
    {"surfaces", "hurst", scene_parse_sweep_list, FIELD(hursts), 0.01, 0.99, NULL, IM_SCENE_MAX_SWEEP,
     FIELD(hurst_count)},
    {"surfaces", "lambda_s", scene_parse_sweep_list, FIELD(lambda_ss), 2, 1e9, NULL, IM_SCENE_MAX_SWEEP,
     FIELD(lambda_s_count)},
    {"surfaces", "lambda_r", scene_parse_double, FIELD(surface.lambda_r), 2, 1e9, NULL, 0, 0},
    {"surfaces", "lambda_0", scene_parse_double, FIELD(surface.lambda_0), 2, 1e9, NULL, 0, 0},
    {"surfaces", "slope_definition", scene_parse_choice, FIELD(surface.slope_definition), 0, 0, "spectral|fd", 0, 0},
    {"surfaces", "slopes", scene_parse_double_list, FIELD(slopes), 0, 10, NULL, IM_SCENE_MAX_FAMILIES,
     FIELD(family_count)},
    {"surfaces", "seeds", scene_parse_seeds, FIELD(seeds), 0, 0, NULL, IM_SCENE_MAX_FAMILIES, 0},
    {"surfaces", "file", scene_parse_string, FIELD(surface_file), 0, 0, NULL, IM_SCENE_PATH, 0},
    {"surfaces", "detrend", scene_parse_choice, FIELD(detrend), 0, 0, "none|plane|curvature", 0, 0},
    {"surfaces", "align", scene_parse_choice, FIELD(align), 0, 0, "none|median|mean|line", 0, 0},
    {"surfaces", "fill", scene_parse_bool, FIELD(fill), 0, 0, NULL, 0, 0},
    {"surfaces", "npy_order", scene_parse_choice, FIELD(npy_order), 0, 0, "sidecar|yx|xy", 0, 0},
    {"surfaces", "channel", scene_parse_string, FIELD(channel), 0, 0, NULL, 64, 0},
    {"surfaces", "resample_square", scene_parse_bool, FIELD(resample_square), 0, 0, NULL, 0, 0},
    {"punch", "shape", scene_parse_punch, FIELD(punch), 0, 0, NULL, 0, 0},
    {"punch", "profile", scene_parse_string, FIELD(profile_file), 0, 0, NULL, IM_SCENE_PATH, 0},
    {"punch", "alpha", scene_parse_sweep_list, FIELD(alphas), 1e-9, 90 - 1e-9, NULL, IM_SCENE_MAX_SWEEP,
     FIELD(alpha_count)},
    {"punch", "radius", scene_parse_double, FIELD(radius), 1e-9, 1e12, NULL, 0, 0},
    {"punch", "periodic", scene_parse_bool, FIELD(periodic), 0, 0, NULL, 0, 0},
    {"material", "modulus", scene_parse_double, FIELD(modulus), 1e-300, 1e300, NULL, 0, 0},
    {"material", "hardness", scene_parse_double, FIELD(hardness), 1e-300, 1e300, NULL, 0, 0},
    {"loading", "control", scene_parse_choice, FIELD(control), 0, 0, "displacement|load|mean_gap", 0, 0},
    {"loading", "load_star", scene_parse_double, FIELD(load_star), 0, 1e15, NULL, 0, 0},
    {"loading", "steps", scene_parse_later, FIELD(steps), 0, 0, NULL, 0, 0},
    {"output", "contact_panels", scene_parse_bool, FIELD(contact_panels), 0, 0, NULL, 0, 0},
    {"output", "frames", scene_parse_bool, FIELD(frames), 0, 0, NULL, 0, 0},
    {"output", "frames3d", scene_parse_bool, FIELD(frames3d), 0, 0, NULL, 0, 0},
    {"output", "page_embed", scene_parse_bool, FIELD(page_embed), 0, 0, NULL, 0, 0},
    {"output", "table", scene_parse_bool, FIELD(table), 0, 0, NULL, 0, 0},
    {"output", "distributions", scene_parse_bool, FIELD(distributions), 0, 0, NULL, 0, 0},
    {"output", "animation", scene_parse_choice, FIELD(animation), 0, 0, "none|gif|mp4|both", 0, 0},
    {"output", "colormap", scene_parse_choice, FIELD(colormap), 0, 0, "viridis|cividis|magma|inferno|grey", 0, 0},
    {"output", "log_norm", scene_parse_bool, FIELD(log_norm), 0, 0, NULL, 0, 0},
    {"output", "frames_slope", scene_parse_double, FIELD(frames_slope), 0, 10, NULL, 0, 0},
    {"output", "frames_clip", scene_parse_double, FIELD(frames_clip), 0, 50 - 1e-9, NULL, 0, 0},
    {"output", "contact_panels_clip", scene_parse_double, FIELD(contact_panels_clip), 0, 50 - 1e-9, NULL, 0, 0},
    {"output", "frame_count", scene_parse_int, FIELD(frame_count), 1, 10000, NULL, 0, 0},
    {"output", "frame_rate", scene_parse_double, FIELD(frame_rate), 0.01, 100, NULL, 0, 0},
    {"output", "frame_scale", scene_parse_int, FIELD(frame_scale), 1, 16, NULL, 0, 0},
    {"output", "frame3d_width", scene_parse_int, FIELD(frame3d_width), 64, 7680, NULL, 0, 0},
    {"output", "frame3d_height", scene_parse_int, FIELD(frame3d_height), 64, 4320, NULL, 0, 0},
    {"adhesion", "work", scene_parse_double, FIELD(adhesion_work), 1e-300, 1e300, NULL, 0, 0},
    {"adhesion", "range", scene_parse_double, FIELD(adhesion_range), 1e-300, 1e300, NULL, 0, 0},
    {"adhesion", "law", scene_parse_adhesion_law, FIELD(adhesion_law), 0, 0, "maugis-dugdale|exponential", 0, 0},
    {"adhesion", "zone", scene_parse_double, FIELD(adhesion_zone), 1e-300, 1e300, NULL, 0, 0},
    {"solver", "tol", scene_parse_double, FIELD(tol), IM_SOLVER_TOL_MIN, IM_SOLVER_TOL_MAX, NULL, 0, 0},
    {"solver", "device", scene_parse_choice, FIELD(device), 0, 0, "cpu|gpu|auto", 0, 0},
    {"output", "plots", scene_parse_plots, FIELD(plots), 0, 0, NULL, 0, 0},
};
_Static_assert(sizeof KEYS / sizeof KEYS[0] == SCENE_KEY_COUNT, "SCENE_KEY_COUNT counts KEYS");

const key_spec *scene_key(int index) { return &KEYS[index]; }

int scene_key_index(const char *section, const char *key)
{
    for (int i = 0; i < SCENE_KEY_COUNT; ++i)
        if (strcmp(KEYS[i].section, section) == 0 && strcmp(KEYS[i].key, key) == 0)
            return i;
    return -1;
}

int scene_section_exists(const char *section)
{
    for (int i = 0; i < SCENE_KEY_COUNT; ++i)
        if (strcmp(KEYS[i].section, section) == 0)
            return 1;
    return 0;
}

const char *im_scene_suggest_key(const char *section, const char *word)
{
    ARG_REQUIRE_OR(word, "word", NULL);
    const char *best = NULL;
    size_t best_distance = strlen(word) / 2 + 1;
    for (int i = 0; i < SCENE_KEY_COUNT; ++i) {
        if (section && strcmp(KEYS[i].section, section) != 0)
            continue;
        const char *candidate = section ? KEYS[i].key : KEYS[i].section;
        size_t distance = scene_edit_distance(word, candidate);
        if (distance < best_distance) {
            best_distance = distance;
            best = candidate;
        }
    }
    return best;
}

void scene_defaults(im_scene *scene)
{
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
    /* forces as every front end draws them (colormap.h: im_colormap_range_norm) */
    scene->colormap = IM_COLORMAP_MAGMA;
    scene->log_norm = 1;
    scene->recorded_plans = -1;
}

void scene_complete(im_scene *scene, int tol_given, int ny_given, int lambda_r_given, int output_given)
{
    im_surface_params *p = &scene->surface;
    if (!tol_given)
        im_quality_tolerance(scene->quality, &scene->tol); /* validated by scene_parse_quality */
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
