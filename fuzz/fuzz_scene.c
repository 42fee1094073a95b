/* libFuzzer harness: im_scene_load on arbitrary bytes must return a status, never crash or trip a
 * sanitizer; an accepted scene must be consistent (fuzz_checks.h). */
#include "fuzz_checks.h"
#include "fuzz_file.h"

#include "indentmap/scene.h"
#include "scene/contents.h"

#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    im_scene *scene = NULL;
    int status = im_scene_load(fuzz_write_input(data, size), &scene);
    const char *problem = fuzz_scene_problem(status, scene);
    im_scene_free(scene);
    if (problem) {
        fprintf(stderr, "fuzz_scene: %s (status %d: %s)\n", problem, status, im_last_error());
        abort();
    }
    return 0;
}
