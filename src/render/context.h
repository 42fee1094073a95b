/* The render context shared by the backends (context.c, osmesa.c) and the drawing code (draw.c). */
#ifndef INDENTMAP_RENDER_CONTEXT_H
#define INDENTMAP_RENDER_CONTEXT_H

#include "indentmap/colormap.h"
#include "indentmap/render.h"
#include "render/gl.h"

#include <stddef.h>
#include <stdint.h>

/* OSMesa, opened with dlopen (osmesa.c). Kept free of GL headers: GL/osmesa.h brings GL/gl.h. */
typedef struct im_osmesa {
    void *library;            /* dlopen handle */
    void *context;            /* OSMesaContext */
    unsigned char buffer[16]; /* 2 x 2 RGBA colour buffer OSMesaMakeCurrent requires; unused */
} im_osmesa;

/* Loads libOSMesa.so.8 and makes a 3.3 core context current; on failure writes why into reason
 * and returns IM_EUNSUPPORTED with everything released. */
int osmesa_library_open(im_osmesa *osmesa, char *reason, size_t reason_size);
/* Makes the context current again on this thread; 1 on success. */
int osmesa_library_make_current(im_osmesa *osmesa);
/* Leaves this thread without a current context. */
void osmesa_library_release_current(im_osmesa *osmesa);
/* OSMesaGetProcAddress of the library opened last. */
void (*osmesa_library_get_proc(const char *name))(void);
void osmesa_library_close(im_osmesa *osmesa);

struct im_render_context {
    im_gl gl;
    im_render_backend backend;
    char display_name[160];
    char renderer[256], version[256];
    void *egl_display, *egl_context; /* EGLDisplay, EGLContext */
    im_osmesa osmesa;
    GLint max_texture_size, max_renderbuffer_size, max_viewport[2], max_samples;
    GLuint vertex_array, contact_program, height_program;
    GLuint surface_program, punch_program, wall_program; /* the 3-D view (view3d.c) */
};

/* Whether EGL's client extensions allow enumerating devices: EGL_EXT_platform_device and
 * EGL_EXT_device_enumeration (or EGL_EXT_device_base, which includes it). */
int egl_can_enumerate_devices(const char *client_extensions);

/* The context of a backend (context.c), current on the calling thread, without the GL objects of
 * render_setup: IM_EUNSUPPORTED naming every backend tried and why it failed, IM_EINVAL for a bad
 * IM_RENDER_BACKEND, IM_ENOMEM. render_context_close releases the backend and frees c. im_render_open
 * and im_render_close (open.c) add the GL objects, so that context.c and draw.c never call each
 * other: draw.c and view3d.c use the context, open.c uses both. */
int render_context_open(im_render_backend backend, im_render_context **out);
void render_context_close(im_render_context *c);

/* Makes the context current on the calling thread (another context may have been used since), for
 * one drawing call; render_release_current ends it, so that the next call may come from another
 * thread (EGL refuses a context still current on another thread). */
int render_make_current(im_render_context *context);
void render_release_current(im_render_context *context);

/* Compiles the embedded shaders and creates the shared GL objects (draw.c). */
int render_setup(im_render_context *context);
void render_teardown(im_render_context *context);

/* ---- shared by the 2-D maps (draw.c) and the 3-D view (view3d.c) ---- */

/* Patch codes sent to the shaders besides the table indices 0..255 (shaders/patch_colour.glsl); a
 * patch under tension has IM_CODE_TENSION plus its tension's code through the tension norm. */
enum { IM_CODE_UNDER = 256, IM_CODE_OVER = 257, IM_CODE_BAD = 258, IM_CODE_BACKGROUND = 259, IM_CODE_TENSION = 512 };

/* The code of a value through the norm: its table index, or under / over / bad. */
int render_patch_code(const im_colormap *colormap, double value);

/* The code of a local force: bad for NaN, through `compression` for f > 0, IM_CODE_TENSION plus the
 * code of -f through `tension` for f < 0, background for 0. */
int render_force_code(const im_colormap *compression, const im_colormap *tension, double force);

/* Binds the tension norm's table on `unit` and sets its under / over colours in the program. */
GLuint render_tension_texture(const im_gl *gl, GLuint program, int unit, const im_colormap *tension);

/* Compiles and links a program from embedded sources (render/shaders.h), each after the #version
 * line; the fragment shader also after fragment_prelude (im_shader_patch_colour for those that colour
 * patches, or NULL). IM_EUNSUPPORTED naming the shader and quoting its log. */
int render_link_program(const im_gl *gl, const char *vertex_source, const char *vertex_name,
                        const char *fragment_prelude, const char *fragment_source, const char *name, GLuint *out);

/* A nearest-filtered, edge-clamped 2-D texture bound on texture unit `unit`. */
GLuint render_texture(const im_gl *gl, int unit, GLint internal, int width, int height, GLenum format, GLenum type,
                      const void *data);
/* The colour map's 256-entry table as a 256 x 1 RGBA8 texture on `unit`. */
GLuint render_table_texture(const im_gl *gl, int unit, im_colormap_id map);

void render_set_colour(const im_gl *gl, GLuint program, const char *name, const uint8_t rgb[3]);
void render_set_int(const im_gl *gl, GLuint program, const char *name, int value);

/* The size limit of images and framebuffers: the smallest of the GL limits and 32768. */
long render_image_limit(const im_render_context *context);

/* Turns GL's bottom-up rows (glReadPixels) into top-down ones; IM_ENOMEM. */
int render_flip_rows(uint8_t *rgba, int width, int height);

/* Links the 3-D view's programs (view3d.c); called by render_setup. */
int render_view3d_setup(im_render_context *context);

#endif
