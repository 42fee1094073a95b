/* Opening a headless OpenGL 3.3 core context: EGL devices, EGL surfaceless, then OSMesa. */
#define EGL_NO_X11
#define MESA_EGL_NO_X11_HEADERS
#include "render/context.h"
#include "core/args.h"

#include "indentmap/status.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_DEVICES = 16 };

/* Displays stay initialised for the life of the process: EGL hands out one EGLDisplay per device,
 * so eglTerminate would end every other context on it, and Mesa unloads its driver on
 * eglTerminate, which would orphan the driver's process-wide allocations. */
int im_render_backend_from_name(const char *name, im_render_backend *backend)
{
    ARG_REQUIRE(name, "name");
    ARG_REQUIRE(backend, "backend");
    static const char *const names[] = {"auto", "egl", "osmesa"};
    for (int i = 0; i < 3; ++i) {
        if (strcmp(name, names[i]) == 0) {
            *backend = (im_render_backend)i;
            return IM_OK;
        }
    }
    return im_fail(IM_EINVAL, "render backend '%s': expected auto, egl or osmesa", name);
}

const char *im_render_backend_name(const im_render_context *c)
{
    ARG_REQUIRE_OR(c, "context", NULL);
    return c->backend == IM_RENDER_OSMESA ? "osmesa" : "egl";
}
const char *im_render_display_name(const im_render_context *c)
{
    ARG_REQUIRE_OR(c, "context", NULL);
    return c->display_name;
}

const char *im_render_gl_renderer(const im_render_context *c)
{
    ARG_REQUIRE_OR(c, "context", NULL);
    return c->renderer;
}

const char *im_render_gl_version(const im_render_context *c)
{
    ARG_REQUIRE_OR(c, "context", NULL);
    return c->version;
}

int gl_load(im_gl *gl, im_gl_loader loader)
{
#define IM_GL_LOAD(name, type)                                                                                       \
    gl->name = (type)loader("gl" #name);                                                                             \
    if (!gl->name)                                                                                                   \
        return im_fail(IM_EUNSUPPORTED, "OpenGL function gl%s is not available", #name);
    IM_GL_FUNCTIONS(IM_GL_LOAD)
#undef IM_GL_LOAD
    return IM_OK;
}

/* Whether a space-separated extension list contains name as a whole word. */
static int has_extension(const char *list, const char *name)
{
    size_t length = strlen(name);
    for (const char *p = list; p && (p = strstr(p, name)) != NULL; p += length)
        if ((p == list || p[-1] == ' ') && (p[length] == ' ' || p[length] == '\0'))
            return 1;
    return 0;
}

static void append_reason(char *reasons, size_t size, const char *reason)
{
    size_t used = strlen(reasons);
    snprintf(reasons + used, size - used, "%s%s", used ? "; " : "", reason);
}

static im_gl_proc egl_loader(const char *name) { return (im_gl_proc)eglGetProcAddress(name); }

/* Initialises display, creates a surfaceless 3.3 core context and makes it current. */
static int egl_context_on(im_render_context *c, EGLDisplay display, char *reason, size_t size)
{
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, NULL, NULL)) {
        snprintf(reason, size, "eglInitialize failed (EGL error 0x%x)", (unsigned)eglGetError());
        return IM_EUNSUPPORTED;
    }
    const char *extensions = eglQueryString(display, EGL_EXTENSIONS);
    EGLContext context = EGL_NO_CONTEXT;
    EGLConfig config = EGL_NO_CONFIG_KHR;
    EGLint count = 0;
    const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
    const EGLint context_attributes[] = {
        EGL_CONTEXT_MAJOR_VERSION,           3,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    if (!has_extension(extensions, "EGL_KHR_surfaceless_context"))
        snprintf(reason, size, "no EGL_KHR_surfaceless_context");
    else if (!eglBindAPI(EGL_OPENGL_API))
        snprintf(reason, size, "eglBindAPI(EGL_OPENGL_API) failed");
    else if (!has_extension(extensions, "EGL_KHR_no_config_context") &&
             (!eglChooseConfig(display, config_attributes, &config, 1, &count) || count < 1))
        snprintf(reason, size, "no EGL config with EGL_OPENGL_BIT");
    else if ((context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes)) == EGL_NO_CONTEXT)
        snprintf(reason, size, "no OpenGL 3.3 core context (EGL error 0x%x)", (unsigned)eglGetError());
    else if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
        snprintf(reason, size, "eglMakeCurrent failed (EGL error 0x%x)", (unsigned)eglGetError());
    else if (gl_load(&c->gl, egl_loader) != IM_OK)
        snprintf(reason, size, "%s", im_last_error());
    else {
        c->egl_display = display;
        c->egl_context = context;
        return IM_OK;
    }
    if (context != EGL_NO_CONTEXT) {
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, context);
    }
    return IM_EUNSUPPORTED;
}

typedef struct egl_platform {
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display;
    PFNEGLQUERYDEVICESEXTPROC query_devices;
    PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string;
} egl_platform;

/* Tries the enumerated devices whose software-ness matches `software`. */
static int egl_try_devices(im_render_context *c, const egl_platform *egl, int software, char *reasons, size_t size)
{
    EGLDeviceEXT devices[MAX_DEVICES];
    EGLint count = 0;
    if (!egl->query_devices(MAX_DEVICES, devices, &count))
        return IM_EUNSUPPORTED;
    for (int i = 0; i < count; ++i) {
        const char *extensions = egl->query_device_string(devices[i], EGL_EXTENSIONS);
        if (has_extension(extensions, "EGL_MESA_device_software") != software)
            continue;
        const char *drm = has_extension(extensions, "EGL_EXT_device_drm")
                              ? egl->query_device_string(devices[i], EGL_DRM_DEVICE_FILE_EXT)
                              : NULL;
        snprintf(c->display_name, sizeof c->display_name, "device %d of %d (%s)", i + 1, (int)count,
                 software ? "EGL_MESA_device_software"
                 : drm    ? drm
                          : "hardware");
        EGLDisplay display = egl->get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL);
        char reason[256];
        if (egl_context_on(c, display, reason, sizeof reason) == IM_OK)
            return IM_OK;
        char line[512];
        snprintf(line, sizeof line, "egl %s: %s", c->display_name, reason);
        append_reason(reasons, size, line);
    }
    return IM_EUNSUPPORTED;
}

int egl_can_enumerate_devices(const char *client_extensions)
{
    return has_extension(client_extensions, "EGL_EXT_platform_device") &&
           (has_extension(client_extensions, "EGL_EXT_device_enumeration") ||
            has_extension(client_extensions, "EGL_EXT_device_base"));
}

static int egl_open(im_render_context *c, char *reasons, size_t size)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    egl_platform egl = {(PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT"),
                        (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT"),
                        (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT")};
    if (!client || !has_extension(client, "EGL_EXT_platform_base") || !egl.get_platform_display) {
        append_reason(reasons, size, "egl: no EGL_EXT_platform_base (no usable libEGL)");
        return IM_EUNSUPPORTED;
    }
    c->backend = IM_RENDER_EGL;
    /* Under glvnd eglGetProcAddress returns a dispatch stub for any name, so the pointers being
     * non-NULL says nothing: the client extensions must name device enumeration. */
    int devices = egl_can_enumerate_devices(client) && egl.query_devices && egl.query_device_string;
    if (!devices)
        append_reason(reasons, size, "egl: no EGL_EXT_platform_device with EGL_EXT_device_enumeration");
    for (int software = 0; devices && software <= 1; ++software)
        if (egl_try_devices(c, &egl, software, reasons, size) == IM_OK)
            return IM_OK;
    if (!has_extension(client, "EGL_MESA_platform_surfaceless")) {
        append_reason(reasons, size, "egl: no EGL_MESA_platform_surfaceless");
        return IM_EUNSUPPORTED;
    }
    snprintf(c->display_name, sizeof c->display_name, "surfaceless");
    char reason[256], line[320];
    EGLDisplay display = egl.get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (egl_context_on(c, display, reason, sizeof reason) == IM_OK)
        return IM_OK;
    snprintf(line, sizeof line, "egl surfaceless: %s", reason);
    append_reason(reasons, size, line);
    return IM_EUNSUPPORTED;
}

static int osmesa_open(im_render_context *c, char *reasons, size_t size)
{
    char reason[512];
    if (osmesa_library_open(&c->osmesa, reason, sizeof reason) != IM_OK) {
        append_reason(reasons, size, reason);
        return IM_EUNSUPPORTED;
    }
    c->backend = IM_RENDER_OSMESA;
    snprintf(c->display_name, sizeof c->display_name, "libOSMesa.so.8");
    if (gl_load(&c->gl, (im_gl_loader)osmesa_library_get_proc) == IM_OK)
        return IM_OK;
    snprintf(reason, sizeof reason, "osmesa: %s", im_last_error());
    append_reason(reasons, size, reason);
    osmesa_library_close(&c->osmesa);
    return IM_EUNSUPPORTED;
}

static void release_backend(im_render_context *c)
{
    if (c->egl_context) {
        eglMakeCurrent(c->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(c->egl_display, c->egl_context);
        eglReleaseThread();
        c->egl_context = NULL;
    }
    if (c->osmesa.context)
        osmesa_library_close(&c->osmesa);
}

int im_render_context_missing(int status, const char *message)
{
    ARG_REQUIRE_OR(message, "message", 0);
    return status == IM_EUNSUPPORTED && strncmp(message, IM_RENDER_NO_CONTEXT, strlen(IM_RENDER_NO_CONTEXT)) == 0;
}

int render_context_open(im_render_backend backend, im_render_context **out)
{
    *out = NULL;
    im_render_context *c = calloc(1, sizeof *c);
    if (!c)
        return im_fail(IM_ENOMEM, "render context: out of memory");
    char reasons[2048] = "";
    int status = IM_EUNSUPPORTED;
    if (backend != IM_RENDER_OSMESA)
        status = egl_open(c, reasons, sizeof reasons);
    if (status != IM_OK && backend != IM_RENDER_EGL)
        status = osmesa_open(c, reasons, sizeof reasons);
    if (status != IM_OK) {
        free(c);
        return im_fail(IM_EUNSUPPORTED, "%s: %s", IM_RENDER_NO_CONTEXT, reasons);
    }
    const GLubyte *renderer = c->gl.GetString(GL_RENDERER), *version = c->gl.GetString(GL_VERSION);
    snprintf(c->renderer, sizeof c->renderer, "%s", renderer ? (const char *)renderer : "unknown");
    snprintf(c->version, sizeof c->version, "%s", version ? (const char *)version : "unknown");
    *out = c;
    return IM_OK;
}

int render_make_current(im_render_context *c)
{
    int current = c->backend == IM_RENDER_OSMESA
                      ? osmesa_library_make_current(&c->osmesa)
                      : (eglBindAPI(EGL_OPENGL_API) &&
                         eglMakeCurrent(c->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, c->egl_context));
    return current ? IM_OK
                   : im_fail(IM_EUNSUPPORTED, "cannot make the %s context current", im_render_backend_name(c));
}

void render_release_current(im_render_context *c)
{
    if (c->backend == IM_RENDER_OSMESA)
        osmesa_library_release_current(&c->osmesa);
    else
        eglMakeCurrent(c->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

void render_context_close(im_render_context *c)
{
    release_backend(c);
    free(c);
}
