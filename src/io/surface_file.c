#include "indentmap/io.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "io/payload.h"
#include "io/readers.h"

#include <string.h>

static int has_extension(const char *path, const char *extension)
{
    size_t n = strlen(path), e = strlen(extension);
    return n > e && strcmp(path + n - e, extension) == 0;
}

int im_surface_read_with(const char *path, const im_surface_read_options *options, im_field **out,
                         im_surface_read_info *info)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(out, "out");
    surface_raw_reader read = has_extension(path, ".npy")   ? npy_read_raw
                              : has_extension(path, ".gsf") ? gsf_read_raw
                              : has_extension(path, ".sdf") ? sdf_read_raw
                              : has_extension(path, ".nc")  ? netcdf_read_raw
                              : has_extension(path, ".x3p") ? x3p_read_raw
                                                            : text_read_raw;
    return surface_read_format(path, read, options, out, info);
}

int im_surface_read(const char *path, im_field **out)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(out, "out");
    return im_surface_read_with(path, NULL, out, NULL);
}

int im_surface_write(const char *path, const im_field *field)
{
    ARG_REQUIRE(path, "path");
    ARG_VIEW(field, "field");
    if (has_extension(path, ".npy")) { /* .npy holds any field; as a surface it must be one */
        int writable = io_check_heights_writable(field, path);
        return writable == IM_OK ? im_npy_write(path, field, IM_NPY_FLOAT64) : writable;
    }
    if (has_extension(path, ".gsf"))
        return im_gsf_write(path, field);
    if (has_extension(path, ".sdf"))
        return im_sdf_write(path, field);
    if (has_extension(path, ".nc"))
        return im_netcdf_write(path, field);
    if (has_extension(path, ".x3p"))
        return im_x3p_write(path, field);
    return im_text_write(path, field);
}
