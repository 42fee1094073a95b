/* The OSMesa fallback, loaded at run time so that the program links no GL implementation. */
#include "render/context.h"

#include "indentmap/status.h"

#include <GL/osmesa.h>
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

typedef OSMesaContext (*create_attribs_fn)(const int *attributes, OSMesaContext share);
typedef GLboolean (*make_current_fn)(OSMesaContext, void *, GLenum, GLsizei, GLsizei);
typedef void (*destroy_fn)(OSMesaContext);
typedef OSMESAproc (*get_proc_fn)(const char *);

static get_proc_fn get_proc_address;

void (*osmesa_library_get_proc(const char *name))(void)
{
    return get_proc_address ? (void (*)(void))get_proc_address(name) : NULL;
}

/* dlsym returns a data pointer; POSIX guarantees it converts to a function pointer. */
static void *symbol(void *library, const char *name) { return dlsym(library, name); }

int osmesa_library_open(im_osmesa *osmesa, char *reason, size_t reason_size)
{
    memset(osmesa, 0, sizeof *osmesa);
    osmesa->library = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
    if (!osmesa->library) {
        snprintf(reason, reason_size, "osmesa: %s", dlerror());
        return IM_EUNSUPPORTED;
    }
    create_attribs_fn create;
    make_current_fn make_current;
    *(void **)&create = symbol(osmesa->library, "OSMesaCreateContextAttribs");
    *(void **)&make_current = symbol(osmesa->library, "OSMesaMakeCurrent");
    *(void **)&get_proc_address = symbol(osmesa->library, "OSMesaGetProcAddress");
    if (!create || !make_current || !get_proc_address) {
        snprintf(reason, reason_size, "osmesa: libOSMesa.so.8 lacks OSMesaCreateContextAttribs");
        osmesa_library_close(osmesa);
        return IM_EUNSUPPORTED;
    }
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              0,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_ACCUM_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              3,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              3,
                              0};
    osmesa->context = create(attributes, NULL);
    if (!osmesa->context) {
        snprintf(reason, reason_size, "osmesa: no OpenGL 3.3 core context");
        osmesa_library_close(osmesa);
        return IM_EUNSUPPORTED;
    }
    if (!make_current(osmesa->context, osmesa->buffer, GL_UNSIGNED_BYTE, 2, 2)) {
        snprintf(reason, reason_size, "osmesa: OSMesaMakeCurrent failed");
        osmesa_library_close(osmesa);
        return IM_EUNSUPPORTED;
    }
    return IM_OK;
}

int osmesa_library_make_current(im_osmesa *osmesa)
{
    make_current_fn make_current;
    *(void **)&make_current = symbol(osmesa->library, "OSMesaMakeCurrent");
    return make_current && make_current(osmesa->context, osmesa->buffer, GL_UNSIGNED_BYTE, 2, 2);
}

void osmesa_library_release_current(im_osmesa *osmesa)
{
    make_current_fn make_current;
    *(void **)&make_current = symbol(osmesa->library, "OSMesaMakeCurrent");
    if (make_current)
        make_current(NULL, NULL, 0, 0, 0);
}

/* The library stays loaded (no dlclose): Mesa's LLVM back end is not safe to unload and load
 * again in one process, and a later context reuses it. */
void osmesa_library_close(im_osmesa *osmesa)
{
    if (osmesa->context) {
        destroy_fn destroy;
        *(void **)&destroy = symbol(osmesa->library, "OSMesaDestroyContext");
        osmesa_library_release_current(osmesa); /* releases the context's framebuffer */
        if (destroy)
            destroy(osmesa->context);
    }
    memset(osmesa, 0, sizeof *osmesa);
}
