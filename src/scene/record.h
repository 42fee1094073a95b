/* Internal: the run record (record.c). */
#ifndef INDENTMAP_SCENE_RECORD_H
#define INDENTMAP_SCENE_RECORD_H

#include "indentmap/scene.h"

/* OUTPUT/run.json: program, version, scene path, quality preset and solver tolerance (record.c), and
 * where the run stands: "status" "running" and "error" "" before it has finished (finished 0); once
 * finished, "ok" or the name of status with im_last_error() as "error". */
int scene_write_record(const im_scene *scene, int finished, int status);

#endif
