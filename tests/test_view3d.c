/* The 3-D view against references of its own: a camera model written here from render.h's
 * definitions, the 2-D contact map, a CPU ray-cast, depth ordering, repeatability. Needs a real GL
 * context; skipped (exit 77) only when none can be created and IM_REQUIRE_GL is not 1. */
#include "support.h"

#include "indentmap/colormap.h"
#include "indentmap/field.h"
#include "indentmap/render.h"
#include "indentmap/status.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static im_render_context *context;
static char open_error[2048];
static int skip_all;

static int gl_required(void)
{
    const char *required = getenv("IM_REQUIRE_GL");
    return required && strcmp(required, "1") == 0;
}

static int open_context(void **state)
{
    (void)state;
    int status = im_render_open(IM_RENDER_AUTO, &context);
    if (status != IM_OK) {
        snprintf(open_error, sizeof open_error, "%s", im_last_error());
        skip_all = im_render_context_missing(status, open_error) && !gl_required();
        context = NULL;
    }
    return 0;
}

static int close_context(void **state)
{
    (void)state;
    im_render_close(context);
    return 0;
}

#define REQUIRE_CONTEXT()                                                                                            \
    do {                                                                                                             \
        if (!context && skip_all)                                                                                    \
            skip();                                                                                                  \
        if (!context)                                                                                                \
            fail_msg("the renderer does not open: %s", open_error);                                                  \
    } while (0)

static double uniform(uint64_t *state)
{
    *state = *state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*state >> 11) * 0x1.0p-53;
}

static im_field *make_field(int nx, int ny)
{
    im_field *f = NULL;
    assert_int_equal(im_field_create(nx, ny, 1.0, &f), IM_OK);
    return f;
}

static const uint8_t *pixel(const im_image *image, int column, int row)
{
    return image->rgba + ((size_t)row * image->width + column) * 4;
}

static int same_pixel(const im_image *a, const im_image *b, int column, int row)
{
    return memcmp(pixel(a, column, row), pixel(b, column, row), 3) == 0;
}

/* ---- the camera, from render.h's words ---- */

typedef struct camera {
    double eye[3], right[3], up[3], forward[3];
    double tan_half, aspect, ortho_half; /* ortho_half > 0: orthographic */
    int width, height;
} camera;

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The target is the grid's centre at the middle of the surface's exaggerated height range. */
static camera camera_of(const im_field *h, const im_view3d_style *s)
{
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < im_field_count(h); ++i) {
        lo = fmin(lo, s->exaggeration * h->data[i]);
        hi = fmax(hi, s->exaggeration * h->data[i]);
    }
    camera c = {.width = s->width, .height = s->height, .aspect = (double)s->width / s->height};
    double az = s->camera.azimuth * M_PI / 180.0, el = s->camera.elevation * M_PI / 180.0;
    double toward[3] = {cos(el) * sin(az), -cos(el) * cos(az), sin(el)};
    double target[3] = {0.5 * h->nx, 0.5 * h->ny, 0.5 * (lo + hi)};
    double distance = s->camera.distance * (h->nx > h->ny ? h->nx : h->ny);
    c.right[0] = cos(az);
    c.right[1] = sin(az);
    for (int i = 0; i < 3; ++i) {
        c.forward[i] = -toward[i];
        c.eye[i] = target[i] + distance * toward[i];
    }
    cross(c.right, c.forward, c.up);
    c.tan_half = tan(0.5 * s->camera.field_of_view * M_PI / 180.0);
    if (s->camera.projection == IM_VIEW3D_ORTHOGRAPHIC) {
        c.ortho_half = 0.5 * s->camera.ortho_height;
        memcpy(c.eye, target, sizeof target); /* the ray's origin moves in the image plane */
    }
    return c;
}

/* Pixel coordinates (x from the left, y from the top, pixel centres at + 0.5) of a world point. */
static void project(const camera *c, const double p[3], double *x, double *y)
{
    double d[3] = {p[0] - c->eye[0], p[1] - c->eye[1], p[2] - c->eye[2]};
    double u = dot(d, c->right), v = dot(d, c->up), w = dot(d, c->forward);
    double nx = c->ortho_half > 0 ? u / (c->ortho_half * c->aspect) : u / (w * c->tan_half * c->aspect);
    double ny = c->ortho_half > 0 ? v / c->ortho_half : v / (w * c->tan_half);
    *x = 0.5 * (nx + 1.0) * c->width;
    *y = 0.5 * (1.0 - ny) * c->height;
}

/* The ray through a pixel centre (perspective). */
static void ray(const camera *c, int column, int row, double direction[3])
{
    double nx = 2.0 * (column + 0.5) / c->width - 1.0, ny = 1.0 - 2.0 * (row + 0.5) / c->height;
    for (int i = 0; i < 3; ++i)
        direction[i] = c->forward[i] + nx * c->tan_half * c->aspect * c->right[i] + ny * c->tan_half * c->up[i];
}

static im_view3d_style plain_style(int width, int height)
{
    im_view3d_style s = im_view3d_style_default(NULL);
    s.width = width;
    s.height = height;
    s.punch_mode = IM_VIEW3D_PUNCH_NONE;
    return s;
}

/* A pyramid with its apex on the corner (ax, ay), slopes 0.6 (steeper than the line of sight): the apex is the topmost point seen
 * from a low camera, and its corner height (the mean of the four patches around it) is known. */
static void test_apex_projects_to_predicted_pixel(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    const int ax = 21, ay = 13;
    im_field *h = make_field(32, 32);
    for (int iy = 0; iy < 32; ++iy)
        for (int ix = 0; ix < 32; ++ix)
            h->data[iy * 32 + ix] = 10.0 - 0.6 * (fabs(ix + 0.5 - ax) + fabs(iy + 0.5 - ay));
    double apex_height = 10.0 - 0.6 * 1.0; /* each of the four patches is (0.5, 0.5) away */
    const double azimuths[] = {30.0, -70.0, 160.0};
    for (int k = 0; k < 3; ++k) {
        im_view3d_style s = plain_style(400, 300);
        s.samples = 1;
        s.shading = 0.0;
        s.camera.azimuth = azimuths[k];
        s.camera.elevation = 12.0;
        camera c = camera_of(h, &s);
        double apex[3] = {ax, ay, apex_height}, x, y;
        project(&c, apex, &x, &y);
        im_image image;
        assert_int_equal(im_render_view3d(context, h, NULL, NULL, &s, &image), IM_OK);
        int top = -1, column = -1;
        for (int row = 0; row < image.height && top < 0; ++row)
            for (int col = 0; col < image.width; ++col)
                if (pixel(&image, col, row)[0] != 255) {
                    top = row;
                    column = col;
                    break;
                }
        /* The first row whose pixel centres lie below the apex, the apex's column within the
         * silhouette's width there. */
        if (abs(top - (int)floor(y)) > 1 || fabs(column + 0.5 - x) > 3.0)
            fail_msg("azimuth %g: apex drawn at pixel (%d, %d), predicted (%.2f, %.2f)", azimuths[k], column, top, x,
                     y);
        im_image_release(&image);
    }
    im_field_free(h);
}

static im_field *random_forces(int nx, int ny, uint64_t seed)
{
    im_field *f = make_field(nx, ny);
    for (size_t i = 0; i < im_field_count(f); ++i) {
        double u = uniform(&seed);
        f->data[i] = u < 0.2 ? 0.0 : u < 0.25 ? -u : u < 0.27 ? NAN : 1.2 * uniform(&seed) + 1e-3;
    }
    return f;
}

/* A flat surface seen from straight above, orthographic, 4 pixels per patch: every pixel is the
 * 2-D contact map's, at full resolution and with a coarse mesh (level of detail) alike. */
static void test_flat_top_view_is_the_contact_map(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    const int nx = 48, ny = 32, scale = 4;
    im_field *force = random_forces(nx, ny, 11), *flat = make_field(nx, ny);
    for (size_t i = 0; i < im_field_count(flat); ++i)
        flat->data[i] = 3.25;
    im_contact_style map_style = im_contact_style_default(force);
    map_style.colormap = im_colormap_make(IM_COLORMAP_MAGMA, 0.1, 1.0);
    map_style.pixels_per_patch = scale;
    map_style.boundary_px = 0;
    im_image map;
    assert_int_equal(im_render_contact_map(context, force, &map_style, &map), IM_OK);
    const int meshes[] = {512, 8};
    for (int k = 0; k < 2; ++k) {
        im_view3d_style s = plain_style(nx * scale, ny * scale);
        s.colormap = map_style.colormap;
        memcpy(s.surface, map_style.background, 3);
        s.tension = map_style.tension;
        s.mesh_side = meshes[k];
        s.camera.projection = IM_VIEW3D_ORTHOGRAPHIC;
        s.camera.elevation = 90.0;
        s.camera.azimuth = 0.0;
        s.camera.ortho_height = ny;
        im_image view;
        assert_int_equal(im_render_view3d(context, flat, force, NULL, &s, &view), IM_OK);
        for (int row = 0; row < view.height; ++row)
            for (int column = 0; column < view.width; ++column)
                if (!same_pixel(&view, &map, column, row)) {
                    const uint8_t *a = pixel(&view, column, row), *b = pixel(&map, column, row);
                    fail_msg("mesh_side %d: pixel (%d, %d) = (%d, %d, %d), the contact map has (%d, %d, %d)",
                             meshes[k], column, row, a[0], a[1], a[2], b[0], b[1], b[2]);
                }
        im_image_release(&view);
    }
    im_image_release(&map);
    im_field_free(force);
    im_field_free(flat);
}

/* A 45 degree cone on a flat surface, a ridge between it and the camera, a contact patch behind
 * it: the opaque punch hides the patch (which shows without the punch), and the ridge hides the
 * punch (which shows there without the ridge). */
static void test_depth_ordering(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    const int n = 64;
    im_field *flat = make_field(n, n), *ridge = make_field(n, n), *force = make_field(n, n);
    for (int iy = 0; iy < n; ++iy)
        for (int ix = 0; ix < n; ++ix) {
            ridge->data[iy * n + ix] = iy >= 4 && iy < 8 ? 12.0 : 0.0;
            force->data[iy * n + ix] = ix >= 28 && ix < 37 && iy >= 38 && iy < 47 ? 1.0 : 0.0;
        }
    flat->data[n * n - 1] = 12.0; /* the ridge's height range, so that both have one camera */
    im_indenter cone = im_indenter_cone(45.0);
    im_view3d_style s = plain_style(480, 360);
    s.colormap = im_colormap_make(IM_COLORMAP_VIRIDIS, 0.0, 1.0);
    s.camera.azimuth = 0.0;
    s.camera.elevation = 20.0;
    camera c = camera_of(ridge, &s);
    double behind[3] = {32.5, 42.5, 0.0}, on_ridge[3] = {32.5, 6.0, 12.0}, x, y, rx, ry;
    project(&c, behind, &x, &y);
    project(&c, on_ridge, &rx, &ry);
    im_image images[4]; /* ridge without punch, ridge with punch, flat without, flat with */
    const im_field *heights[4] = {ridge, ridge, flat, flat};
    for (int k = 0; k < 4; ++k) {
        s.punch_mode = k % 2 ? IM_VIEW3D_PUNCH_OPAQUE : IM_VIEW3D_PUNCH_NONE;
        assert_int_equal(im_render_view3d(context, heights[k], force, &cone, &s, &images[k]), IM_OK);
    }
    int column = (int)x, row = (int)y, ridge_column = (int)rx, ridge_row = (int)ry + 2;
    const uint8_t *patch = pixel(&images[0], column, row);
    assert_true(patch[0] == 253 && patch[1] == 231 && patch[2] == 37);         /* viridis(1.0), level ground */
    assert_false(same_pixel(&images[0], &images[1], column, row));             /* hidden by the punch */
    assert_false(same_pixel(&images[2], &images[3], ridge_column, ridge_row)); /* the punch is there */
    assert_true(same_pixel(&images[0], &images[1], ridge_column, ridge_row));  /* the ridge hides it */
    for (int k = 0; k < 4; ++k)
        im_image_release(&images[k]);
    im_field_free(flat);
    im_field_free(ridge);
    im_field_free(force);
}

static im_field *rough(int nx, int ny, double amplitude, uint64_t seed)
{
    im_field *h = make_field(nx, ny);
    for (int iy = 0; iy < ny; ++iy)
        for (int ix = 0; ix < nx; ++ix)
            h->data[iy * nx + ix] = amplitude * (sin(0.7 * ix + 0.3) * cos(0.5 * iy) + 0.6 * uniform(&seed));
    return h;
}

/* Draw, draw something else, draw again: the same bytes. */
static void test_same_image_on_repeated_runs(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *h = rough(96, 80, 4.0, 3), *force = random_forces(96, 80, 5), *other = rough(96, 80, 9.0, 4);
    im_indenter cone = im_indenter_cone(70.0);
    im_view3d_style s = im_view3d_style_default(force);
    s.width = 640;
    s.height = 400;
    s.exaggeration = 2.0;
    im_image first, between, again;
    assert_int_equal(im_render_view3d(context, h, force, &cone, &s, &first), IM_OK);
    assert_int_equal(im_render_view3d(context, other, NULL, &cone, &s, &between), IM_OK);
    assert_int_equal(im_render_view3d(context, h, force, &cone, &s, &again), IM_OK);
    assert_memory_not_equal(first.rgba, between.rgba, (size_t)first.width * first.height * 4);
    assert_memory_equal(first.rgba, again.rgba, (size_t)first.width * first.height * 4);
    im_image_release(&first);
    im_image_release(&between);
    im_image_release(&again);
    im_field_free(h);
    im_field_free(force);
    im_field_free(other);
}

/* ---- a CPU ray-cast of the documented mesh and shading ---- */

typedef struct scene {
    const im_field *h, *force;
    const im_view3d_style *s;
    double *corners; /* (nx + 1) x (ny + 1), exaggerated */
} scene;

static double corner_height(const im_field *h, int x, int y)
{
    double sum = 0.0;
    int count = 0;
    for (int iy = y - 1; iy <= y; ++iy)
        for (int ix = x - 1; ix <= x; ++ix)
            if (ix >= 0 && iy >= 0 && ix < h->nx && iy < h->ny) {
                sum += h->data[iy * h->nx + ix];
                ++count;
            }
    return sum / count;
}

/* Distance along the ray to triangle (a, b, c), or INFINITY (Moller-Trumbore). */
static double hit_triangle(const double o[3], const double d[3], const double a[3], const double b[3],
                           const double c[3])
{
    double e1[3], e2[3], p[3], q[3], t[3];
    for (int i = 0; i < 3; ++i) {
        e1[i] = b[i] - a[i];
        e2[i] = c[i] - a[i];
        t[i] = o[i] - a[i];
    }
    cross(d, e2, p);
    double det = dot(e1, p);
    if (fabs(det) < 1e-12)
        return INFINITY;
    double u = dot(t, p) / det;
    cross(t, e1, q);
    double v = dot(d, q) / det, distance = dot(e2, q) / det;
    return u >= 0 && v >= 0 && u + v <= 1 && distance > 0 ? distance : INFINITY;
}

/* The nearest hit on the side walls (from each edge down to the base), or INFINITY. */
static double hit_walls(const scene *sc, const double o[3], const double d[3])
{
    int nx = sc->h->nx, ny = sc->h->ny;
    double nearest = INFINITY, base = INFINITY; /* 0.04 grid sides below the lowest edge corner */
    for (int y = 0; y <= ny; ++y)
        for (int x = 0; x <= nx; ++x)
            if (x == 0 || y == 0 || x == nx || y == ny)
                base = fmin(base, sc->corners[y * (nx + 1) + x] - 0.04 * (nx > ny ? nx : ny));
    for (int side = 0; side < 4; ++side) {
        int count = side % 2 ? ny : nx;
        for (int j = 0; j < count; ++j) {
            /* the wall quad under edge segment j of this side */
            int a[2], b[2];
            if (side == 0) {
                a[0] = j;
                a[1] = 0;
                b[0] = j + 1;
                b[1] = 0;
            } else if (side == 1) {
                a[0] = nx;
                a[1] = j;
                b[0] = nx;
                b[1] = j + 1;
            } else if (side == 2) {
                a[0] = j;
                a[1] = ny;
                b[0] = j + 1;
                b[1] = ny;
            } else {
                a[0] = 0;
                a[1] = j;
                b[0] = 0;
                b[1] = j + 1;
            }
            double top_a = sc->corners[a[1] * (nx + 1) + a[0]], top_b = sc->corners[b[1] * (nx + 1) + b[0]];
            double p0[3] = {a[0], a[1], base}, p1[3] = {b[0], b[1], base}, p2[3] = {b[0], b[1], top_b},
                   p3[3] = {a[0], a[1], top_a};
            nearest = fmin(nearest, fmin(hit_triangle(o, d, p0, p1, p2), hit_triangle(o, d, p0, p2, p3)));
        }
    }
    return nearest;
}

/* The nearest hit of the ray on the mesh (two triangles per patch along (x, y)-(x+1, y+1)); 0
 * when it misses or meets a side wall first. */
static int cast(const scene *sc, const double o[3], const double d[3], double hit[3])
{
    int nx = sc->h->nx, ny = sc->h->ny;
    double nearest = INFINITY;
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) {
            double v[4][3];
            const int corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            for (int k = 0; k < 4; ++k) {
                v[k][0] = x + corner[k][0];
                v[k][1] = y + corner[k][1];
                v[k][2] = sc->corners[(y + corner[k][1]) * (nx + 1) + x + corner[k][0]];
            }
            nearest = fmin(nearest, fmin(hit_triangle(o, d, v[0], v[1], v[2]), hit_triangle(o, d, v[0], v[2], v[3])));
        }
    for (int i = 0; i < 3; ++i)
        hit[i] = o[i] + nearest * d[i];
    return isfinite(nearest) && nearest < hit_walls(sc, o, d);
}

static double patch_height(const im_field *h, int x, int y)
{
    x = x < 0 ? 0 : x >= h->nx ? h->nx - 1 : x;
    y = y < 0 ? 0 : y >= h->ny ? h->ny - 1 : y;
    return h->data[y * h->nx + x];
}

/* The documented colour of patch (x, y): its force's colour (or the surface colour) times the
 * shade of its central-difference normal, relative to level ground. */
static void shaded_colour(const scene *sc, int x, int y, double rgb[3])
{
    const im_view3d_style *s = sc->s;
    const im_field *h = sc->h;
    double f = sc->force->data[y * h->nx + x];
    uint8_t base[3];
    if (f > 0.0)
        im_colormap_rgb(&s->colormap, f, base);
    else if (f < 0.0) /* under tension (adhesion) */
        im_colormap_rgb(&s->tension, -f, base);
    else
        memcpy(base, s->surface, 3);
    int left = x > 0 ? x - 1 : 0, right = x < h->nx - 1 ? x + 1 : x;
    int down = y > 0 ? y - 1 : 0, up = y < h->ny - 1 ? y + 1 : y;
    double sx = s->exaggeration * (patch_height(h, right, y) - patch_height(h, left, y)) / (right - left);
    double sy = s->exaggeration * (patch_height(h, x, up) - patch_height(h, x, down)) / (up - down);
    double norm = sqrt(sx * sx + sy * sy + 1.0), n[3] = {-sx / norm, -sy / norm, 1.0 / norm};
    double az = s->light_azimuth * M_PI / 180.0, alt = s->light_altitude * M_PI / 180.0;
    double l[3] = {cos(alt) * sin(az), cos(alt) * cos(az), sin(alt)};
    double shade = 1.0 + s->shading * (fmax(dot(n, l), 0.0) / l[2] - 1.0);
    for (int k = 0; k < 3; ++k)
        rgb[k] = 255.0 * fmin(fmax(base[k] / 255.0 * shade, 0.0), 1.0);
}

/* Pixels whose ray and the rays a pixel away hit one patch, away from its edges: compared with
 * the GL image within one colour level. */
static void test_cpu_ray_cast_agrees(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    const int nx = 14, ny = 12;
    im_field *h = rough(nx, ny, 1.5, 9), *force = random_forces(nx, ny, 21);
    for (size_t i = 0; i < im_field_count(force); ++i)
        force->data[i] = isnan(force->data[i]) ? 0.0 : force->data[i];
    im_view3d_style s = plain_style(640, 480);
    s.colormap = im_colormap_make(IM_COLORMAP_VIRIDIS, 0.0, 1.2);
    s.tension = im_contact_tension_norm(0.25); /* the tensions, 0.2 to 0.25: the ramp's upper fifth */
    s.tension.lo = 0.19;
    s.exaggeration = 1.7;
    s.camera.azimuth = 35.0;
    s.camera.elevation = 40.0;
    s.camera.distance = 1.3;
    double *corners = malloc(sizeof(double) * (nx + 1) * (ny + 1));
    for (int y = 0; y <= ny; ++y)
        for (int x = 0; x <= nx; ++x)
            corners[y * (nx + 1) + x] = s.exaggeration * corner_height(h, x, y);
    scene sc = {h, force, &s, corners};
    camera c = camera_of(h, &s);
    im_image image;
    assert_int_equal(im_render_view3d(context, h, force, NULL, &s, &image), IM_OK);
    int compared = 0;
    for (int row = 20; row < s.height; row += 23)
        for (int column = 20; column < s.width; column += 29) {
            double d[3], hit[3], expected[3];
            int patch[2] = {-1, -1}, same = 1;
            for (int k = 0; k < 5 && same; ++k) {
                const int offset[5][2] = {{0, 0}, {-1, 0}, {1, 0}, {0, -1}, {0, 1}};
                ray(&c, column + offset[k][0], row + offset[k][1], d);
                if (!cast(&sc, c.eye, d, hit)) {
                    same = 0;
                    break;
                }
                int px = (int)floor(hit[0]), py = (int)floor(hit[1]);
                double fx = hit[0] - px, fy = hit[1] - py;
                same = (k == 0 || (px == patch[0] && py == patch[1])) && fx > 0.1 && fx < 0.9 && fy > 0.1 && fy < 0.9;
                patch[0] = k == 0 ? px : patch[0];
                patch[1] = k == 0 ? py : patch[1];
            }
            if (!same)
                continue;
            shaded_colour(&sc, patch[0], patch[1], expected);
            const uint8_t *p = pixel(&image, column, row);
            for (int k = 0; k < 3; ++k)
                if (fabs(p[k] - expected[k]) > 1.0)
                    fail_msg("pixel (%d, %d) on patch (%d, %d): GL (%d, %d, %d), ray-cast (%.2f, %.2f, %.2f)", column,
                             row, patch[0], patch[1], p[0], p[1], p[2], expected[0], expected[1], expected[2]);
            ++compared;
        }
    print_message("ray-cast: %d pixels compared\n", compared);
    assert_true(compared >= 40);
    im_image_release(&image);
    free(corners);
    im_field_free(h);
    im_field_free(force);
}

/* Whether any pixel of the image's outermost rows and columns differs from the background. */
static int touches_border(const im_image *image, const uint8_t background[3])
{
    for (int row = 0; row < image->height; ++row)
        for (int column = 0; column < image->width; ++column) {
            int border = row == 0 || column == 0 || row == image->height - 1 || column == image->width - 1;
            if (border && memcmp(pixel(image, column, row), background, 3) != 0)
                return 1;
        }
    return 0;
}

/* A wide block under a cone, seen from low to high: at the fitted distance background surrounds
 * all that is drawn (the block's front edge included), 15 % nearer something is cut (a flat
 * surface, so that the block's corners are drawn points). */
static void test_fit_distance_frames_the_block(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *h = make_field(96, 64);
    im_indenter cone = im_indenter_cone(70.0);
    const double elevations[] = {15.0, 35.0, 80.0};
    for (int k = 0; k < 3; ++k) {
        im_view3d_style s = im_view3d_style_default(NULL);
        s.width = 480;
        s.height = 200;
        s.exaggeration = 3.0;
        s.camera.elevation = elevations[k];
        double fitted;
        assert_int_equal(im_view3d_fit_distance(h, &cone, &s, &fitted), IM_OK);
        const double scales[] = {1.0, 0.85};
        for (int near = 0; near < 2; ++near) {
            s.camera.distance = scales[near] * fitted;
            im_image image;
            assert_int_equal(im_render_view3d(context, h, NULL, &cone, &s, &image), IM_OK);
            if (touches_border(&image, s.background) != near)
                fail_msg("elevation %g, distance %g (%s the fitted %g): %s", elevations[k], s.camera.distance,
                         near ? "nearer than" : "at", fitted, near ? "nothing is cut" : "the view is cut");
            im_image_release(&image);
        }
    }
    im_field_free(h);
}

static void test_bad_input_refused(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *h = rough(16, 16, 1.0, 1), *force = make_field(16, 15);
    im_view3d_style s = plain_style(64, 64);
    im_image image;
    assert_int_equal(im_render_view3d(context, h, force, NULL, &s, &image), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "expected the grid of the heights"));
    assert_null(image.rgba);
    s.camera.elevation = 0.0;
    assert_int_equal(im_render_view3d(context, h, NULL, NULL, &s, &image), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "elevation"));
    s = plain_style(64, 64);
    s.samples = 3;
    assert_int_equal(im_render_view3d(context, h, NULL, NULL, &s, &image), IM_EINVAL);
    s = plain_style(64, 64);
    h->data[5] = NAN;
    assert_int_equal(im_render_view3d(context, h, NULL, NULL, &s, &image), IM_ENUMERIC);
    char text[64];
    im_view3d_exaggeration_text(2.5, text, sizeof text);
    assert_string_equal(text, "vertical exaggeration \u00d72.5");
    im_view3d_exaggeration_text(1.0, text, sizeof text);
    assert_string_equal(text, "true vertical scale");
    im_field_free(h);
    im_field_free(force);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_apex_projects_to_predicted_pixel),
        cmocka_unit_test(test_flat_top_view_is_the_contact_map),
        cmocka_unit_test(test_depth_ordering),
        cmocka_unit_test(test_same_image_on_repeated_runs),
        cmocka_unit_test(test_cpu_ray_cast_agrees),
        cmocka_unit_test(test_fit_distance_frames_the_block),
        cmocka_unit_test(test_bad_input_refused),
    };
    int failed = cmocka_run_group_tests(tests, open_context, close_context);
    if (skip_all)
        fprintf(stderr, "SKIPPED: %s\n", open_error);
    return failed ? failed : skip_all ? 77 : 0; /* 77: ctest's SKIP_RETURN_CODE */
}
