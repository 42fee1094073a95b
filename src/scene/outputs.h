/* Internal: where a scene's outputs go: paths, figures as PNG and PDF, the folder's lock (outputs.c). */
#ifndef INDENTMAP_SCENE_OUTPUTS_H
#define INDENTMAP_SCENE_OUTPUTS_H

#include "indentmap/io.h"
#include "indentmap/scene.h"
#include "paper/figures.h"

#include <stddef.h>

/* output_dir/relative into buffer, noted as an output of the run (manifest.h: a damaged file there is
 * removed); IM_EINVAL if it does not fit. */
int scene_output_path(const im_scene *scene, const char *relative, char *buffer, size_t size);

/* Opens output_dir/relative for writing through io.h's im_atomic_open (commit or abort it). */
int scene_open_output(const im_scene *scene, const char *relative, im_atomic_file *file);

/* Writes NAME.png and NAME.pdf under the output folder with draw(scene, data, file), each file carrying
 * the scene's provenance (provenance.h: scene_figure_texts). */
int scene_write_png_pdf(const im_scene *scene, const char *name,
                        int (*draw)(const im_scene *, const void *, const paper_file *), const void *data);

#endif
