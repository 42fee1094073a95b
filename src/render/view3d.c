/* The 3-D view of the deformed surface: a lit mesh coloured by local force, the punch, a camera. */
#include "render/context.h"
#include "core/args.h"
#include "render/shaders.h"

#include "indentmap/status.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The punch's shaft above its face, and the block under the surface below its lowest point, in
 * units of the grid's longer side. */
static const double SHAFT = 0.12, BASE_DEPTH = 0.04;

/* The walls' colour: the surface colour darkened, as the cut face of a block. */
static const double WALL_SHADE = 0.85;

/* What im_view3d_fit_distance leaves free on each side, as a fraction of the half image. */
static const double FIT_MARGIN = 0.03;

enum { PROFILE_POINTS = 64, PUNCH_SEGMENTS = 128, SPHERE_RINGS = 40, MIN_IMAGE_SIDE = 16 };

/* The surface's textures: codes, heights, corners, the colour map's table, the tension ramp's. */
enum { SURFACE_TEXTURES = 5 };

static double radians(double degrees) { return degrees * M_PI / 180.0; }

int render_view3d_setup(im_render_context *c)
{
    int status = render_link_program(&c->gl, im_shader_surface_vert, "surface.vert", im_shader_patch_colour,
                                     im_shader_surface_frag, "surface.frag", &c->surface_program);
    if (status == IM_OK)
        status = render_link_program(&c->gl, im_shader_punch_vert, "punch.vert", NULL, im_shader_punch_frag,
                                     "punch.frag", &c->punch_program);
    if (status == IM_OK)
        status = render_link_program(&c->gl, im_shader_wall_vert, "wall.vert", NULL, im_shader_wall_frag, "wall.frag",
                                     &c->wall_program);
    return status;
}

im_view3d_style im_view3d_style_default(const im_field *force)
{
    if (force && arg_view(__func__, "force", force) != IM_OK)
        force = NULL; /* an invalid view: the defaults without a force field */
    im_view3d_style style = {.colormap = force ? im_contact_style_default(force).colormap
                                               : im_colormap_make(IM_COLORMAP_VIRIDIS, 0.0, 1.0),
                             .tension = im_contact_tension_norm(force ? im_contact_largest_tension(force) : 0.0),
                             .width = 1920,
                             .height = 1080,
                             .samples = 4,
                             .mesh_side = 384,
                             .exaggeration = 1.0,
                             .shading = 0.7,
                             .light_azimuth = 315.0,
                             .light_altitude = 45.0,
                             .surface = {230, 230, 230},
                             .background = {255, 255, 255},
                             .punch_colour = {150, 160, 175},
                             .punch_mode = IM_VIEW3D_PUNCH_TRANSLUCENT,
                             .punch_opacity = 0.35,
                             .punch_extent = 0.0,
                             .camera = {.azimuth = 20.0,
                                        .elevation = 35.0,
                                        .distance = 2.1,
                                        .field_of_view = 30.0,
                                        .projection = IM_VIEW3D_PERSPECTIVE,
                                        .ortho_height = 0.0,
                                        .target_z = NAN}};
    return style;
}

static int check_camera(const im_view3d_camera *k)
{
    if (!isfinite(k->azimuth) || !(k->elevation >= 1.0 && k->elevation <= 90.0))
        return im_fail(IM_EINVAL,
                       "3-D view: camera azimuth %g, elevation %g: expected a finite azimuth and "
                       "an elevation in [1, 90] degrees",
                       k->azimuth, k->elevation);
    if (k->projection != IM_VIEW3D_PERSPECTIVE && k->projection != IM_VIEW3D_ORTHOGRAPHIC)
        return im_fail(IM_EINVAL, "3-D view: camera projection %d: expected perspective or orthographic",
                       (int)k->projection);
    if (!(k->distance > 0.0 && k->distance < 1e6))
        return im_fail(IM_EINVAL, "3-D view: camera distance = %g: expected (0, 1e6) grid sides", k->distance);
    if (!(k->field_of_view > 1.0 && k->field_of_view < 120.0))
        return im_fail(IM_EINVAL, "3-D view: field_of_view = %g: expected (1, 120) degrees", k->field_of_view);
    if (isinf(k->target_z))
        return im_fail(IM_EINVAL, "3-D view: target_z is infinite: expected a height or NAN (automatic)");
    if (!(k->ortho_height >= 0.0 && k->ortho_height < 1e9))
        return im_fail(IM_EINVAL,
                       "3-D view: ortho_height = %g: expected 0 (automatic) or a positive "
                       "height in patches",
                       k->ortho_height);
    return IM_OK;
}

/* The members that decide what is drawn where (no GL limit involved). */
static int check_geometry_style(const im_view3d_style *s)
{
    if (s->mesh_side < 8)
        return im_fail(IM_EINVAL, "3-D view: mesh_side = %d: expected at least 8", s->mesh_side);
    if (!(s->exaggeration > 0.0 && s->exaggeration < 1e6))
        return im_fail(IM_EINVAL, "3-D view: exaggeration = %g: expected (0, 1e6)", s->exaggeration);
    if (s->punch_mode < IM_VIEW3D_PUNCH_TRANSLUCENT || s->punch_mode > IM_VIEW3D_PUNCH_NONE)
        return im_fail(IM_EINVAL, "3-D view: punch_mode = %d: expected translucent, opaque, cutaway or none",
                       (int)s->punch_mode);
    if (!(s->punch_extent >= 0.0 && s->punch_extent < 1e9))
        return im_fail(IM_EINVAL, "3-D view: punch_extent = %g: expected 0 (automatic) or a radius in patches",
                       s->punch_extent);
    if (s->width < MIN_IMAGE_SIDE || s->height < MIN_IMAGE_SIDE)
        return im_fail(IM_EINVAL, "3-D view: image %d x %d pixels: expected at least %d per side", s->width,
                       s->height, MIN_IMAGE_SIDE);
    return check_camera(&s->camera);
}

static int check_style(const im_render_context *c, const im_view3d_style *s, const im_field *height)
{
    if (height->nx > c->max_texture_size || height->ny > c->max_texture_size)
        return im_fail(IM_EINVAL, "3-D view: grid %d x %d exceeds GL_MAX_TEXTURE_SIZE %d of %s", height->nx,
                       height->ny, c->max_texture_size, c->renderer);
    int status = im_colormap_check(&s->colormap);
    if (status != IM_OK)
        return im_fail_context(status, "3-D view");
    status = im_colormap_check(&s->tension);
    if (status != IM_OK)
        return im_fail_context(status, "3-D view: tension");
    long limit = render_image_limit(c);
    if (s->width < MIN_IMAGE_SIDE || s->height < MIN_IMAGE_SIDE || s->width > limit || s->height > limit)
        return im_fail(IM_EINVAL, "3-D view: image %d x %d pixels: expected %d..%ld per side (GL limits of %s)",
                       s->width, s->height, MIN_IMAGE_SIDE, limit, c->renderer);
    if (s->samples != 1 && s->samples != 2 && s->samples != 4 && s->samples != 8)
        return im_fail(IM_EINVAL, "3-D view: samples = %d: expected 1, 2, 4 or 8", s->samples);
    if (s->mesh_side < 8 || s->mesh_side > c->max_texture_size - 1)
        return im_fail(IM_EINVAL, "3-D view: mesh_side = %d: expected 8..%d", s->mesh_side, c->max_texture_size - 1);
    if (!(s->shading >= 0.0 && s->shading <= 1.0))
        return im_fail(IM_EINVAL, "3-D view: shading = %g: expected [0, 1]", s->shading);
    if (!(s->light_altitude > 0.0 && s->light_altitude <= 90.0) || !isfinite(s->light_azimuth))
        return im_fail(IM_EINVAL,
                       "3-D view: light altitude %g, azimuth %g: expected altitude in (0, 90] "
                       "degrees and a finite azimuth",
                       s->light_altitude, s->light_azimuth);
    if (s->punch_mode == IM_VIEW3D_PUNCH_TRANSLUCENT && !(s->punch_opacity > 0.0 && s->punch_opacity < 1.0))
        return im_fail(IM_EINVAL, "3-D view: punch_opacity = %g: expected (0, 1)", s->punch_opacity);
    return check_geometry_style(s);
}

static int check_inputs(const im_field *height, const im_field *force, const im_indenter *punch)
{
    if (!height || height->nx < 2 || height->ny < 2)
        return im_fail(IM_EINVAL, "3-D view: expected a height field of at least 2 x 2 patches");
    int status = im_field_check_finite(height, "3-D view: height");
    if (status != IM_OK)
        return status;
    if (force && (force->nx != height->nx || force->ny != height->ny))
        return im_fail(IM_EINVAL, "3-D view: force field %d x %d: expected the grid of the heights, %d x %d",
                       force->nx, force->ny, height->nx, height->ny);
    if (punch && punch->kind == IM_PUNCH_PROFILE_2D)
        return im_fail(IM_EUNSUPPORTED, "3-D view: a 2-D profile punch is not drawn (axisymmetric punches only; "
                                        "draw without the punch)");
    return punch ? im_indenter_check(punch) : IM_OK;
}

void im_view3d_exaggeration_text(double exaggeration, char *text, size_t size)
{
    ARG_REQUIRE_OR(text, "text", );
    if (exaggeration == 1.0)
        snprintf(text, size, "true vertical scale");
    else
        snprintf(text, size, "vertical exaggeration \u00d7%.3g", exaggeration);
}

/* ---- what is drawn, in world units (patches) ---- */

typedef struct view_geometry {
    int nx, ny, stride, cells_x, cells_y;
    double z_lo, z_hi; /* exaggerated surface heights */
    double base;       /* the bottom of the block under the surface */
    int has_punch;
    double axis[2];
    float profile[PROFILE_POINTS][2];
    int profile_count;
    double punch_top; /* highest z of the punch */
} view_geometry;

static double punch_profile(const im_indenter *punch, double delta, double r_patches)
{
    return im_indenter_profile(punch, r_patches * delta) / delta;
}

/* The height of the punch's lowest point, in patches: it rests on the heights it presses. */
static double punch_base(const im_field *h, const im_indenter *punch, const double axis[2])
{
    double base = -INFINITY, highest = -INFINITY;
    for (int iy = 0; iy < h->ny; ++iy)
        for (int ix = 0; ix < h->nx; ++ix) {
            double z = h->data[(size_t)iy * h->nx + ix] / h->delta;
            double r = hypot(ix + 0.5 - axis[0], iy + 0.5 - axis[1]);
            highest = fmax(highest, z);
            base = fmax(base, z - punch_profile(punch, h->delta, r));
        }
    return isfinite(base) ? base : highest;
}

static void add_profile_point(view_geometry *g, double r, double z)
{
    g->profile[g->profile_count][0] = (float)r;
    g->profile[g->profile_count][1] = (float)z;
    g->profile_count++;
    g->punch_top = fmax(g->punch_top, z);
}

/* The punch's profile polyline from its tip outwards, up its shaft, then its flat top back to the axis. */
static void punch_geometry(view_geometry *g, const im_field *h, const im_indenter *punch, const im_view3d_style *s)
{
    double x, y, e = s->exaggeration;
    im_indenter_axis(punch, h->nx, h->ny, h->delta, &x, &y);
    g->axis[0] = x / h->delta;
    g->axis[1] = y / h->delta;
    double base = punch_base(h, punch, g->axis), side = fmin(h->nx, h->ny);
    g->has_punch = 1;
    g->punch_top = -INFINITY;
    if (punch->kind == IM_PUNCH_FLAT) {
        double a = punch->radius / h->delta, top = e * base + SHAFT * fmax(h->nx, h->ny);
        add_profile_point(g, 0.0, e * base);
        add_profile_point(g, a, e * base);
        add_profile_point(g, a, top);
        add_profile_point(g, 0.0, top);
        return;
    }
    double extent = s->punch_extent > 0.0 ? s->punch_extent : 0.3 * side;
    if (punch->kind == IM_PUNCH_SPHERE && s->punch_extent <= 0.0)
        extent = fmin(extent, punch->radius / h->delta);
    if (punch->kind == IM_PUNCH_PROFILE) /* drawn up to its last sample */
        extent = fmin(extent, im_profile_extent(punch->profile) / h->delta);
    int rings = punch->kind == IM_PUNCH_CONE ? 2 : SPHERE_RINGS;
    for (int k = 0; k < rings; ++k) {
        double r = extent * k / (rings - 1);
        add_profile_point(g, r, e * (base + punch_profile(punch, h->delta, r)));
    }
    add_profile_point(g, extent, g->punch_top + SHAFT * fmax(h->nx, h->ny));
    add_profile_point(g, 0.0, g->punch_top);
}

static void surface_geometry(view_geometry *g, const im_field *h, const im_view3d_style *s)
{
    g->nx = h->nx;
    g->ny = h->ny;
    int longer = h->nx > h->ny ? h->nx : h->ny;
    g->stride = (longer + s->mesh_side - 1) / s->mesh_side;
    g->cells_x = (h->nx + g->stride - 1) / g->stride;
    g->cells_y = (h->ny + g->stride - 1) / g->stride;
    g->z_lo = INFINITY;
    g->z_hi = -INFINITY;
    for (size_t i = 0; i < im_field_count(h); ++i) {
        g->z_lo = fmin(g->z_lo, s->exaggeration * h->data[i] / h->delta);
        g->z_hi = fmax(g->z_hi, s->exaggeration * h->data[i] / h->delta);
    }
}

/* Corner heights / delta: the mean of the 2 stride x 2 stride patches around each mesh corner. */
static void corner_heights(const view_geometry *g, const im_field *h, float *corners)
{
    int s = g->stride;
    for (int b = 0; b <= g->cells_y; ++b)
        for (int a = 0; a <= g->cells_x; ++a) {
            int x = a * s < g->nx ? a * s : g->nx, y = b * s < g->ny ? b * s : g->ny;
            int x0 = x - s > 0 ? x - s : 0, x1 = x + s < g->nx ? x + s : g->nx;
            int y0 = y - s > 0 ? y - s : 0, y1 = y + s < g->ny ? y + s : g->ny;
            double sum = 0.0;
            for (int iy = y0; iy < y1; ++iy)
                for (int ix = x0; ix < x1; ++ix)
                    sum += h->data[(size_t)iy * g->nx + ix];
            corners[(size_t)b * (g->cells_x + 1) + a] = (float)(sum / ((double)(x1 - x0) * (y1 - y0)) / h->delta);
        }
}

/* ---- camera ---- */

typedef struct camera_frame {
    double eye[3], right[3], up[3], forward[3];
    double view_projection[16]; /* column-major, as GL takes it */
} camera_frame;

static void camera_axes(const im_view3d_camera *k, camera_frame *f)
{
    double az = radians(k->azimuth), el = radians(k->elevation);
    double towards_eye[3] = {cos(el) * sin(az), -cos(el) * cos(az), sin(el)};
    for (int i = 0; i < 3; ++i)
        f->forward[i] = -towards_eye[i];
    f->right[0] = cos(az);
    f->right[1] = sin(az);
    f->right[2] = 0.0;
    /* up = right x forward */
    f->up[0] = f->right[1] * f->forward[2] - f->right[2] * f->forward[1];
    f->up[1] = f->right[2] * f->forward[0] - f->right[0] * f->forward[2];
    f->up[2] = f->right[0] * f->forward[1] - f->right[1] * f->forward[0];
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static double drawn_top(const view_geometry *g) { return g->has_punch ? fmax(g->z_hi, g->punch_top) : g->z_hi; }

static void camera_target(const view_geometry *g, const im_view3d_camera *k, double target[3])
{
    target[0] = 0.5 * g->nx;
    target[1] = 0.5 * g->ny;
    target[2] = isnan(k->target_z) ? 0.5 * (g->z_lo + g->z_hi) : k->target_z;
}

/* The least eye-target distance D at which `point` lies inside the image, FIT_MARGIN of its
 * half-width and half-height to spare: at offset d from the target the point lies at depth
 * D + d.forward, and fits when |d.right| <= (D + d.forward) tan_x and |d.up| <= (D + d.forward) tan_y. */
static double fitting_distance(const camera_frame *f, const double target[3], const double point[3], double tan_x,
                               double tan_y)
{
    double d[3] = {point[0] - target[0], point[1] - target[1], point[2] - target[2]};
    return fmax(fabs(dot3(d, f->right)) / tan_x, fabs(dot3(d, f->up)) / tan_y) - dot3(d, f->forward);
}

/* The smallest eye-target distance (in patches) at which all that is drawn fits the image: the
 * corners of the block (the grid from the base to the highest surface point) and the punch's
 * rings (the vertices of its drawn polygons). The picture of the convex hull of these points
 * holds the picture of the drawing. */
static double fit_distance(const view_geometry *g, const im_view3d_camera *k, double aspect)
{
    camera_frame f;
    camera_axes(k, &f);
    double target[3], distance = 0.0;
    camera_target(g, k, target);
    double tan_y = (1.0 - FIT_MARGIN) * tan(0.5 * radians(k->field_of_view)), tan_x = aspect * tan_y;
    double lo[3] = {0.0, 0.0, fmin(g->base, g->z_lo)}, hi[3] = {g->nx, g->ny, g->z_hi};
    for (int corner = 0; corner < 8; ++corner) {
        double point[3] = {corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1], corner & 4 ? hi[2] : lo[2]};
        distance = fmax(distance, fitting_distance(&f, target, point, tan_x, tan_y));
    }
    for (int i = 0; g->has_punch && i < g->profile_count; ++i)
        for (int segment = 0; segment < PUNCH_SEGMENTS; ++segment) {
            double angle = 2.0 * M_PI * segment / PUNCH_SEGMENTS, r = g->profile[i][0];
            double point[3] = {g->axis[0] + r * cos(angle), g->axis[1] + r * sin(angle), g->profile[i][1]};
            distance = fmax(distance, fitting_distance(&f, target, point, tan_x, tan_y));
        }
    return distance;
}

/* Eye, axes and the view-projection matrix for an image of the given aspect ratio. */
static void camera_frame_of(const view_geometry *g, const im_view3d_camera *k, double aspect, camera_frame *f)
{
    camera_axes(k, f);
    double z_hi = drawn_top(g), target[3];
    camera_target(g, k, target);
    double extent[3] = {0.5 * g->nx, 0.5 * g->ny, fmax(z_hi - target[2], target[2] - fmin(g->base, g->z_lo))};
    double radius = sqrt(dot3(extent, extent)) + 1.0, longer = g->nx > g->ny ? g->nx : g->ny;
    int perspective = k->projection == IM_VIEW3D_PERSPECTIVE;
    double distance = perspective ? k->distance * longer : 2.0 * radius + 1.0;
    for (int i = 0; i < 3; ++i)
        f->eye[i] = target[i] - distance * f->forward[i];
    double near = fmax(distance - radius, 1e-3 * distance), far = distance + radius;
    double p[4][4] = {{0}}; /* p[row][column] */
    if (perspective) {
        double focal = 1.0 / tan(0.5 * radians(k->field_of_view));
        p[0][0] = focal / aspect;
        p[1][1] = focal;
        p[2][2] = (far + near) / (near - far);
        p[2][3] = 2.0 * far * near / (near - far);
        p[3][2] = -1.0;
    } else {
        double half = 0.5 * (k->ortho_height > 0.0 ? k->ortho_height : 1.15 * hypot(g->nx, g->ny));
        p[0][0] = 1.0 / (half * aspect);
        p[1][1] = 1.0 / half;
        p[2][2] = -2.0 / (far - near);
        p[2][3] = -(far + near) / (far - near);
        p[3][3] = 1.0;
    }
    /* view: rows right, up, -forward, translated to the eye */
    double v[4][4] = {{f->right[0], f->right[1], f->right[2], -dot3(f->right, f->eye)},
                      {f->up[0], f->up[1], f->up[2], -dot3(f->up, f->eye)},
                      {-f->forward[0], -f->forward[1], -f->forward[2], dot3(f->forward, f->eye)},
                      {0, 0, 0, 1}};
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 4; ++column) {
            double sum = 0.0;
            for (int i = 0; i < 4; ++i)
                sum += p[row][i] * v[i][column];
            f->view_projection[column * 4 + row] = sum;
        }
}

/* ---- drawing ---- */

typedef struct view_targets {
    GLuint multisampled, resolved, colour, depth, resolved_colour;
} view_targets;

static int make_targets(const im_render_context *c, int width, int height, int samples, view_targets *t)
{
    const im_gl *gl = &c->gl;
    gl->GenFramebuffers(1, &t->multisampled);
    gl->GenFramebuffers(1, &t->resolved);
    gl->GenRenderbuffers(1, &t->colour);
    gl->GenRenderbuffers(1, &t->depth);
    gl->GenRenderbuffers(1, &t->resolved_colour);
    gl->BindFramebuffer(GL_FRAMEBUFFER, t->multisampled);
    gl->BindRenderbuffer(GL_RENDERBUFFER, t->colour);
    gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->colour);
    gl->BindRenderbuffer(GL_RENDERBUFFER, t->depth);
    gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width, height);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t->depth);
    GLenum complete = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
    gl->BindFramebuffer(GL_FRAMEBUFFER, t->resolved);
    gl->BindRenderbuffer(GL_RENDERBUFFER, t->resolved_colour);
    gl->RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->resolved_colour);
    if (complete == GL_FRAMEBUFFER_COMPLETE)
        complete = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
    gl->BindFramebuffer(GL_FRAMEBUFFER, t->multisampled);
    return complete == GL_FRAMEBUFFER_COMPLETE
               ? IM_OK
               : im_fail(IM_EUNSUPPORTED, "3-D view: framebuffer %d x %d with %d samples incomplete (0x%x)", width,
                         height, samples, complete);
}

static void release_targets(const im_gl *gl, view_targets *t)
{
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    GLuint buffers[3] = {t->colour, t->depth, t->resolved_colour}, frames[2] = {t->multisampled, t->resolved};
    gl->DeleteRenderbuffers(3, buffers);
    gl->DeleteFramebuffers(2, frames);
}

static void set_matrix(const im_gl *gl, GLuint program, const camera_frame *f)
{
    float m[16];
    for (int i = 0; i < 16; ++i)
        m[i] = (float)f->view_projection[i];
    gl->UniformMatrix4fv(gl->GetUniformLocation(program, "view_projection"), 1, GL_FALSE, m);
}

static void light_vector(const im_view3d_style *s, float light[3])
{
    double az = radians(s->light_azimuth), alt = radians(s->light_altitude);
    light[0] = (float)(cos(alt) * sin(az));
    light[1] = (float)(cos(alt) * cos(az));
    light[2] = (float)sin(alt);
}

/* Inputs of the surface shaders: per-patch codes and heights / delta, and the mesh's corners. */
typedef struct surface_inputs {
    uint16_t *codes;
    float *heights, *corners;
    uint32_t *indices; /* 6 per mesh cell: (0,0)-(1,0)-(1,1) and (0,0)-(1,1)-(0,1) */
} surface_inputs;

static void free_inputs(surface_inputs *in)
{
    free(in->codes);
    free(in->heights);
    free(in->corners);
    free(in->indices);
}

/* The base of the side walls: BASE_DEPTH grid sides below the lowest edge corner. (The surface
 * may dip below it inside, where nothing above can see it.) */
static void wall_base(view_geometry *g, const im_view3d_style *s, const float *corners)
{
    int row = g->cells_x + 1, longer = g->nx > g->ny ? g->nx : g->ny;
    double lowest = INFINITY;
    for (int a = 0; a <= g->cells_x; ++a)
        lowest = fmin(lowest, fmin(corners[a], corners[(size_t)g->cells_y * row + a]));
    for (int b = 0; b <= g->cells_y; ++b)
        lowest = fmin(lowest, fmin(corners[(size_t)b * row], corners[(size_t)b * row + g->cells_x]));
    g->base = s->exaggeration * lowest - BASE_DEPTH * longer;
}

/* Two triangles per cell, split along the diagonal from its corner (a, b) to (a + 1, b + 1). */
static void mesh_indices(const view_geometry *g, uint32_t *indices)
{
    uint32_t row = (uint32_t)g->cells_x + 1;
    for (uint32_t b = 0; b < (uint32_t)g->cells_y; ++b)
        for (uint32_t a = 0; a < (uint32_t)g->cells_x; ++a) {
            uint32_t corner = b * row + a;
            uint32_t cell[6] = {corner, corner + 1, corner + row + 1, corner, corner + row + 1, corner + row};
            memcpy(indices + 6 * ((size_t)b * g->cells_x + a), cell, sizeof cell);
        }
}

static int make_inputs(view_geometry *g, const im_field *h, const im_field *force, const im_view3d_style *s,
                       surface_inputs *in)
{
    size_t count = im_field_count(h), corners = (size_t)(g->cells_x + 1) * (g->cells_y + 1);
    in->codes = malloc(count * sizeof *in->codes);
    in->heights = malloc(count * sizeof *in->heights);
    in->corners = malloc(corners * sizeof *in->corners);
    in->indices = malloc(6 * (size_t)g->cells_x * g->cells_y * sizeof *in->indices);
    if (!in->codes || !in->heights || !in->corners || !in->indices) {
        free_inputs(in);
        return im_fail(IM_ENOMEM, "3-D view %d x %d: out of memory", h->nx, h->ny);
    }
    for (size_t i = 0; i < count; ++i) {
        in->codes[i] = (uint16_t)render_force_code(&s->colormap, &s->tension, force ? force->data[i] : 0.0);
        in->heights[i] = (float)(h->data[i] / h->delta);
    }
    corner_heights(g, h, in->corners);
    mesh_indices(g, in->indices);
    wall_base(g, s, in->corners);
    return IM_OK;
}

static void draw_surface(const im_render_context *c, const view_geometry *g, const surface_inputs *in,
                         const im_view3d_style *s, const camera_frame *f, GLuint textures[SURFACE_TEXTURES])
{
    const im_gl *gl = &c->gl;
    GLuint program = c->surface_program;
    gl->UseProgram(program);
    textures[0] = render_texture(gl, 0, GL_R16UI, g->nx, g->ny, GL_RED_INTEGER, GL_UNSIGNED_SHORT, in->codes);
    textures[1] = render_texture(gl, 1, GL_R32F, g->nx, g->ny, GL_RED, GL_FLOAT, in->heights);
    textures[2] = render_texture(gl, 2, GL_R32F, g->cells_x + 1, g->cells_y + 1, GL_RED, GL_FLOAT, in->corners);
    textures[3] = render_table_texture(gl, 3, s->colormap.map);
    render_set_int(gl, program, "codes", 0);
    render_set_int(gl, program, "heights", 1);
    render_set_int(gl, program, "corners", 2);
    render_set_int(gl, program, "table", 3);
    render_set_colour(gl, program, "under_colour", s->colormap.under);
    render_set_colour(gl, program, "over_colour", s->colormap.over);
    render_set_colour(gl, program, "bad_colour", s->colormap.bad);
    render_set_colour(gl, program, "surface_colour", s->surface);
    textures[4] = render_tension_texture(gl, program, 4, &s->tension);
    gl->Uniform2i(gl->GetUniformLocation(program, "grid"), g->nx, g->ny);
    gl->Uniform2i(gl->GetUniformLocation(program, "cells"), g->cells_x, g->cells_y);
    render_set_int(gl, program, "stride", g->stride);
    gl->Uniform1f(gl->GetUniformLocation(program, "exaggeration"), (float)s->exaggeration);
    gl->Uniform1f(gl->GetUniformLocation(program, "shading"), (float)s->shading);
    float light[3];
    light_vector(s, light);
    gl->Uniform3f(gl->GetUniformLocation(program, "light"), light[0], light[1], light[2]);
    set_matrix(gl, program, f);
    GLsizei count = 6 * g->cells_x * g->cells_y;
    GLuint buffer;
    gl->GenBuffers(1, &buffer);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffer);
    gl->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)count * sizeof *in->indices, in->indices, GL_STATIC_DRAW);
    gl->DrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, NULL);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    gl->DeleteBuffers(1, &buffer);
}

/* The side walls, reusing the surface's corner texture (still bound on unit 2). */
static void draw_walls(const im_render_context *c, const view_geometry *g, const im_view3d_style *s,
                       const camera_frame *f)
{
    const im_gl *gl = &c->gl;
    GLuint program = c->wall_program;
    gl->UseProgram(program);
    render_set_int(gl, program, "corners", 2);
    gl->Uniform2i(gl->GetUniformLocation(program, "grid"), g->nx, g->ny);
    gl->Uniform2i(gl->GetUniformLocation(program, "cells"), g->cells_x, g->cells_y);
    render_set_int(gl, program, "stride", g->stride);
    gl->Uniform1f(gl->GetUniformLocation(program, "exaggeration"), (float)s->exaggeration);
    gl->Uniform1f(gl->GetUniformLocation(program, "base"), (float)g->base);
    uint8_t wall[3];
    for (int k = 0; k < 3; ++k)
        wall[k] = (uint8_t)(WALL_SHADE * s->surface[k]);
    render_set_colour(gl, program, "wall_colour", wall);
    float light[3];
    light_vector(s, light);
    gl->Uniform3f(gl->GetUniformLocation(program, "light"), light[0], light[1], light[2]);
    set_matrix(gl, program, f);
    gl->DrawArrays(GL_TRIANGLES, 0, 6 * 2 * (g->cells_x + g->cells_y));
}

static void draw_punch(const im_render_context *c, const view_geometry *g, const im_view3d_style *s,
                       const camera_frame *f)
{
    const im_gl *gl = &c->gl;
    GLuint program = c->punch_program;
    int translucent = s->punch_mode == IM_VIEW3D_PUNCH_TRANSLUCENT;
    gl->UseProgram(program);
    gl->Uniform2fv(gl->GetUniformLocation(program, "profile"), g->profile_count, &g->profile[0][0]);
    render_set_int(gl, program, "segments", PUNCH_SEGMENTS);
    gl->Uniform2f(gl->GetUniformLocation(program, "axis"), (float)g->axis[0], (float)g->axis[1]);
    double az = radians(s->camera.azimuth);
    gl->Uniform2f(gl->GetUniformLocation(program, "towards_camera"), (float)sin(az), (float)-cos(az));
    render_set_int(gl, program, "cutaway", s->punch_mode == IM_VIEW3D_PUNCH_CUTAWAY);
    gl->Uniform1f(gl->GetUniformLocation(program, "opacity"), translucent ? (float)s->punch_opacity : 1.0f);
    render_set_colour(gl, program, "punch_colour", s->punch_colour);
    float light[3];
    light_vector(s, light);
    gl->Uniform3f(gl->GetUniformLocation(program, "light"), light[0], light[1], light[2]);
    gl->Uniform3f(gl->GetUniformLocation(program, "eye"), (float)f->eye[0], (float)f->eye[1], (float)f->eye[2]);
    set_matrix(gl, program, f);
    GLsizei vertices = 6 * PUNCH_SEGMENTS * (g->profile_count - 1);
    /* Where the surface is in contact it lies on the punch's face: pushing the punch back by a
     * little depth lets the surface win the tie, so contact shows through a cut-away punch. */
    gl->Enable(GL_POLYGON_OFFSET_FILL);
    gl->PolygonOffset(1.0f, 4.0f);
    if (translucent) {
        /* Only the punch's nearest layer is blended over the surface: a depth-only pass first,
         * then colour where the depth is the punch's own. */
        gl->ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        gl->DrawArrays(GL_TRIANGLES, 0, vertices);
        gl->ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        gl->Enable(GL_BLEND);
        gl->BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        gl->DepthFunc(GL_LEQUAL);
    }
    gl->DrawArrays(GL_TRIANGLES, 0, vertices);
    gl->Disable(GL_BLEND);
    gl->Disable(GL_POLYGON_OFFSET_FILL);
    gl->DepthFunc(GL_LESS);
}

/* Clears, draws the surface then the punch into the multisampled target (samples 0: a plain
 * one), resolves, reads back. */
static int draw_view(const im_render_context *c, const view_geometry *g, const surface_inputs *in,
                     const im_view3d_style *s, int samples, im_image *image)
{
    const im_gl *gl = &c->gl;
    view_targets targets = {0};
    GLuint textures[SURFACE_TEXTURES] = {0};
    int status = make_targets(c, s->width, s->height, samples, &targets);
    if (status == IM_OK) {
        camera_frame frame;
        camera_frame_of(g, &s->camera, (double)s->width / s->height, &frame);
        gl->Viewport(0, 0, s->width, s->height);
        gl->ClearColor(s->background[0] / 255.0f, s->background[1] / 255.0f, s->background[2] / 255.0f, 1.0f);
        gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        gl->Enable(GL_DEPTH_TEST);
        gl->DepthFunc(GL_LESS);
        draw_surface(c, g, in, s, &frame, textures);
        draw_walls(c, g, s, &frame);
        if (g->has_punch)
            draw_punch(c, g, s, &frame);
        gl->Disable(GL_DEPTH_TEST);
        gl->BindFramebuffer(GL_READ_FRAMEBUFFER, targets.multisampled);
        gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, targets.resolved);
        gl->BlitFramebuffer(0, 0, s->width, s->height, 0, 0, s->width, s->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        gl->BindFramebuffer(GL_READ_FRAMEBUFFER, targets.resolved);
        gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl->ReadPixels(0, 0, s->width, s->height, GL_RGBA, GL_UNSIGNED_BYTE, image->rgba);
        GLenum error = gl->GetError();
        if (error != GL_NO_ERROR)
            status = im_fail(IM_EUNSUPPORTED, "3-D view %d x %d: GL error 0x%x", s->width, s->height, error);
    }
    gl->DeleteTextures(SURFACE_TEXTURES, textures);
    release_targets(gl, &targets);
    return status == IM_OK ? render_flip_rows(image->rgba, s->width, s->height) : status;
}

static int allocate_view_image(const im_field *h, const im_view3d_style *s, im_image *image)
{
    image->rgba = malloc((size_t)s->width * s->height * 4);
    if (!image->rgba)
        return im_fail(IM_ENOMEM, "3-D view image %d x %d: out of memory", s->width, s->height);
    image->width = s->width;
    image->height = s->height;
    image->nx = h->nx;
    image->ny = h->ny;
    image->delta = h->delta;
    memcpy(image->unit, h->unit, sizeof image->unit);
    return IM_OK;
}

static void view_geometry_of(view_geometry *g, const im_field *h, const im_indenter *punch, const im_view3d_style *s)
{
    surface_geometry(g, h, s);
    if (punch && s->punch_mode != IM_VIEW3D_PUNCH_NONE)
        punch_geometry(g, h, punch, s);
}

static int fitted_distance(const im_field *height, const im_indenter *punch, const im_view3d_style *s, double *fitted)
{
    int status = check_inputs(height, NULL, punch);
    if (status == IM_OK)
        status = check_geometry_style(s);
    if (status != IM_OK)
        return status;
    view_geometry g = {0};
    view_geometry_of(&g, height, punch, s);
    float *corners = malloc((size_t)(g.cells_x + 1) * (g.cells_y + 1) * sizeof *corners);
    if (!corners)
        return im_fail(IM_ENOMEM, "3-D view %d x %d: out of memory", height->nx, height->ny);
    corner_heights(&g, height, corners);
    wall_base(&g, s, corners);
    free(corners);
    *fitted = fit_distance(&g, &s->camera, (double)s->width / s->height) / fmax(g.nx, g.ny);
    im_view3d_camera camera = s->camera;
    camera.distance = *fitted; /* a camera the view can take: refused here, not after the frames' solves (S12) */
    return check_camera(&camera);
}

int im_view3d_fit_distance(const im_field *height, const im_indenter *punch, const im_view3d_style *s,
                           double *distance)
{
    ARG_REQUIRE(distance, "distance");
    int status = arg_view(__func__, "height", height);
    if (status == IM_OK && !s)
        status = arg_null(__func__, "style");
    double fitted = NAN; /* written last: `distance` may be the style's own camera distance */
    if (status == IM_OK)
        status = fitted_distance(height, punch, s, &fitted);
    *distance = fitted;
    return status;
}

int im_render_view3d(im_render_context *c, const im_field *height, const im_field *force, const im_indenter *punch,
                     const im_view3d_style *s, im_image *image)
{
    ARG_REQUIRE(c, "context");
    ARG_VIEW(height, "height");
    ARG_REQUIRE(s, "style");
    ARG_REQUIRE(image, "image");
    if (force)
        ARG_VIEW(force, "force");
    memset(image, 0, sizeof *image);
    int status = check_inputs(height, force, punch);
    if (status == IM_OK)
        status = check_style(c, s, height);
    if (status == IM_OK)
        status = im_memory_check(4.0 * (double)s->width * s->height * (2.0 * s->samples + 2.0) +
                                     14.0 * (double)im_field_count(height) +
                                     28.0 * (double)s->mesh_side * s->mesh_side,
                                 "3-D view");
    if (status != IM_OK)
        return status;
    view_geometry geometry = {0};
    view_geometry_of(&geometry, height, punch, s);
    surface_inputs inputs = {0};
    status = make_inputs(&geometry, height, force, s, &inputs);
    if (status == IM_OK)
        status = allocate_view_image(height, s, image);
    int samples = s->samples < c->max_samples ? s->samples : c->max_samples;
    if (status == IM_OK)
        status = render_make_current(c);
    if (status == IM_OK) {
        status = draw_view(c, &geometry, &inputs, s, samples > 1 ? samples : 0, image);
        render_release_current(c);
    }
    free_inputs(&inputs);
    if (status != IM_OK)
        im_image_release(image);
    return status;
}
