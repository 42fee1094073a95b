/* indentmap/render.h: the off-screen OpenGL renderer: draws fields (local contact forces, heights)
 * into pixel buffers. Annotations (colour bars, labels, layout) are figure.h's job.
 *
 * Entry points:
 *   im_render_open, im_render_close                       a GL context (EGL or OSMesa)
 *   im_render_contact_map, im_contact_style_default       forces as the paper's Fig. 4 draws them
 *   im_render_height_map, im_height_style_default         heights, with the contact outline
 *   im_render_view3d, im_view3d_style_default             the deformed surface in 3-D
 *   im_image_release                                      a rendered picture's pixels
 *
 * Context: OpenGL 3.3 core, no window system. Backends, in the order `auto` tries them:
 *   1. EGL on a device (EGL_EXT_device_enumeration + EGL_EXT_platform_device): hardware devices
 *      (e.g. NVIDIA) first, then Mesa's software device (llvmpipe);
 *   2. EGL on Mesa's surfaceless platform (EGL_MESA_platform_surfaceless);
 *   3. OSMesa, loaded at run time with dlopen("libOSMesa.so.8").
 * The display is always obtained with eglGetPlatformDisplayEXT naming its platform, the context is
 * surfaceless and draws into a framebuffer object that is read back with glReadPixels. Every GL
 * function is loaded through eglGetProcAddress or OSMesaGetProcAddress, so the program never links
 * a GL library. The caller chooses the backend (the indentmap program's IM_RENDER_BACKEND, auto,
 * egl or osmesa, applies where its --backend is auto; the library reads no environment). A machine
 * where no context can be had gives IM_EUNSUPPORTED with the reason of each attempt.
 *
 * Colours: the norm of a colour map (colormap.h) is evaluated on the CPU in double precision by
 * im_colormap_index, the single definition of value -> table index; the GPU receives each patch's
 * index as an integer texture and looks it up in the same 256-entry table uploaded as a 256 x 1
 * texture. (float32 arithmetic in a shader cannot reproduce floor(256 t) for values at a bin
 * edge.) So a rendered patch has exactly the colour of im_colormap_rgb.
 *
 * Images: RGBA, 8 bits per channel, alpha 255, row 0 = top, stride 4 * width. Field row 0 (y = 0)
 * is at the bottom, as in im_colormap_field_image. Each patch becomes pixels_per_patch x
 * pixels_per_patch pixels with no interpolation across patches; the data are surrounded by a
 * frame of boundary_px pixels (the boundary square of the surface).
 *
 * Misuse (status.h): IM_EINVAL for a NULL context, style, image or output and for an invalid field
 * view (checked before the context is used); the getters give NULL for a NULL context, the style
 * defaults of an invalid view are those of an empty field (no force: view3d's of NULL),
 * im_height_outline_width(NULL) is 0, im_render_context_missing(status, NULL) 0, and
 * im_view3d_exaggeration_text does nothing for NULL text; im_render_close and im_image_release
 * accept NULL.
 * Threads: a context serves one call at a time, from any thread (im_render_open says how). The
 * library's own runs draw with one context from one thread at a time; several contexts drawing in
 * several threads at once are not tested. The style functions are thread-safe.
 */
#ifndef INDENTMAP_RENDER_H
#define INDENTMAP_RENDER_H

#include "indentmap/colormap.h"
#include "indentmap/field.h"
#include "indentmap/indenter.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum im_render_backend { IM_RENDER_AUTO = 0, IM_RENDER_EGL, IM_RENDER_OSMESA } im_render_backend;

/* "auto", "egl" or "osmesa"; IM_EINVAL naming the valid choices otherwise. */
int im_render_backend_from_name(const char *name, im_render_backend *backend);

typedef struct im_render_context im_render_context;

/* Opens a context. IM_RENDER_AUTO tries EGL, then OSMesa (the library reads no environment: the
 * indentmap program turns IM_RENDER_BACKEND into the backend it passes here). When no backend can create an OpenGL 3.3 core context: IM_EUNSUPPORTED with a message
 * starting IM_RENDER_NO_CONTEXT and listing each attempt's reason. A context that is created but
 * cannot compile or link the shaders or set up its objects is a defect, not a missing feature:
 * IM_EUNSUPPORTED with a message naming the shader or GL error, which im_render_context_missing
 * tells apart. A context serves one call at a time, from any thread: each call that draws makes it
 * current on the calling thread and releases it before returning. */
int im_render_open(im_render_backend backend, im_render_context **out);

#define IM_RENDER_NO_CONTEXT "no OpenGL 3.3 core context"

/* 1 when status and message (im_last_error()) from im_render_open mean that no context could be
 * created at all: the one case where GL tests may skip (and, with IM_REQUIRE_GL=1, must fail). */
int im_render_context_missing(int status, const char *message);

/* Releases the context and its GL objects; accepts NULL. */
void im_render_close(im_render_context *context);

/* "egl" or "osmesa". */
const char *im_render_backend_name(const im_render_context *context);
/* Which EGL display: "device 1 of 2 (EGL_MESA_device_software)", "surfaceless", or "libOSMesa.so.8". */
const char *im_render_display_name(const im_render_context *context);
/* glGetString(GL_RENDERER) and glGetString(GL_VERSION). */
const char *im_render_gl_renderer(const im_render_context *context);
const char *im_render_gl_version(const im_render_context *context);

/* A rendered picture. The rectangle of pixels covered by the field (without the frame) is
 * [data_x, data_x + nx * pixels_per_patch) x [data_y, data_y + ny * pixels_per_patch), with
 * data_y counted from the top. */
typedef struct im_image {
    int width, height;
    uint8_t *rgba;      /* owned; free with im_image_release */
    int data_x, data_y; /* top-left pixel of the field */
    int pixels_per_patch;
    int nx, ny;   /* the field's grid */
    double delta; /* the field's patch side and unit, for scale bars */
    char unit[16];
} im_image;

/* Frees the pixels and zeroes the struct; accepts an image never rendered into (zeroed). */
void im_image_release(im_image *image);

/* ---- contact map (the paper's Fig. 4) ---- */
typedef struct im_contact_style {
    im_colormap colormap;      /* norm on the local compressive force */
    int pixels_per_patch;      /* integer upscaling, 1..64 */
    int boundary_px;           /* width of the boundary square around the data, 0..64 */
    uint8_t background[3];     /* patches not in contact (force = 0) */
    im_colormap tension;       /* norm on the tension -f of patches with force < 0 (adhesion, solver.h) */
    uint8_t line[3];           /* boundary square and circle */
    double circle_radius;      /* smooth-surface contact radius, in patches; <= 0: no circle */
    double circle_x, circle_y; /* its centre in patches: field coordinates, x right, y up; patch
                                  (ix, iy) covers [ix, ix + 1) x [iy, iy + 1) */
    double circle_width_px;    /* line width of the circle in pixels, > 0 */
    int circle_aliased;        /* 0 (default): anti-aliased; 1: a pixel at least half covered by the
                                  line takes the line colour, any other none, so the image holds
                                  only exact colours (a GIF palette) */
} im_contact_style;

/* Defaults for a force field: viridis, linear norm on [0, largest force] (or [0, 1] when no
 * patch is in contact), the tension norm im_contact_tension_norm(im_contact_largest_tension(force)),
 * 2 pixels per patch, 2-pixel black boundary, light grey (230) background,
 * no circle (centre preset to the middle of the grid), circle width 2 px, anti-aliased. */
im_contact_style im_contact_style_default(const im_field *force);

/* The norm of the tension -f of patches under tension: the blue ramp IM_COLORMAP_TENSION (light for
 * the least tension, dark for the most), linear on [0, largest] ([0, 1] unless largest > 0 and
 * finite). Frames of a history share one, as they share the force norm. */
im_colormap im_contact_tension_norm(double largest);

/* The largest tension -f over the finite patches with force f < 0; 0 when none (nor for an invalid
 * view, whose message is recorded). A figure draws the tension's colour bar only where it is > 0, so
 * a field without tension is drawn as before there was one. */
double im_contact_largest_tension(const im_field *force);

/* Draws a contact map: each patch with force > 0 in the colour of its force through the norm
 * (under / over colours outside the norm's range), patches with force < 0 in the colour of their
 * tension -f through the tension norm (its under / over colours outside its range), patches with
 * force 0 in the background colour, NaN patches in the colour map's bad colour. A field with no patch in contact
 * is drawn as background only (a valid picture, not an error). The circle is anti-aliased with
 * its exact coverage of each pixel across the line (box filter), or aliased at half coverage. Errors: IM_EINVAL for a bad
 * style (norm, scale, sizes) or an image larger than the GL implementation's limits (named in
 * the message) or an infinite force (a force is finite; NaN marks no data), naming the first such
 * patch (x, y); IM_ENOMEM; IM_EUNSUPPORTED if GL fails. On failure *image is left zeroed. */
int im_render_contact_map(im_render_context *context, const im_field *force, const im_contact_style *style,
                          im_image *image);

/* ---- height field ---- */
typedef struct im_height_style {
    im_colormap colormap;    /* norm on heights */
    int pixels_per_patch;    /* 1..64 */
    int boundary_px;         /* 0..64 */
    uint8_t line[3];         /* boundary colour */
    double shading;          /* hill-shading strength: 0 none .. 1 full */
    double light_azimuth;    /* degrees, clockwise from +y (north): 315 = from the upper left */
    double light_altitude;   /* degrees above the horizon, (0, 90] */
    double exaggeration;     /* slopes are multiplied by this for the shading only, > 0 */
    const im_field *contact; /* optional (NULL): same grid, patches with value > 0 outlined */
    uint8_t outline[3];      /* contact outline colour */
    int outline_px;          /* contact outline width in pixels; 0: automatic (see
                                  im_height_outline_width) */
} im_height_style;

/* Defaults for a surface: viridis on [min, max] of the finite heights (a flat surface gets
 * [h - 1, h + 1]), 2 pixels per patch, 2-pixel black boundary, shading 0.6, light from 315
 * degrees at 45 degrees, exaggeration chosen so the shaded rms slope is about 0.5, no contact,
 * white outline of automatic width. */
im_height_style im_height_style_default(const im_field *height);

/* The contact outline's width in pixels: outline_px when > 0, else automatic, scaled with the
 * pixels per patch s so that it stays visible at print resolution: 1 px at s = 1, else
 * max(2, round(s / 3)) (2 px up to 7 pixels per patch, 3 px at 8, 5 px at 16). */
int im_height_outline_width(const im_height_style *style);

/* Draws heights through the colour map, hill-shaded with Lambert's law from per-patch normals
 * (central differences of heights / delta, one-sided at the edges), and, with style->contact,
 * a line along the edges between patches in contact and patches not in contact, inside the
 * contact patches. NaN heights take the bad colour, unshaded. Errors as im_render_contact_map,
 * and IM_EINVAL when the contact field's grid differs. */
int im_render_height_map(im_render_context *context, const im_field *height, const im_height_style *style,
                         im_image *image);

/* ---- 3-D view of the deformed surface ----
 *
 * World coordinates are in patches: x right and y up as in the 2-D maps (patch (ix, iy) covers
 * [ix, ix + 1) x [iy, iy + 1)), z = exaggeration * height / delta. The surface is a mesh with one
 * vertex per patch corner, its height the mean of the (up to four) patches that share the
 * corner, each square split along its diagonal from (ix, iy) to (ix + 1, iy + 1). A fragment
 * takes the colour and the normal of the patch it lies in: colour from the force through the
 * norm (as im_render_contact_map, so contact patches have the exact colours of the 2-D map), from
 * the tension -f through the tension norm where force < 0, or the surface colour where force = 0;
 * normal from central differences of the patch heights (one-sided at the edges), like the 2-D
 * height map. Shading is Lambert's law relative to level
 * ground: a level patch keeps its exact colour (shade 1) whatever the light, so a flat surface
 * seen from straight above reproduces the 2-D contact map; shade = 1 + shading * (max(n.l, 0) /
 * l_z - 1), then the colour times shade, clamped to [0, 1].
 *
 * Side walls close the surface into a block: from each edge corner straight down to a flat base
 * 0.04 * max(nx, ny) below the lowest edge corner, in the surface colour darkened to 85 %, lit with an
 * ambient part (0.55 + 0.45 max(n.l, 0)). Seen from straight above they cover no pixel.
 *
 * Level of detail: with more than mesh_side patches along the longer side, the mesh is built on
 * every s-th corner (s = ceil(longer side / mesh_side)), each corner's height the mean of the 2s x
 * 2s patches around it; colours and normals stay per patch, so contact patches keep their
 * outlines while the geometry is coarser.
 *
 * Camera: it looks at the target, the centre of the grid (nx / 2, ny / 2) at the height target_z
 * (by default the middle of the surface's drawn height range), from the direction
 *     (cos(el) sin(az), -cos(el) cos(az), sin(el)),
 * az = azimuth, el = elevation: azimuth 0 looks from the bottom edge of the 2-D map (-y) towards
 * +y, 90 from the right edge (+x). Its right-hand direction is (cos az, sin az, 0) and up is
 * right x forward, so a top view (elevation 90, azimuth 0) is oriented as the 2-D map.
 * Perspective: the eye at target + distance * L * direction, L = max(nx, ny), vertical field of
 * view field_of_view degrees. Orthographic: ortho_height patches of the world span the image's
 * height (0: automatic, 1.15 * the grid's diagonal). Pixel centres map to normalised device
 * coordinates the usual GL way (x from the left, y from the bottom of the image).
 *
 * The punch (optional): its profile (indenter.h) revolved around its axis, in world units with
 * the same exaggeration, placed where it touches the deformed surface: its lowest point at
 * c = max over patches of (h / delta - profile(r) / delta), r the patch centre's distance from
 * the axis, i.e. resting on the heights it presses. Drawn out to the radius punch_extent (cone,
 * sphere), then a cylindrical shaft 0.12 max(nx, ny) high closed by a flat top; a flat punch as
 * a cylinder of its radius and that height.
 */
typedef enum im_view3d_projection { IM_VIEW3D_PERSPECTIVE = 0, IM_VIEW3D_ORTHOGRAPHIC = 1 } im_view3d_projection;

typedef enum im_view3d_punch {
    IM_VIEW3D_PUNCH_TRANSLUCENT = 0, /* blended over the scene with punch_opacity */
    IM_VIEW3D_PUNCH_OPAQUE = 1,      /* solid: what lies behind it is hidden */
    IM_VIEW3D_PUNCH_CUTAWAY = 2,     /* solid, its half towards the camera removed */
    IM_VIEW3D_PUNCH_NONE = 3
} im_view3d_punch;

typedef struct im_view3d_camera {
    double azimuth;       /* degrees, any finite value (see above) */
    double elevation;     /* degrees above the horizon, [1, 90] */
    double distance;      /* perspective: eye-target distance in units of max(nx, ny), > 0 */
    double field_of_view; /* perspective: vertical, degrees, (1, 120) */
    im_view3d_projection projection;
    double ortho_height; /* orthographic: world height spanned by the image, in patches; 0 auto */
    double target_z;     /* height looked at, in world units (exaggerated patches); NAN: the
                                  middle of the surface's drawn range. Frames of a history fix it
                                  so that the camera stays put as the surface deforms. */
} im_view3d_camera;

typedef struct im_view3d_style {
    im_colormap colormap;  /* norm on the local compressive force */
    int width, height;     /* image size in pixels, >= 16 each */
    int samples;           /* multisampling per pixel: 1 (none), 2, 4 or 8; capped at the GL
                                  implementation's GL_MAX_SAMPLES */
    int mesh_side;         /* level of detail: most mesh cells along the longer side, >= 8 */
    double exaggeration;   /* vertical exaggeration, > 0 (1: true scale) */
    double shading;        /* [0, 1]: 0 unlit (exact colours everywhere) */
    double light_azimuth;  /* degrees, clockwise from +y, as the 2-D height map */
    double light_altitude; /* degrees above the horizon, (0, 90] */
    uint8_t surface[3];    /* patches not in contact (force = 0, or no force field) */
    im_colormap tension;   /* norm on the tension -f of patches with force < 0, as the contact map's */
    uint8_t background[3];
    uint8_t punch_colour[3];
    im_view3d_punch punch_mode;
    double punch_opacity; /* translucent punch: (0, 1) */
    double punch_extent;  /* radius to which a cone or sphere is drawn, in patches; 0:
                                  automatic (0.3 * min(nx, ny), a sphere at most its radius) */
    im_view3d_camera camera;
} im_view3d_style;

/* Defaults for a force field (may be NULL): the contact map's norms (im_contact_style_default),
 * 1920 x 1080 pixels, 4 samples, mesh_side 384, true scale (exaggeration 1), shading 0.7, light
 * from 315 degrees at 45 degrees, surface light grey (230),
 * white background, a steel-grey (150,
 * 160, 175) translucent punch of opacity 0.35, perspective from azimuth 20, elevation 35,
 * distance 2.1, field of view 30 degrees, automatic target height (NAN). */
im_view3d_style im_view3d_style_default(const im_field *force);

/* Draws the deformed surface `height` (h - u, in the field's units; all values finite) in 3-D,
 * with contact patches coloured by `force` (same grid; NULL: no contact colours) and the punch
 * (NULL: none; lengths in the units of delta, as solver.h). Multisampled; the read-back image is
 * the same on every run with the same inputs and renderer. The image's data_x, data_y and
 * pixels_per_patch are 0 (no patch maps to a fixed pixel square); nx, ny, delta and unit are the
 * field's. Errors: IM_EINVAL for a bad style (naming the member and the valid range), grids that
 * differ, or an image larger than the GL limits; IM_ENUMERIC for a non-finite height; IM_ENOMEM;
 * IM_EUNSUPPORTED if GL fails. On failure *image is left zeroed. */
int im_render_view3d(im_render_context *context, const im_field *height, const im_field *force,
                     const im_indenter *punch, const im_view3d_style *style, im_image *image);

/* The perspective camera distance (as im_view3d_camera.distance, in units of max(nx, ny)) at which
 * all that im_render_view3d draws for these inputs (the surface, the block under it, the punch
 * unless punch_mode is none) lies inside the image with 3 % of its half-width and half-height to
 * spare, seen from the style's camera direction, target and field of view at its image's aspect
 * ratio; the projection and the distance set in the style are not read. The frames of a history
 * take the largest over their steps for one camera that shows every step whole. Errors: IM_EINVAL
 * for a bad height, punch or camera (as im_render_view3d), also for a fitted distance the camera cannot take
 * (a needle of a cone rising 1e10 grid sides over the grid; *distance is set then), IM_ENUMERIC for a non-finite height,
 * IM_ENOMEM; *distance is NaN then. */
int im_view3d_fit_distance(const im_field *height, const im_indenter *punch, const im_view3d_style *style,
                           double *distance);

/* The statement of the vertical scale to print on a 3-D image: "true vertical scale" for an
 * exaggeration of 1, else "vertical exaggeration ×X" (UTF-8, X with up to 3 significant digits).
 * Writes at most size bytes. */
void im_view3d_exaggeration_text(double exaggeration, char *text, size_t size);

#ifdef __cplusplus
}
#endif

#endif
