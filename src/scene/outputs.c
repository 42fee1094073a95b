/* Where a scene's outputs go: paths under its output folder, figures as PNG and PDF (the folder itself:
 * front/run_folder.h). */
#include "indentmap/plot.h"
#include "scene/contents.h"
#include "indentmap/status.h"
#include "scene/manifest.h"
#include "scene/outputs.h"
#include "scene/provenance.h"

#include <stdio.h>

int scene_open_output(const im_scene *scene, const char *relative, im_atomic_file *file)
{
    char path[IM_SCENE_PATH];
    int status = scene_output_path(scene, relative, path, sizeof path);
    return status == IM_OK ? im_atomic_open(file, path) : status;
}

int scene_write_png_pdf(const im_scene *scene, const char *name,
                        int (*draw)(const im_scene *, const void *, const paper_file *), const void *data)
{
    run_figure_texts texts;
    int status = scene_figure_texts(scene, NULL, 0, &texts);
    const char *extensions[] = {"png", "pdf"};
    for (int i = 0; i < 2 && status == IM_OK; ++i) {
        char relative[128], path[IM_SCENE_PATH];
        snprintf(relative, sizeof relative, "%s.%s", name, extensions[i]);
        status = scene_output_path(scene, relative, path, sizeof path);
        const paper_file file = {path, texts.texts, texts.count};
        if (status == IM_OK)
            status = draw(scene, data, &file);
    }
    run_figure_texts_free(&texts);
    return status;
}

int scene_output_path(const im_scene *scene, const char *relative, char *buffer, size_t size)
{
    int status = im_path_join(buffer, size, scene->output_dir, relative);
    if (status == IM_OK)
        scene_outputs_note(scene, buffer);
    return status;
}
