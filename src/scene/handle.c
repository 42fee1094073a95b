/* The scene handle of scene.h: made by a load, read through its accessors, freed. */
#include "indentmap/scene.h"
#include "scene/contents.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "scene/provenance.h"

#include <stdlib.h>
#include <string.h>

/* A new scene filled by load from source; NULL in *out on an error. */
static int load_new(int (*load)(const char *, im_scene *), const char *source, im_scene **out)
{
    *out = NULL;
    im_scene *scene = malloc(sizeof *scene);
    if (!scene)
        return im_fail(IM_ENOMEM, "%s: allocation of the scene failed", source);
    int status = load(source, scene);
    if (status != IM_OK) {
        free(scene);
        return status;
    }
    *out = scene;
    return IM_OK;
}

int im_scene_load(const char *path, im_scene **scene)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(scene, "scene");
    return load_new(scene_load_file, path, scene);
}

int im_scene_load_record(const char *record, im_scene **scene)
{
    ARG_REQUIRE(record, "record");
    ARG_REQUIRE(scene, "scene");
    return load_new(scene_load_record, record, scene);
}

void im_scene_free(im_scene *scene) { free(scene); }

const char *im_scene_path(const im_scene *scene)
{
    ARG_REQUIRE_OR(scene, "scene", "");
    return scene->path;
}

const char *im_scene_name(const im_scene *scene)
{
    ARG_REQUIRE_OR(scene, "scene", "");
    return scene->name;
}

const char *im_scene_output_dir(const im_scene *scene)
{
    ARG_REQUIRE_OR(scene, "scene", "");
    return scene->output_dir;
}

int im_scene_set_output_dir(im_scene *scene, const char *dir)
{
    ARG_REQUIRE(scene, "scene");
    ARG_REQUIRE(dir, "dir");
    size_t length = strlen(dir);
    if (length >= sizeof scene->output_dir) /* the message could not hold the whole path */
        return im_fail(IM_EINVAL, "%.64s...: %zu bytes: expected a path shorter than %zu bytes", dir, length,
                       sizeof scene->output_dir);
    memcpy(scene->output_dir, dir, length + 1);
    return IM_OK;
}

void im_scene_set_wisdom_path(im_scene *scene, const char *path)
{
    ARG_REQUIRE_OR(scene, "scene", );
    scene->wisdom_path = path;
}

int im_scene_recorded_plans(const im_scene *scene)
{
    ARG_REQUIRE_OR(scene, "scene", -1);
    return scene->recorded_plans;
}

int im_scene_asks_for_output(const im_scene *scene)
{
    ARG_REQUIRE_OR(scene, "scene", 0);
    return scene->table || scene->plots || scene->contact_panels || scene->frames || scene->frames3d ||
           scene->distributions || scene->periodic;
}

int im_scene_renders(const im_scene *scene)
{
    ARG_REQUIRE_OR(scene, "scene", 0);
    return scene->contact_panels || scene->frames;
}
