/* Internal: the run record (record.c). */
#ifndef INDENTMAP_SCENE_RECORD_H
#define INDENTMAP_SCENE_RECORD_H

#include "indentmap/scene.h"

/* OUTPUT/run.json: program, version, scene path, quality preset and solver tolerance (record.c). */
int scene_write_record(const im_scene *scene);

#endif
