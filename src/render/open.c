/* A render context ready to draw: the backend's context (context.c) with the shared GL objects
 * (draw.c) created on it. */
#include "render/context.h"
#include "core/args.h"

#include "indentmap/status.h"

#include <stddef.h>

int im_render_open(im_render_backend backend, im_render_context **out)
{
    ARG_REQUIRE(out, "out");
    int status = render_context_open(backend, out);
    if (status != IM_OK)
        return status;
    status = render_setup(*out);
    if (status == IM_OK) {
        render_release_current(*out); /* each drawing call makes it current on its own thread */
    } else {
        im_render_close(*out);
        *out = NULL;
    }
    return status;
}

void im_render_close(im_render_context *c)
{
    if (!c)
        return;
    if (render_make_current(c) == IM_OK)
        render_teardown(c);
    render_context_close(c);
}
