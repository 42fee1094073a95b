/* OUTPUT/run.json of a scene run: which quality preset and solver tolerance made its outputs. */
#include "scene/scene_internal.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <jansson.h>
#include <stdlib.h>
#include <string.h>

int scene_write_record(const im_scene *scene)
{
    char path_text[4 * IM_SCENE_PATH + 1]; /* a path is bytes; JSON is UTF-8 */
    int escaped = im_path_utf8(scene->path, path_text, sizeof path_text);
    json_t *root = json_pack("{s:s, s:s, s:s, s:{s:s, s:f}}", "program", "indentmap run", "version", IM_VERSION,
                             "scene", path_text, "solver", "quality", scene->quality, "tol", scene->tol);
    if (root && escaped)
        json_object_set_new(root, "scene_encoding", json_string("escaped"));
    char *text = root ? json_dumps(root, JSON_INDENT(2) | JSON_REAL_PRECISION(17)) : NULL;
    json_decref(root);
    char path[IM_SCENE_PATH + 16];
    int status = text ? scene_output_path(scene, "run.json", path, sizeof path) : im_fail(IM_ENOMEM, "run.json");
    if (status == IM_OK) {
        size_t length = strlen(text);
        text[length] = '\n'; /* json_dumps leaves room: its terminator becomes the newline */
        status = im_write_file_atomic(path, text, length + 1);
    }
    free(text);
    return status;
}
