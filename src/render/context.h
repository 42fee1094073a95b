/* The render context shared by the backends (context.c, osmesa.c) and the drawing code (draw.c). */
#ifndef INDENTMAP_RENDER_CONTEXT_H
#define INDENTMAP_RENDER_CONTEXT_H

#include "indentmap/colormap.h"
#include "indentmap/render.h"
#include "render/gl.h"

#include <stddef.h>

/* OSMesa, opened with dlopen (osmesa.c). Kept free of GL headers: GL/osmesa.h brings GL/gl.h. */
typedef struct im_osmesa {
    void *library;          /* dlopen handle */
    void *context;          /* OSMesaContext */
    unsigned char buffer[16]; /* 2 x 2 RGBA colour buffer OSMesaMakeCurrent requires; unused */
} im_osmesa;

/* Loads libOSMesa.so.8 and makes a 3.3 core context current; on failure writes why into reason
 * and returns IM_EUNSUPPORTED with everything released. */
int im_osmesa_open(im_osmesa *osmesa, char *reason, size_t reason_size);
/* Makes the context current again on this thread; 1 on success. */
int im_osmesa_make_current(im_osmesa *osmesa);
/* OSMesaGetProcAddress of the library opened last. */
void (*im_osmesa_get_proc(const char *name))(void);
void im_osmesa_close(im_osmesa *osmesa);

struct im_render_context {
    im_gl gl;
    im_render_backend backend;
    char display_name[160];
    char renderer[256], version[256];
    void *egl_display, *egl_context;  /* EGLDisplay, EGLContext */
    im_osmesa osmesa;
    GLint max_texture_size, max_renderbuffer_size, max_viewport[2];
    GLuint vertex_array, contact_program, height_program;
};

/* Whether EGL's client extensions allow enumerating devices: EGL_EXT_platform_device and
 * EGL_EXT_device_enumeration (or EGL_EXT_device_base, which includes it). */
int im_egl_can_enumerate_devices(const char *client_extensions);

/* Makes the context current on the calling thread (another context may have been used since). */
int im_render_make_current(im_render_context *context);

/* Compiles the embedded shaders and creates the shared GL objects (draw.c). */
int im_render_setup(im_render_context *context);
void im_render_teardown(im_render_context *context);

#endif
