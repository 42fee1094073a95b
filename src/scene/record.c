/* OUTPUT/run.json of a scene run: which quality preset and solver tolerance made its outputs. */
#include "scene/outputs.h"
#include "scene/record.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <jansson.h>
#include <stdlib.h>
#include <string.h>

/* The files of a scene over files, each with its measured h'rms, and what that h'rms is. */
static json_t *files_record(const im_scene *scene)
{
    static const char *const DETREND[] = {"none", "plane", "curvature"};
    json_t *files = json_array();
    for (int i = 0; i < scene->file_count; ++i) {
        char path[IM_SCENE_PATH];
        im_scene_file_path(scene, i, path, sizeof path);
        json_array_append_new(files, json_pack("{s:s, s:f}", "path", path, "slope_rms", scene->file_slopes[i]));
    }
    return json_pack("{s:o, s:f, s:s, s:s, s:b, s:f, s:s}", "files", files, "slope_rms", scene->slopes[0],
                     "slope_definition", "forward differences of each surface as solved; the ensemble's is their "
                     "root mean square, the h'rms of eq. (12)", "detrend", DETREND[scene->detrend], "fill",
                     scene->fill, "delta", scene->surface.delta, "length_unit",
                     scene->file_unit[0] ? scene->file_unit : "delta");
}

int scene_write_record(const im_scene *scene)
{
    char path_text[4 * IM_SCENE_PATH + 1]; /* a path is bytes; JSON is UTF-8 */
    int escaped = im_path_utf8(scene->path, path_text, sizeof path_text);
    json_t *root = json_pack("{s:s, s:s, s:s, s:{s:s, s:f}}", "program", "indentmap run", "version", IM_VERSION,
                             "scene", path_text, "solver", "quality", scene->quality, "tol", scene->tol);
    if (root && escaped)
        json_object_set_new(root, "scene_encoding", json_string("escaped"));
    if (root && scene->file_count > 0)
        json_object_set_new(root, "surface_files", files_record(scene));
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
