/* The surfaces of a scene: generated per family and seed, or read from its files (measured first,
 * checked to share one grid). */
#include "indentmap/scene.h"
#include "scene/contents.h"
#include "scene/run_state.h"

#include "front/front.h"
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"
#include "scene/surfaces.h"

#include <jansson.h>
#include <math.h>
#include <string.h>

/* File i of the scene, read and prepared as it is solved; info (may be NULL): how it was read. */
static int file_surface(const im_scene *scene, int i, im_field **out, im_surface_read_info *info)
{
    char path[IM_SCENE_PATH];
    int status = im_scene_file_path(scene, i, path, sizeof path);
    im_surface_read_options read = {.fill = scene->fill,
                                    .resample_square = scene->resample_square,
                                    .npy_order = scene->npy_order};
    memcpy(read.channel, scene->channel, sizeof read.channel);
    if (status == IM_OK)
        status = im_surface_read_with(path, &read, out, info);
    if (status == IM_OK && ((status = im_surface_align_rows(*out, scene->align)) != IM_OK ||
                            (status = im_surface_detrend(*out, scene->detrend)) != IM_OK))
        im_fail_context(status, "%s", path);
    if (status != IM_OK && *out) {
        im_field_free(*out);
        *out = NULL;
    }
    return status;
}

/* An ensemble of files shares one grid and spacing (the panels, limits and sums assume it). */
static int check_same_grid(const im_scene *scene, const im_field *first, const im_field *other, int i)
{
    if (other->nx == first->nx && other->ny == first->ny && other->delta == first->delta &&
        strcmp(other->unit, first->unit) == 0)
        return IM_OK;
    char a[IM_SCENE_PATH], b[IM_SCENE_PATH];
    im_scene_file_path(scene, 0, a, sizeof a);
    im_scene_file_path(scene, i, b, sizeof b);
    return im_fail(IM_EFORMAT,
                   "%s: file: %s is %d x %d with delta %g %s but %s is %d x %d with delta %g %s: the "
                   "files of an ensemble share one grid",
                   scene->path, b, other->nx, other->ny, other->delta, other->unit, a, first->nx, first->ny,
                   first->delta, first->unit);
}

/* Whether file i's sidecar names a generator that targeted the spectral h'rms (`indentmap surface`'s
 * default): its h'rms is then that target, as a generated family's is. */
static int generated_spectral(const im_scene *scene, int i)
{
    char path[IM_SCENE_PATH];
    return im_scene_file_path(scene, i, path, sizeof path) == IM_OK &&
           surface_sidecar_slope_definition(path) == IM_SLOPE_SPECTRAL;
}

/* The h'rms definition of the files, one for the ensemble, into state with what chose it. Spectral when
 * the scene is solved as a periodic cell, or every file is a generated surface of spectral h'rms (its
 * sidecar says so): generated families are measured by their target, the spectral h'rms of the grid
 * (realised within 2 ulp), so a generated surface written to a file and read back gives the numbers it
 * gave generated. Else forward differences, `indent`'s rule for a measured surface: a scan's spectrum
 * counts the steps across its edges, and one whose edges meet may still hold noise up to the pixel, which
 * the spectrum weighs more (shared test data bcrf-1.bcrf: edges meeting, spectral h'rms 1.23 times). */
static void choose_slope_definition(const im_scene *scene, scene_run_state *state)
{
    int generated = 1;
    for (int i = 0; i < scene->file_count && generated; ++i)
        generated = generated_spectral(scene, i);
    const int spectral = scene->periodic || generated;
    state->file_slope_definition = spectral ? IM_SLOPE_SPECTRAL : IM_SLOPE_FINITE_DIFFERENCE;
    state->file_slope_reason =
        scene->periodic ? "default: a periodic cell ([punch] periodic)"
        : generated     ? "default: generated surfaces (every file's sidecar names a generator of spectral h'rms)"
                        : "default: measured surfaces (not every file's sidecar names a generator of spectral "
                          "h'rms)";
}

int scene_measure_files(im_scene *scene, scene_run_state *state)
{
    im_field *first = NULL;
    double sum_squares = 0.0;
    int status = IM_OK;
    choose_slope_definition(scene, state);
    for (int i = 0; i < scene->file_count && status == IM_OK; ++i) {
        im_field *surface = NULL;
        im_surface_read_info info;
        status = file_surface(scene, i, &surface, &info);
        if (status == IM_OK) {
            state->file_spacing_differences[i] = info.spacing_difference;
            state->file_resampled[i] = info.resampled[0] != '\0';
            memcpy(state->file_assumed[i], info.assumed, sizeof state->file_assumed[i]);
        }
        if (status == IM_OK && first)
            status = check_same_grid(scene, first, surface, i);
        if (status == IM_OK)
            status = im_surface_slope_rms(surface, (enum im_slope_definition)state->file_slope_definition,
                                          &state->file_slopes[i]);
        sum_squares += status == IM_OK ? state->file_slopes[i] * state->file_slopes[i] : 0.0;
        if (!first)
            first = surface;
        else
            im_field_free(surface);
    }
    if (status == IM_OK && first) { /* the grid the scene's records and checks describe */
        scene->surface.nx = first->nx;
        scene->surface.ny = first->ny;
        scene->surface.delta = first->delta;
        memcpy(scene->file_unit, first->unit, sizeof scene->file_unit);
        scene->slopes[0] = sqrt(sum_squares / scene->file_count);
    }
    im_field_free(first);
    return status;
}

int scene_surface(const im_scene *scene, int family, uint64_t seed, im_field **out)
{
    if (scene->surface_file[0])
        return file_surface(scene, (int)seed, out, NULL);
    if (scene->slopes[family] == 0.0)
        return im_field_create(scene->surface.nx, scene->surface.ny, scene->surface.delta, out);
    im_surface_params params = scene->surface;
    params.target = IM_TARGET_SLOPE;
    params.slope_rms = scene->slopes[family];
    params.seed = seed;
    return im_surface_generate(&params, out);
}

double scene_member_slope(const im_scene *scene, int family, uint64_t seed)
{
    return scene->file_count > 0 ? scene->run->file_slopes[seed] : scene->slopes[family];
}
