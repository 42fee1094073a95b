#include "indentmap/io.h"

#include <string.h>

static int has_extension(const char *path, const char *extension)
{
    size_t n = strlen(path), e = strlen(extension);
    return n > e && strcmp(path + n - e, extension) == 0;
}

int im_surface_read(const char *path, im_field **out)
{
    if (has_extension(path, ".npy"))
        return im_npy_read(path, out);
    if (has_extension(path, ".gsf"))
        return im_gsf_read(path, out);
    return im_text_read(path, out);
}

int im_surface_write(const char *path, const im_field *field)
{
    if (has_extension(path, ".npy"))
        return im_npy_write(path, field, IM_NPY_FLOAT64);
    if (has_extension(path, ".gsf"))
        return im_gsf_write(path, field);
    return im_text_write(path, field);
}
