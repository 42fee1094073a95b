/* The paths a scene names (surface files, profile, output folder): relative to the scene file. */
#include "indentmap/scene.h"
#include "scene/contents.h"
#include "core/args.h"
#include "indentmap/status.h"

#include <string.h>

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
