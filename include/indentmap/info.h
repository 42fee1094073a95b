/* indentmap/info.h: what this build is and what it reads, as the text `indentmap info` and `indentmap
 * formats` print, so that every front end (the program, Python's im.info() and im.formats()) says the
 * same bytes.
 *
 * Entry points:
 *   im_info_text      the build: version, libraries, threads, render backend, GPU devices
 *   im_formats_text   the surface formats im_surface_read reads
 *
 * Both functions write into a new buffer (*text, UTF-8, lines ending in '\n'; release it with free()).
 * Misuse (status.h): IM_EINVAL for a NULL text.
 * Threads: thread-safe; im_info_text opens and closes a render context of its own (render.h) and
 * probes the Vulkan devices, im_formats_text runs the Gwyddion reader as a child process.
 */
#ifndef INDENTMAP_INFO_H
#define INDENTMAP_INFO_H

#include "indentmap/render.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The version, the libraries in use (FFTW, GSL, libpng), the OpenMP thread count, the OpenGL renderer
 * that backend opens ("render backend: unavailable (...)" where no context can be had) and the Vulkan
 * devices the GPU engine could use ("none: REASON" without any, "not built (IM_GPU off)"). A context
 * that opens and then fails (shaders, set-up) is a defect: its line says "render backend: failed (...)"
 * and the status is IM_EUNSUPPORTED, *text set all the same. IM_ENOMEM (*text NULL). */
int im_info_text(im_render_backend backend, char **text);

/* The surface formats this build reads (im_surface_read): its own readers with what each is and whether
 * it also writes it, then Gwyddion's file modules through the program im_gwyddion_reader() names, sorted
 * by name and counted, or a line saying the build has none. IM_EIO when that program cannot be run or
 * lists no module (the text says so; *text set all the same), IM_ENOMEM (*text NULL). */
int im_formats_text(char **text);

#ifdef __cplusplus
}
#endif

#endif
