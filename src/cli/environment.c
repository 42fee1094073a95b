/* The environment variables that configure the library: read here, by the program, and passed in
 * (the library itself reads no environment). */
#include "cli/cli.h"

#include "indentmap/field.h"
#include "indentmap/render.h"
#include "indentmap/status.h"
#include "core/number.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cli_apply_memory_limit(void)
{
    const char *text = getenv("IM_MEMORY_LIMIT_MIB");
    if (!text || !text[0])
        return 0;
    char *end;
    double mib = number_parse(text, &end);
    if (end == text || *end != '\0' || !(mib > 0.0) || !isfinite(mib)) {
        fprintf(stderr, "indentmap: IM_MEMORY_LIMIT_MIB = '%s': expected a number of MiB > 0\n", text);
        return -1;
    }
    im_memory_set_limit((size_t)fmin(mib * 1048576.0, 0x1p63)); /* far beyond any machine; exact in size_t */
    return 0;
}

int cli_space_check_off(void)
{
    const char *off = getenv("IM_NO_SPACE_CHECK");
    return off && off[0] && strcmp(off, "0") != 0;
}

int cli_render_backend(im_render_backend *backend)
{
    const char *variable = getenv("IM_RENDER_BACKEND");
    if (*backend != IM_RENDER_AUTO || !variable || !*variable)
        return IM_OK;
    if (im_render_backend_from_name(variable, backend) != IM_OK)
        return im_fail_context(IM_EINVAL, "environment variable IM_RENDER_BACKEND");
    return IM_OK;
}

int cli_render_open(im_render_backend backend, im_render_context **out)
{
    *out = NULL;
    int status = cli_render_backend(&backend);
    return status == IM_OK ? im_render_open(backend, out) : status;
}
