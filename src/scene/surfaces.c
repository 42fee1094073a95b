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

/* Both h'rms of one file as solved, and whether its edges meet. */
static int measure_file(const im_field *surface, double *spectral, double *forward, int *periodic)
{
    double edge, inner;
    *periodic = !periodic_edge_mismatch(surface, &edge, &inner);
    int status = im_surface_slope_rms(surface, IM_SLOPE_SPECTRAL, spectral);
    return status == IM_OK ? im_surface_slope_rms(surface, IM_SLOPE_FINITE_DIFFERENCE, forward) : status;
}

/* The files' h'rms into state, their root mean square into slopes[0]: one definition for the ensemble,
 * front.h's rule (periodic_slope_definition) with edges that meet when every file's do, the rule generated
 * families follow (their target is the spectral h'rms of the grid, realised to about 1e-16): a generated
 * surface written to a file and read back gives the numbers it gave generated. */
static void set_file_slopes(im_scene *scene, scene_run_state *state, const double *spectral, const double *forward,
                            int all_periodic)
{
    state->file_slope_definition = periodic_slope_definition(scene->periodic != 0, all_periodic,
                                                             &state->file_slope_reason);
    double sum_squares = 0.0;
    for (int i = 0; i < scene->file_count; ++i) {
        state->file_slopes[i] = state->file_slope_definition == IM_SLOPE_SPECTRAL ? spectral[i] : forward[i];
        sum_squares += state->file_slopes[i] * state->file_slopes[i];
    }
    scene->slopes[0] = sqrt(sum_squares / scene->file_count);
}

int scene_measure_files(im_scene *scene, scene_run_state *state)
{
    im_field *first = NULL;
    double spectral[IM_SCENE_MAX_FAMILIES], forward[IM_SCENE_MAX_FAMILIES];
    int status = IM_OK, all_periodic = 1;
    for (int i = 0; i < scene->file_count && status == IM_OK; ++i) {
        im_field *surface = NULL;
        im_surface_read_info info;
        int periodic = 0;
        status = file_surface(scene, i, &surface, &info);
        if (status == IM_OK) {
            state->file_spacing_differences[i] = info.spacing_difference;
            state->file_resampled[i] = info.resampled[0] != '\0';
        }
        if (status == IM_OK && first)
            status = check_same_grid(scene, first, surface, i);
        if (status == IM_OK)
            status = measure_file(surface, &spectral[i], &forward[i], &periodic);
        all_periodic = all_periodic && periodic;
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
        set_file_slopes(scene, state, spectral, forward, all_periodic);
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
