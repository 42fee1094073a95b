/* Keys of kept results: a hash of every input that determines a member's result, written with
 * the result, so that --resume solves again what an edited scene would compute differently. */
#include "core/fnv1a.h"
#include "scene/contents.h"
#include "scene/run_state.h"
#include "indentmap/status.h"
#include "scene/key.h"
#include "scene/progress.h"
#include "scene/punch.h"

#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

/* FNV-1a, 64 bits, over text fed piece by piece. */
typedef struct key_hash {
    uint64_t value;
} key_hash;

static void key_add_bytes(key_hash *hash, const char *bytes, size_t length)
{
    hash->value = fnv1a_add(hash->value, bytes, length);
}

/* Numbers and short words through a buffer; paths, which may be long, go to key_add_bytes. */
static void key_add(key_hash *hash, const char *format, ...) __attribute__((format(printf, 2, 3)));
static void key_add(key_hash *hash, const char *format, ...)
{
    char text[512];
    va_list arguments;
    va_start(arguments, format);
    int length = vsnprintf(text, sizeof text, format, arguments);
    va_end(arguments);
    key_add_bytes(hash, text, length < (int)sizeof text ? (size_t)length : sizeof text - 1);
}

/* The surface: generator parameters, slope and seed, or the file (path, size and time). */
static void add_surface(key_hash *hash, const im_scene *scene, int family, uint64_t seed)
{
    const im_surface_params *p = &scene->surface;
    if (scene->surface_file[0]) {
        char path[IM_SCENE_PATH] = "";
        struct stat info = {0};
        im_scene_file_path(scene, (int)seed, path, sizeof path);
        stat(path, &info);
        key_add(hash, "file ");
        key_add_bytes(hash, path, strlen(path));
        /* "readers 2": the readers now read some files differently (x y z points, decimal commas, NetCDF's
         * x:unit), so results kept from the earlier readers are solved again */
        key_add(hash, " %lld %lld.%09ld detrend %d fill %d readers 2 channel '%s';", (long long)info.st_size,
                (long long)info.st_mtim.tv_sec, info.st_mtim.tv_nsec, scene->detrend, scene->fill, scene->channel);
        if (scene->align != IM_ALIGN_NONE)
            key_add(hash, "align %d;", (int)scene->align);
        if (scene->resample_square) /* only then: the keys of results read without it stay as they were */
            key_add(hash, "resample_square;");
        if (scene->npy_order) /* likewise */
            key_add(hash, "npy_order %d;", (int)scene->npy_order);
        return;
    }
    key_add(hash, "grid %d %d %.17g;", p->nx, p->ny, p->delta);
    if (scene->slopes[family] == 0.0) {
        key_add(hash, "smooth;");
        return;
    }
    key_add(hash, "surface %.17g %.17g %.17g %.17g %d %.17g %" PRIu64 ";", p->hurst, p->lambda_s, p->lambda_r,
            p->lambda_0, (int)p->slope_definition, scene->slopes[family], seed);
}

/* A profile punch's samples, bytes and all: an edited profile file changes the key. */
static void add_profile(key_hash *hash, const im_profile *profile)
{
    const double *r, *z;
    const im_field *field;
    int count;
    im_profile_samples(profile, &r, &z, &count, &field);
    key_add(hash, "profile %d;", (int)im_profile_kind(profile));
    if (field) {
        key_add(hash, "%d %d %.17g;", field->nx, field->ny, field->delta);
        key_add_bytes(hash, (const char *)field->data, sizeof(double) * im_field_count(field));
        return;
    }
    key_add_bytes(hash, (const char *)r, sizeof(double) * (size_t)count);
    key_add_bytes(hash, (const char *)z, sizeof(double) * (size_t)count);
}

/* The punch, the material and the solver (tolerance, iteration cap, window). */
static void add_contact(key_hash *hash, const im_scene *scene)
{
    im_solver_options o = scene_solver_options(scene);
    key_add(hash, "punch %d %.17g %.17g; modulus %.17g;", scene->punch, scene->alpha_degrees, scene->radius,
            scene->modulus);
    const im_profile *profile = scene_profile(scene);
    if (profile) /* only then, so that the keys of the other punches stay as they were */
        add_profile(hash, profile);
    key_add(hash, "solver %.17g %.17g %d %d %d;", o.e_star, o.tol, o.max_iterations, o.crop, o.window_margin);
    /* only then, so that the keys of results without a cap stay as they were; "memory": results made
     * since the cap remembers its plastic flow (and load control searches the approach) differ from
     * the memoryless cap's, which --resume must not reuse */
    if (o.hardness > 0)
        key_add(hash, "hardness %.17g; memory;", o.hardness);
    if (scene->periodic) /* likewise */
        key_add(hash, "periodic %d;", scene->periodic);
    /* likewise: the GPU engine's results differ from the CPU's in the last bits (and in iterations), so
     * --resume after [solver] device is edited must not keep the other engine's */
    if (o.device != IM_DEVICE_CPU)
        key_add(hash, "device %s;", o.device == IM_DEVICE_GPU ? "gpu" : "auto");
    if (o.adhesion_work > 0) /* likewise: only then; the Maugis-Dugdale law's keys as before the law was a choice */
        key_add(hash, "adhesion %s %.17g %.17g;",
                o.adhesion_law == IM_ADHESION_EXPONENTIAL ? "exponential" : "maugis-dugdale", o.adhesion_work,
                o.adhesion_range);
    if (o.adhesion_zone > 0) /* likewise */
        key_add(hash, "adhesion zone %.17g;", o.adhesion_zone);
}

uint64_t scene_checksum(const char *bytes, size_t length)
{
    key_hash hash = {FNV1A_START};
    key_add_bytes(&hash, bytes, length);
    return hash.value;
}

int scene_kept_damaged(const im_scene_run_options *options, const char *path, const char *why)
{
    scene_warn(options, "%s is damaged (%s): solving it again", path, why);
    return 0;
}

int scene_load_star_step(const im_scene *scene)
{
    const int at_n_star = scene->control == IM_CONTROL_LOAD && !scene->periodic && !scene_steps_are_loads(scene);
    for (int i = 0; at_n_star && i < scene->step_count; ++i)
        if (fabs(scene->steps[i] - scene->load_star) <= 1e-12 * scene->load_star)
            return i;
    return -1;
}

uint64_t scene_result_key(const im_scene *scene, int family, uint64_t seed, enum scene_result_kind kind)
{
    key_hash hash = {FNV1A_START};
    key_add(&hash, "indentmap result 1;");
    add_surface(&hash, scene, family, seed);
    add_contact(&hash, scene);
    if (kind != SCENE_RESULT_HISTORY) {
        key_add(&hash, "load_star %.17g;", scene->load_star);
        if (kind == SCENE_RESULT_FRAMED)
            key_add(&hash, "frames %d;", scene->frame_count);
    } else {
        key_add(&hash, "control %d; steps", scene->control);
        for (int i = 0; i < scene->step_count; ++i)
            key_add(&hash, " %.17g", scene->steps[i]);
        if (scene->table && scene_load_star_step(scene) >= 0)
            key_add(&hash, "; the table's state at load_star %.17g", scene->load_star);
    }
    return hash.value;
}

int scene_key_matches(const im_scene_run_options *options, const char *path, uint64_t kept, uint64_t wanted)
{
    if (kept == wanted)
        return 1;
    /* a warning, logged even when quiet: a kept result is being replaced */
    if (kept == 0)
        scene_warn(options,
                   "%s cannot be read back (damaged, or written by an older version without a key): "
                   "solving it again",
                   path);
    else
        scene_warn(options,
                   "%s was made from other inputs (key %016" PRIx64 ", the scene's is %016" PRIx64
                   "): solving it again",
                   path, kept, wanted);
    return 0;
}
