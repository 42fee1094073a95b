/* The text of `indentmap info` and `indentmap formats` (info.h), written once for every front end. */
#include "indentmap/info.h"

#include "indentmap/formats.h"
#include "indentmap/gpu_config.h"
#include "indentmap/io.h"
#include "indentmap/status.h"
#include "indentmap/version.h"
#if IM_HAVE_GPU
#include "gpu/vulkan.h"
#endif

#include <fftw3.h>
#include <gsl/gsl_version.h>
#include <omp.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A text written with stdio into memory: open, write to .stream, close into *text. */
typedef struct text_stream {
    FILE *stream;
    char *text;
    size_t length;
} text_stream;

static int text_open(text_stream *t, const char *function)
{
    *t = (text_stream){NULL, NULL, 0};
    t->stream = open_memstream(&t->text, &t->length);
    return t->stream ? IM_OK : im_fail(IM_ENOMEM, "%s: out of memory", function);
}

/* Closes the stream and hands its text to *text (NULL, freed, when out of memory); status as given
 * unless the text could not be kept. */
static int text_close(text_stream *t, int status, const char *function, char **text)
{
    if (fclose(t->stream) != 0) {
        free(t->text);
        *text = NULL;
        return im_fail(IM_ENOMEM, "%s: out of memory", function);
    }
    *text = t->text;
    return status;
}

/* The render backend and GL strings; a machine without GL is reported, not an error, but a renderer that
 * opens a context and then fails is. */
static int write_renderer(FILE *out, im_render_backend backend)
{
    im_render_context *context = NULL;
    int status = im_render_open(backend, &context);
    if (status != IM_OK) {
        int missing = im_render_context_missing(status, im_last_error());
        fprintf(out, "render backend: %s (%s)\n", missing ? "unavailable" : "failed", im_last_error());
        return missing ? IM_OK : status;
    }
    fprintf(out, "render backend: %s, %s\n", im_render_backend_name(context), im_render_display_name(context));
    fprintf(out, "GL_RENDERER: %s\n", im_render_gl_renderer(context));
    fprintf(out, "GL_VERSION: %s\n", im_render_gl_version(context));
    im_render_close(context);
    return IM_OK;
}

/* The Vulkan devices, one line each; none is not an error (the CPU solver needs no GPU). */
static void write_vulkan_devices(FILE *out)
{
    fprintf(out, "Vulkan devices:");
#if IM_HAVE_GPU
    char text[4096];
    if (gpu_devices_describe(text, sizeof text) != IM_OK) {
        fprintf(out, " none: %s\n", im_last_error());
        return;
    }
    fprintf(out, "\n");
    char *rest = NULL;
    for (char *line = strtok_r(text, "\n", &rest); line; line = strtok_r(NULL, "\n", &rest))
        fprintf(out, "  %s\n", line);
#else
    fprintf(out, " not built (IM_GPU off)\n");
#endif
}

int im_info_text(im_render_backend backend, char **text)
{
    if (!text)
        return im_fail(IM_EINVAL, "im_info_text: text is NULL");
    text_stream t;
    int status = text_open(&t, "im_info_text");
    if (status != IM_OK)
        return status;
    fprintf(t.stream, "indentmap %s\n", im_version());
    fprintf(t.stream, "fftw: %s\n", fftw_version);
    fprintf(t.stream, "gsl: %s\n", gsl_version);
    fprintf(t.stream, "libpng: %s\n", png_libpng_ver);
    fprintf(t.stream, "openmp threads: %d (of %d processors)\n", omp_get_max_threads(), omp_get_num_procs());
    status = write_renderer(t.stream, backend);
    write_vulkan_devices(t.stream);
    return text_close(&t, status, "im_info_text", text);
}

static const char *const OWN_FORMATS[] = {
    ".npy   NumPy array, float or integer (units in its .json sidecar)            read, write",
    ".gsf   Gwyddion Simple Field                                                read, write",
    ".sdf   ISO 25178-71, ASCII or binary                                        read, write",
    ".nc    NetCDF, SurfaceTopography / contact.engineering layout               read, write",
    ".x3p   ISO 25178-72 (ISO 5436-2 XML in a zip)                               read, write",
    ".tmd   TrueMap / GelSight binary (lengths and heights in mm)                read",
    ".h5    HDF5: each 2-D numeric data set a channel; a bare matrix             read",
    ".zip   contact.engineering container (meta.yml): each topography a channel  read",
    ("text   matrix; x y z points on a grid; Gwyddion (English, German) and\n" /* one entry of two lines */
     "         Wyko/Vision ASCII exports; decimal commas                          read, write (matrix)"),
};

static int compare_lines(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* Writes the lines the program listed ("NAME<TAB>WHAT"), sorted by name. */
static void write_sorted(FILE *out, char **lines, int count)
{
    qsort(lines, (size_t)count, sizeof *lines, compare_lines);
    for (int k = 0; k < count; ++k) {
        char *what = strchr(lines[k], '\t');
        fprintf(out, "  %-14.*s %s", what ? (int)(what - lines[k]) : 0, lines[k], what ? what + 1 : lines[k]);
    }
}

/* Gwyddion's modules that load files, as the program lists them. */
static int write_gwyddion_modules(FILE *out, const char *program)
{
    enum { MAX_MODULES = 1024, LINE = 256 };
    char command[4200];
    snprintf(command, sizeof command, "'%s' --formats", program);
    FILE *listing = strchr(program, '\'') ? NULL : popen(command, "r");
    char(*lines)[LINE] = listing ? malloc(MAX_MODULES * sizeof *lines) : NULL;
    char **sorted = lines ? malloc(MAX_MODULES * sizeof *sorted) : NULL;
    int count = 0;
    while (sorted && count < MAX_MODULES && fgets(lines[count], LINE, listing)) {
        sorted[count] = lines[count];
        ++count;
    }
    int ended = listing ? pclose(listing) : -1;
    if (sorted) {
        write_sorted(out, sorted, count);
        fprintf(out, "(%d Gwyddion modules)\n", count);
    }
    free(sorted);
    free(lines);
    if (!listing)
        return im_fail(IM_EIO, "formats: cannot run %s", program);
    if (!sorted)
        return im_fail(IM_ENOMEM, "formats: out of memory");
    return ended == 0 && count > 0 ? IM_OK
                                   : im_fail(IM_EIO, "formats: %s --formats failed or listed no module", program);
}

int im_formats_text(char **text)
{
    if (!text)
        return im_fail(IM_EINVAL, "im_formats_text: text is NULL");
    text_stream t;
    int status = text_open(&t, "im_formats_text");
    if (status != IM_OK)
        return status;
    fprintf(t.stream, "indentmap's own readers:\n");
    for (size_t k = 0; k < sizeof OWN_FORMATS / sizeof *OWN_FORMATS; ++k)
        fprintf(t.stream, "  %s\n", OWN_FORMATS[k]);
    const char *program = im_gwyddion_reader();
    if (!program)
        fprintf(t.stream, "Gwyddion's file modules: not in this build (install libgwyddion20-dev and gwyddion, "
                          "then rebuild)\n");
    else {
        fprintf(t.stream, "Gwyddion's file modules, through %s (any other file that is not text):\n", program);
        status = write_gwyddion_modules(t.stream, program);
    }
    return text_close(&t, status, "im_formats_text", text);
}
