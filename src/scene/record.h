/* Internal: the run record (record.c). */
#ifndef INDENTMAP_SCENE_RECORD_H
#define INDENTMAP_SCENE_RECORD_H

#include "indentmap/scene.h"

#include <jansson.h>

/* The run record of OUTPUT/run.json (*record, the caller's to free): program, version, scene path,
 * quality preset and solver tolerance, the inputs' checksums (record.c). The run writes it as it starts
 * and finishes it with its status (front.h: run_record_start; run_folder.h: run_folder_record). */
int scene_record_create(const im_scene *scene, json_t **record);

#endif
