/* A surface file's preparation before it is solved or measured (front.h): the crop, the scan lines'
 * alignment and the detrending, what they did in words, and the warning of a surface mostly filled. */
#include "front/front.h"

#include "indentmap/status.h"

#include <stdio.h>

int surface_prepare(const surface_preparation *p, im_field **surface)
{
    if (p->crop[2] > 0) {
        im_field *crop = NULL;
        int status = im_surface_crop(*surface, p->crop[0], p->crop[1], p->crop[2], p->crop[3], &crop);
        if (status != IM_OK)
            return im_fail_context(status, "--crop");
        im_field_free(*surface);
        *surface = crop;
    }
    int status = im_surface_align_rows(*surface, p->align);
    if (status != IM_OK)
        return im_fail_context(status, "--align");
    return im_surface_detrend(*surface, p->detrend);
}

int surface_fill_warning(const char *path, long filled, size_t points, char *text, size_t size)
{
    if (!(points > 0 && (double)filled > 0.05 * (double)points))
        return 0;
    snprintf(text, size,
             "warning: %s: --fill invented %.1f%% of the surface (%ld of %zu points): its statistics and contacts "
             "there are the fill's",
             path, 100.0 * (double)filled / (double)points, filled, points);
    return 1;
}

int surface_assumption_warning(const char *path, const im_surface_read_info *info, char *text, size_t size)
{
    if (!info->assumed[0])
        return 0;
    snprintf(text, size, "warning: %s: %s (--height-unit states theirs)", path, info->assumed);
    return 1;
}

void surface_preparation_describe(const surface_preparation *p, long filled, char *text, size_t size)
{
    static const char *const DETREND[] = {"nothing removed", "plane removed", "plane and curvature removed"};
    int length = snprintf(text, size, "%s", DETREND[p->detrend]);
    if (p->crop[2] > 0)
        length += snprintf(text + length, size - (size_t)length, ", cropped to %d x %d at (%d, %d)", p->crop[2],
                           p->crop[3], p->crop[0], p->crop[1]);
    static const char *const ALIGN[] = {"", "median", "mean", "line"};
    if (p->align != IM_ALIGN_NONE && length < (int)size)
        length += snprintf(text + length, size - (size_t)length, ", rows aligned (%s)", ALIGN[p->align]);
    if (filled > 0 && length < (int)size)
        snprintf(text + length, size - (size_t)length, ", %ld missing points filled", filled);
}
