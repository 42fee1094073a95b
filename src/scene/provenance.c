/* A scene run's provenance: the scene's contents and its inputs' SHA-256 in run.json, so that the run
 * can be made again from its record alone (im_scene_load_record; docs/scenes.md, "Provenance"). */
#include "scene/provenance.h"
#include "scene/contents.h"
#include "front/front.h"
#include "paper/figures.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <limits.h>
#include <stdio.h>
#include <string.h>

static const char GIVEN[] = "every key the scene file set, as parsed (values trimmed, comments dropped); the keys it "
                            "did not set take their defaults (include/indentmap/scene.h)";

/* One "key = value" line of the contents under section; IM_EFORMAT when a value is not UTF-8. */
static int add_key_line(const im_scene *scene, json_t *section, const char *line, size_t length)
{
    const char *equals = strstr(line, " = ");
    if (!section || !equals || equals > line + length)
        return im_fail(IM_EFORMAT, "%s: the scene's contents hold a line that is not key = value", scene->path);
    char key[64];
    snprintf(key, sizeof key, "%.*s", (int)(equals - line), line);
    const char *value = equals + 3;
    json_t *text = json_stringn(value, length - (size_t)(value - line));
    if (!text)
        return im_fail(IM_EFORMAT, "%s: [%s] its value is not UTF-8: a record holds text (write the value in UTF-8)",
                       scene->path, key);
    json_object_set_new(section, key, text);
    return IM_OK;
}

/* The contents "[section]\nkey = value\n..." as {"section": {"key": "value"}}, in their order. */
static json_t *contents_sections(const im_scene *scene)
{
    json_t *sections = json_object(), *section = NULL;
    int status = IM_OK;
    for (const char *line = scene->contents; *line && status == IM_OK;) {
        size_t length = strcspn(line, "\n");
        if (line[0] == '[') {
            char name[32];
            snprintf(name, sizeof name, "%.*s", (int)(length - 2), line + 1);
            section = json_object();
            json_object_set_new(sections, name, section);
        } else {
            status = add_key_line(scene, section, line, length);
        }
        line += length + (line[length] == '\n');
    }
    if (status == IM_OK)
        return sections;
    json_decref(sections);
    return NULL;
}

int scene_contents_record(const im_scene *scene, json_t **record)
{
    char absolute[PATH_MAX], text[4 * PATH_MAX + 1];
    *record = NULL;
    int status = im_path_absolute(scene->path, absolute, sizeof absolute);
    if (status != IM_OK)
        return status;
    int escaped = im_path_utf8(absolute, text, sizeof text);
    json_t *sections = contents_sections(scene);
    if (!sections)
        return IM_EFORMAT;
    *record = json_pack("{s:s, s:s, s:o}", "scene_file", text, "given", GIVEN, "sections", sections);
    if (*record && escaped) /* --from-record refuses it: its relative paths hang on the bytes escaped here */
        json_object_set_new(*record, "scene_file_encoding", json_string("escaped"));
    return *record ? IM_OK : im_fail(IM_ENOMEM, "run.json: out of memory");
}

int scene_input(const im_scene *scene, int i, int profile_resolved, const char **key, char *path, size_t size)
{
    if (i < scene->file_count) {
        *key = "[surfaces] file";
        return im_scene_file_path(scene, i, path, size) == IM_OK;
    }
    if (i > scene->file_count || !scene->profile_file[0])
        return 0;
    *key = "[punch] profile";
    if (profile_resolved)
        snprintf(path, size, "%s", scene->profile_file);
    else
        im_scene_resolve_path(scene, scene->profile_file, path, size);
    return 1;
}

int scene_inputs_record(const im_scene *scene, json_t **record)
{
    json_t *inputs = json_array();
    const char *key;
    char path[IM_SCENE_PATH];
    int status = inputs ? IM_OK : im_fail(IM_ENOMEM, "run.json: out of memory");
    for (int i = 0; status == IM_OK && scene_input(scene, i, 1, &key, path, sizeof path); ++i)
        status = run_record_add_input(inputs, key, path);
    if (status != IM_OK) {
        json_decref(inputs);
        inputs = NULL;
    }
    *record = inputs;
    return status;
}

int scene_figure_texts(const im_scene *scene, const im_png_text *own, int own_count, run_figure_texts *texts)
{
    json_t *inputs;
    *texts = (run_figure_texts){0};
    if (own_count > 4)
        return im_fail(IM_EINVAL, "scene_figure_texts: %d texts of the figure's own: expected at most 4", own_count);
    int status = scene_inputs_record(scene, &inputs);
    if (status != IM_OK)
        return status;
    im_png_text given[6] = {{"Source", scene->path}};
    int count = 1;
    if (scene->contents[0])
        given[count++] = (im_png_text){PAPER_SCENE_CONTENTS, scene->contents};
    for (int i = 0; i < own_count; ++i)
        given[count++] = own[i];
    status = run_figure_texts_make(given, count, inputs, texts);
    json_decref(inputs);
    return status;
}

/* ---- the scene rebuilt from a record ---- */

/* The recorded sections as scene text, "[section]\nkey = value\n..." (im_scene.contents). */
static int contents_text(const char *record, json_t *sections, char *text, size_t size)
{
    size_t used = 0;
    const char *name, *key;
    json_t *section, *value;
    json_object_foreach(sections, name, section)
    {
        used += (size_t)snprintf(text + used, used < size ? size - used : 0, "[%s]\n", name);
        json_object_foreach(section, key, value)
        {
            if (!json_is_string(value))
                return im_fail(IM_EFORMAT, "%s: scene_contents [%s] %s: expected a string, the value as parsed",
                               record, name, key);
            used += (size_t)snprintf(text + used, used < size ? size - used : 0, "%s = %s\n", key,
                                     json_string_value(value));
        }
    }
    if (used >= size)
        return im_fail(IM_EFORMAT, "%s: scene_contents: more than %zu bytes: expected a scene's keys", record, size);
    return IM_OK;
}

/* The scene's text and its file's path from the record's scene_contents. */
static int recorded_scene(const char *record, json_t *root, char *text, size_t size, const char **scene_file)
{
    json_t *contents = json_object_get(root, "scene_contents");
    json_t *sections = json_object_get(contents, "sections");
    *scene_file = json_string_value(json_object_get(contents, "scene_file"));
    if (!json_is_object(sections) || !*scene_file)
        return im_fail(IM_EFORMAT,
                       "%s: no scene_contents with its sections and scene_file: expected the record of a "
                       "scene run by a version that keeps them (issue 31); run the scene file instead",
                       record);
    if (json_object_get(contents, "scene_file_encoding"))
        return im_fail(IM_EFORMAT,
                       "%s: scene_file %s is a path that was not UTF-8, recorded escaped: the scene's "
                       "relative paths cannot be resolved from it; run the scene file instead",
                       record, *scene_file);
    return contents_text(record, sections, text, size);
}

/* Each input of the rebuilt scene against the record's: the same number, each the same SHA-256. */
static int check_inputs(const char *record, json_t *root, const im_scene *scene)
{
    json_t *inputs = json_object_get(root, "inputs");
    const char *key;
    char path[IM_SCENE_PATH];
    size_t count = 0;
    for (; scene_input(scene, (int)count, 0, &key, path, sizeof path); ++count) {
        const char *recorded = json_string_value(json_object_get(json_array_get(inputs, count), "sha256"));
        if (!recorded)
            return im_fail(IM_EFORMAT, "%s: inputs: no SHA-256 of %s %s: expected one for each input", record, key,
                           path);
        int status = run_record_check_input(record, key, path, recorded);
        if (status != IM_OK)
            return status;
    }
    if (count != json_array_size(inputs))
        return im_fail(IM_EFORMAT, "%s: inputs: %zu recorded, the scene has %zu: expected one for each input", record,
                       json_array_size(inputs), count);
    return IM_OK;
}

static int rebuild(const char *record, json_t *root, im_scene *scene)
{
    char text[IM_SCENE_CONTENTS];
    const char *scene_file;
    int status = run_record_check_origin(record, root, "indentmap run", "a scene run");
    if (status == IM_OK)
        status = recorded_scene(record, root, text, sizeof text, &scene_file);
    if (status == IM_OK && (status = scene_load_text(text, scene_file, scene)) != IM_OK)
        return im_fail_context(status, "%s: the recorded scene", record);
    if (status == IM_OK)
        status = check_inputs(record, root, scene);
    if (status != IM_OK)
        return status;
    snprintf(scene->from_record, sizeof scene->from_record, "%s", record);
    scene->recorded_plans = json_is_true(json_object_get(json_object_get(root, "solver"), "fftw_wisdom"));
    return IM_OK;
}

int scene_load_record(const char *record, im_scene *scene)
{
    json_t *root;
    int status = run_record_load(record, &root);
    if (status != IM_OK)
        return status;
    status = rebuild(record, root, scene);
    json_decref(root);
    return status;
}
