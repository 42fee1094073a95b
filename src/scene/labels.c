/* How a scene's figures name its families and colour their forces. */
#include "scene/labels.h"
#include "scene/contents.h"

#include <math.h>
#include <stdio.h>

void scene_family_title(const im_scene *scene, int family, char *buffer, size_t size)
{
    if (scene->file_count > 1)
        snprintf(buffer, size, "%d files, h′_{rms} = %.3g", scene->file_count, scene->slopes[family]);
    else if (scene->surface_file[0])
        snprintf(buffer, size, "%s, h′_{rms} = %.3g", scene->surface_file, scene->slopes[family]);
    else if (scene->slopes[family] == 0.0)
        snprintf(buffer, size, "smooth");
    else
        snprintf(buffer, size, "h′_{rms} = %g", scene->slopes[family]);
}

im_colormap scene_force_norm(const im_scene *scene, const im_colormap_range *forces)
{
    return im_colormap_range_norm(forces, scene->colormap, NAN, NAN, scene->log_norm);
}
