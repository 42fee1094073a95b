/* The GL renderer against the CPU colour-map reference, pixel geometry, and bad input. Needs a
 * real GL context (Mesa llvmpipe in CI). Only when no OpenGL 3.3 core context can be created at
 * all do the GL tests report themselves skipped (exit 77); with IM_REQUIRE_GL=1 that fails too,
 * and any other failure of im_render_open (shaders, set-up) always fails. */
#include "support.h"

#include "render/context.h"
#include "render/shaders.h"

#include "indentmap/colormap.h"
#include "indentmap/field.h"
#include "indentmap/render.h"
#include "indentmap/status.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static im_render_context *context;
static char open_error[2048];
static int skip_all; /* no context can be created and IM_REQUIRE_GL is not 1: exit 77 */

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
    } else {
        print_message("renderer: %s, %s; GL_RENDERER %s; GL_VERSION %s\n", im_render_backend_name(context),
                      im_render_display_name(context), im_render_gl_renderer(context), im_render_gl_version(context));
    }
    return 0;
}

static int close_context(void **state)
{
    (void)state;
    im_render_close(context);
    return 0;
}

/* Skips only when no OpenGL 3.3 core context exists at all (and IM_REQUIRE_GL is not 1); a
 * context that opens but fails later (shaders, set-up) is a failure. */
#define REQUIRE_CONTEXT()                                                                                            \
    do {                                                                                                             \
        if (!context && skip_all) {                                                                                  \
            print_message("SKIPPED (no GL context): %s\n", open_error);                                              \
            skip();                                                                                                  \
        }                                                                                                            \
        if (!context)                                                                                                \
            fail_msg("the renderer does not open%s: %s", gl_required() ? " (IM_REQUIRE_GL=1)" : "", open_error);     \
    } while (0)

/* Deterministic pseudo-random numbers in [0, 1). */
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

static void assert_pixel(const im_image *image, int column, int row, const uint8_t expected[3], int tolerance)
{
    const uint8_t *p = pixel(image, column, row);
    for (int k = 0; k < 3; ++k)
        if (abs((int)p[k] - (int)expected[k]) > tolerance)
            fail_msg("pixel (%d, %d) = (%d, %d, %d), expected (%d, %d, %d) within %d", column, row, p[0], p[1], p[2],
                     expected[0], expected[1], expected[2], tolerance);
    assert_int_equal(p[3], 255);
}

/* Every pixel of a contact map against im_colormap_field_image (rows top first), with the tension -f
 * through the tension norm where force < 0, the background where it is 0 and the boundary frame in
 * the line colour. */
static void compare_with_reference(const im_field *force, const im_contact_style *style)
{
    im_image image;
    assert_int_equal(im_render_contact_map(context, force, style, &image), IM_OK);
    int s = style->pixels_per_patch, b = style->boundary_px;
    assert_int_equal(image.width, force->nx * s + 2 * b);
    assert_int_equal(image.height, force->ny * s + 2 * b);
    uint8_t *reference = malloc(im_field_count(force) * 3);
    im_colormap_field_image(&style->colormap, force, reference);
    for (int row = 0; row < image.height; ++row)
        for (int column = 0; column < image.width; ++column) {
            int ix = (column - b) / s, r = (row - b) / s;
            if (column < b || row < b || ix >= force->nx || r >= force->ny) {
                assert_pixel(&image, column, row, style->line, 0);
                continue;
            }
            double f = force->data[(size_t)(force->ny - 1 - r) * force->nx + ix];
            uint8_t expected[3];
            memcpy(expected, reference + ((size_t)r * force->nx + ix) * 3, 3);
            if (f < 0.0) /* under tension (adhesion) */
                im_colormap_rgb(&style->tension, -f, expected);
            else if (!isnan(f) && !(f > 0.0))
                memcpy(expected, style->background, 3);
            assert_pixel(&image, column, row, expected, 1);
        }
    free(reference);
    im_image_release(&image);
}

/* Random forces over and beyond the norm, with zeros, negatives and NaN, on a non-square grid. */
static im_field *random_forces(uint64_t seed)
{
    im_field *f = make_field(37, 23);
    for (size_t i = 0; i < im_field_count(f); ++i) {
        double u = uniform(&seed);
        f->data[i] = u < 0.1 ? 0.0 : u < 0.15 ? -u : u < 0.17 ? NAN : 1.3 * uniform(&seed) + 1e-3;
    }
    return f;
}

static void test_colours_match_cpu_reference(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *force = random_forces(7);
    for (int map = 0; map < IM_COLORMAP_COUNT; ++map) {
        im_contact_style style = im_contact_style_default(force);
        style.colormap = im_colormap_make((im_colormap_id)map, 0.05, 1.1);
        style.colormap.under[0] = 250, style.colormap.under[1] = 10, style.colormap.under[2] = 20;
        style.colormap.over[0] = 5, style.colormap.over[1] = 250, style.colormap.over[2] = 30;
        style.tension = im_contact_tension_norm(0.14); /* the tensions, 0.1 to 0.15: some over it */
        style.tension.lo = 0.11;                       /* and some under */
        style.tension.under[0] = 240, style.tension.under[1] = 200, style.tension.under[2] = 0;
        style.tension.over[0] = 0, style.tension.over[1] = 0, style.tension.over[2] = 0;
        style.pixels_per_patch = 1;
        style.boundary_px = 0;
        compare_with_reference(force, &style);
        style.colormap.logarithmic = 1;
        style.pixels_per_patch = 3;
        style.boundary_px = 2;
        compare_with_reference(force, &style);
    }
    im_field_free(force);
}

/* Values exactly on the norm's bin edges, where float arithmetic would round either way. */
static void test_bin_edges_match_cpu_reference(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *force = make_field(64, 8);
    for (int i = 0; i < 512; ++i)
        force->data[i] = 0.3 + 1.7 * (double)(i / 2) / 256.0 * (i % 2 ? 1.0 + 1e-15 : 1.0);
    im_contact_style style = im_contact_style_default(force);
    style.colormap = im_colormap_make(IM_COLORMAP_MAGMA, 0.3, 2.0);
    style.pixels_per_patch = 1;
    compare_with_reference(force, &style);
    im_field_free(force);
}

/* Patch (ix, iy) must cover image columns b + s ix .. and rows b + s (ny - 1 - iy) .. (y up). */
static void assert_patch_pixels(const im_image *image, const im_field *f, const im_contact_style *style,
                                const uint8_t lit[3])
{
    int s = style->pixels_per_patch, b = style->boundary_px;
    for (int row = b; row < image->height - b; ++row)
        for (int column = b; column < image->width - b; ++column) {
            int ix = (column - b) / s, iy = f->ny - 1 - (row - b) / s;
            int in_contact = f->data[(size_t)iy * f->nx + ix] > 0.0;
            assert_pixel(image, column, row, in_contact ? lit : style->background, 0);
        }
}

static void render_and_check_pattern(im_field *f)
{
    im_contact_style style = im_contact_style_default(f);
    style.colormap = im_colormap_make(IM_COLORMAP_VIRIDIS, 0.0, 1.0);
    style.pixels_per_patch = 4;
    style.boundary_px = 3;
    im_image image;
    assert_int_equal(im_render_contact_map(context, f, &style, &image), IM_OK);
    uint8_t lit[3];
    im_colormap_rgb(&style.colormap, 1.0, lit);
    assert_patch_pixels(&image, f, &style, lit);
    for (int column = 0; column < image.width; ++column) {
        assert_pixel(&image, column, 0, style.line, 0);
        assert_pixel(&image, column, image.height - 1, style.line, 0);
    }
    im_image_release(&image);
}

static void test_single_patch_lands_on_its_pixels(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *f = make_field(8, 6);
    f->data[1 * 8 + 3] = 1.0; /* ix = 3, iy = 1: near the bottom of the picture */
    render_and_check_pattern(f);
    /* Spelled out for this one: rows 3 + 4 (6 - 1 - 1) = 19 .. 22, columns 3 + 12 = 15 .. 18. */
    im_contact_style style = im_contact_style_default(f);
    style.colormap = im_colormap_make(IM_COLORMAP_VIRIDIS, 0.0, 1.0);
    style.pixels_per_patch = 4;
    style.boundary_px = 3;
    im_image image;
    assert_int_equal(im_render_contact_map(context, f, &style, &image), IM_OK);
    uint8_t top_entry[3];
    memcpy(top_entry, im_colormap_table(IM_COLORMAP_VIRIDIS)[255], 3);
    assert_pixel(&image, 15, 19, top_entry, 0);
    assert_pixel(&image, 18, 22, top_entry, 0);
    assert_pixel(&image, 14, 19, style.background, 0);
    assert_pixel(&image, 15, 23, style.background, 0);
    assert_pixel(&image, 15, 18, style.background, 0);
    im_image_release(&image);
    im_field_free(f);
}

static void test_checkerboard_and_disc(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *f = make_field(11, 7);
    for (int iy = 0; iy < f->ny; ++iy)
        for (int ix = 0; ix < f->nx; ++ix)
            f->data[iy * f->nx + ix] = (ix + iy) % 2 ? 1.0 : 0.0;
    render_and_check_pattern(f);
    im_field_free(f);
    f = make_field(20, 20);
    for (int iy = 0; iy < 20; ++iy)
        for (int ix = 0; ix < 20; ++ix)
            f->data[iy * 20 + ix] = hypot(ix + 0.5 - 8.0, iy + 0.5 - 12.0) < 5.5 ? 1.0 : 0.0;
    render_and_check_pattern(f);
    im_field_free(f);
}

/* The circle's coverage, recovered from the pixels, has its centroid at the requested centre and
 * its mean radius at the requested radius (plus w^2 / (12 R) for a band of width w). */
static void test_circle_centre_and_radius(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *f = make_field(40, 36);
    im_contact_style style = im_contact_style_default(f);
    style.pixels_per_patch = 2;
    style.boundary_px = 3; /* the circle is placed relative to the data, not the frame */
    style.circle_radius = 12.4;
    style.circle_x = 19.3;
    style.circle_y = 17.05;
    style.circle_width_px = 2.0;
    im_image image;
    assert_int_equal(im_render_contact_map(context, f, &style, &image), IM_OK);
    double weight = 0.0, sum_x = 0.0, sum_y = 0.0, sum_r = 0.0;
    double cx = style.circle_x * 2, cy = style.circle_y * 2, radius = style.circle_radius * 2;
    for (int row = 3; row < image.height - 3; ++row)
        for (int column = 3; column < image.width - 3; ++column) {
            double coverage = (230.0 - pixel(&image, column, row)[0]) / 230.0;
            double x = column - 3 + 0.5, y = image.height - 3 - row - 0.5; /* from the data's corner */
            weight += coverage;
            sum_x += coverage * x;
            sum_y += coverage * y;
            sum_r += coverage * hypot(x - cx, y - cy);
        }
    assert_close(sum_x / weight, cx, 0.02);
    assert_close(sum_y / weight, cy, 0.02);
    assert_close(sum_r / weight, radius + 4.0 / (12.0 * radius), 0.03);
    assert_close(weight, 2.0 * M_PI * radius * 2.0, 0.01 * 2.0 * M_PI * radius * 2.0);
    im_image_release(&image);
    im_field_free(f);
}

/* An aliased circle: every pixel is either the line colour or exactly the map drawn without the
 * circle, and the line-coloured pixels are those at least half covered: about 2 pi R w of them. */
static void test_aliased_circle_exact_colours(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *force = random_forces(5);
    im_contact_style style = im_contact_style_default(force);
    im_image plain, aliased;
    assert_int_equal(im_render_contact_map(context, force, &style, &plain), IM_OK);
    style.circle_radius = 9.3;
    style.circle_width_px = 2.0;
    style.circle_aliased = 1;
    assert_int_equal(im_render_contact_map(context, force, &style, &aliased), IM_OK);
    long on_line = 0;
    for (int row = 0; row < plain.height; ++row)
        for (int column = 0; column < plain.width; ++column) {
            const uint8_t *a = pixel(&aliased, column, row), *p = pixel(&plain, column, row);
            int is_line = memcmp(a, style.line, 3) == 0;
            if (!is_line && memcmp(a, p, 3) != 0)
                fail_msg("pixel (%d, %d) = (%d, %d, %d): neither the line colour nor the map's", column, row, a[0],
                         a[1], a[2]);
            on_line += is_line && memcmp(p, style.line, 3) != 0;
        }
    double expected = 2.0 * M_PI * style.circle_radius * style.pixels_per_patch * style.circle_width_px;
    assert_close((double)on_line, expected, 0.05 * expected);
    im_image_release(&plain);
    im_image_release(&aliased);
    im_field_free(force);
}

static void test_repeated_runs_identical(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *force = random_forces(11);
    im_contact_style style = im_contact_style_default(force);
    style.circle_radius = 9.7;
    im_image first, second;
    assert_int_equal(im_render_contact_map(context, force, &style, &first), IM_OK);
    assert_int_equal(im_render_contact_map(context, force, &style, &second), IM_OK);
    assert_memory_equal(first.rgba, second.rgba, (size_t)first.width * first.height * 4);
    im_image_release(&second);
    /* A fresh context gives the same picture. */
    im_render_close(context);
    assert_int_equal(im_render_open(IM_RENDER_AUTO, &context), IM_OK);
    assert_int_equal(im_render_contact_map(context, force, &style, &second), IM_OK);
    assert_memory_equal(first.rgba, second.rgba, (size_t)first.width * first.height * 4);
    im_image_release(&first);
    im_image_release(&second);
    im_field_free(force);
}

/* Both backends, where each is available, draw the same pixels. */
static void test_backends_agree(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *force = random_forces(3);
    im_contact_style style = im_contact_style_default(force);
    style.circle_radius = 8.2;
    im_image images[2] = {{0}};
    const im_render_backend backends[2] = {IM_RENDER_EGL, IM_RENDER_OSMESA};
    int rendered = 0;
    for (int i = 0; i < 2; ++i) {
        im_render_context *other = NULL;
        int status = im_render_open(backends[i], &other);
        if (status != IM_OK && !im_render_context_missing(status, im_last_error()))
            fail_msg("backend %d opens a context but fails: %s", (int)backends[i], im_last_error());
        if (status != IM_OK) {
            print_message("backend %d unavailable: %s\n", (int)backends[i], im_last_error());
            continue;
        }
        print_message("%s: %s, %s\n", im_render_backend_name(other), im_render_gl_renderer(other),
                      im_render_gl_version(other));
        assert_int_equal(im_render_contact_map(other, force, &style, &images[rendered]), IM_OK);
        im_render_close(other);
        ++rendered;
    }
    if (rendered < 2) {
        im_image_release(&images[0]);
        im_field_free(force);
        print_message("SKIPPED: only %d backend available\n", rendered);
        skip();
    }
    assert_memory_equal(images[0].rgba, images[1].rgba, (size_t)images[0].width * images[0].height * 4);
    im_image_release(&images[0]);
    im_image_release(&images[1]);
    im_field_free(force);
}

/* The three pictures of one field: a contact map, a height map and a 3-D view. */
typedef struct three_pictures {
    im_render_context *context;
    const im_field *field;
    int status[3];
    im_image image[3];
    char error[512]; /* the drawing thread's last message */
} three_pictures;

static void *draw_three_pictures(void *argument)
{
    three_pictures *p = argument;
    im_contact_style contact = im_contact_style_default(p->field);
    im_height_style height = im_height_style_default(p->field);
    im_view3d_style view = im_view3d_style_default(p->field);
    view.width = view.height = 96;
    p->status[0] = im_render_contact_map(p->context, p->field, &contact, &p->image[0]);
    p->status[1] = im_render_height_map(p->context, p->field, &height, &p->image[1]);
    p->status[2] = im_render_view3d(p->context, p->field, p->field, NULL, &view, &p->image[2]);
    snprintf(p->error, sizeof p->error, "%s", im_last_error());
    return NULL;
}

static void assert_same_pictures(const three_pictures *a, const three_pictures *b, const char *backend)
{
    for (int i = 0; i < 3; ++i) {
        if (b->status[i] != IM_OK)
            fail_msg("%s: picture %d drawn on another thread: %s", backend, i, b->error);
        assert_int_equal(a->image[i].width, b->image[i].width);
        assert_memory_equal(a->image[i].rgba, b->image[i].rgba, (size_t)a->image[i].width * a->image[i].height * 4);
    }
}

/* A context opened on one thread draws on others, one call at a time, the same pixels (EGL refused a
 * context still current on the thread that drew last, so Python could not draw without its GIL). */
static void test_drawing_from_several_threads(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *force = make_field(24, 20);
    for (int iy = 0; iy < force->ny; ++iy)
        for (int ix = 0; ix < force->nx; ++ix)
            force->data[iy * force->nx + ix] = 1.0 + sin(0.4 * ix) * cos(0.3 * iy);
    const im_render_backend backends[2] = {IM_RENDER_EGL, IM_RENDER_OSMESA};
    for (int i = 0; i < 2; ++i) {
        im_render_context *own = NULL;
        if (im_render_open(backends[i], &own) != IM_OK)
            continue; /* test_backends_agree tells an unavailable backend from a broken one */
        three_pictures here = {.context = own, .field = force}, there[2];
        draw_three_pictures(&here);
        for (int k = 0; k < 3; ++k)
            if (here.status[k] != IM_OK)
                fail_msg("%s: picture %d: %s", im_render_backend_name(own), k, here.error);
        for (int t = 0; t < 2; ++t) {
            pthread_t thread;
            there[t] = (three_pictures){.context = own, .field = force};
            assert_int_equal(pthread_create(&thread, NULL, draw_three_pictures, &there[t]), 0);
            assert_int_equal(pthread_join(thread, NULL), 0);
            assert_same_pictures(&here, &there[t], im_render_backend_name(own));
        }
        three_pictures again = {.context = own, .field = force};
        draw_three_pictures(&again); /* and back on the thread that opened it */
        assert_same_pictures(&here, &again, im_render_backend_name(own));
        for (int k = 0; k < 3; ++k) {
            im_image_release(&here.image[k]);
            im_image_release(&again.image[k]);
            for (int t = 0; t < 2; ++t)
                im_image_release(&there[t].image[k]);
        }
        im_render_close(own);
    }
    im_field_free(force);
}

/* Only a missing context may be skipped: a shader or set-up failure after the context exists must
 * not look like one, and the device probe needs device enumeration named, not just pointers. */
static void test_missing_context_is_told_apart(void **state)
{
    (void)state;
    assert_true(im_render_context_missing(IM_EUNSUPPORTED, IM_RENDER_NO_CONTEXT ": egl: no EGL_EXT_platform_base"));
    assert_false(im_render_context_missing(IM_EUNSUPPORTED, "shader contact.frag does not compile: 0:1 error"));
    assert_false(im_render_context_missing(IM_EUNSUPPORTED, "GL setup failed: error 0x502"));
    assert_false(im_render_context_missing(IM_EINVAL, IM_RENDER_NO_CONTEXT ": but the wrong status"));
    assert_false(im_render_context_missing(IM_OK, ""));
    assert_true(
        egl_can_enumerate_devices("EGL_EXT_platform_base EGL_EXT_device_enumeration EGL_EXT_platform_device"));
    assert_true(egl_can_enumerate_devices("EGL_EXT_device_base EGL_EXT_platform_device"));
    assert_false(egl_can_enumerate_devices("EGL_EXT_platform_base EGL_EXT_platform_device"));
    assert_false(egl_can_enumerate_devices("EGL_EXT_device_enumeration_extra EGL_EXT_platform_device"));
    assert_false(egl_can_enumerate_devices("EGL_EXT_device_enumeration"));
    assert_false(egl_can_enumerate_devices(NULL));
}

/* A shader that does not compile is refused with its name, and the compiler's message gives the
 * line in the shader's own file although the #version line and shaders/patch_colour.glsl (19 lines)
 * are compiled before it. Mesa writes "0:3(1): error", other drivers "0(3) : error". */
static void test_shader_errors_name_the_file_and_its_line(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    static const char broken[] = "out vec4 colour;\n"
                                 "void main() { colour = vec4(patch_colour(0u, vec3(0.0)), 1.0); }\n"
                                 "not a declaration;\n";
    assert_int_equal(render_make_current(context), IM_OK); /* another test may have made its own current */
    GLuint program = 0;
    int status = render_link_program(&context->gl, im_shader_fullscreen_vert, "fullscreen.vert",
                                     im_shader_patch_colour, broken, "broken.frag", &program);
    assert_int_equal(status, IM_EUNSUPPORTED);
    const char *message = im_last_error();
    if (!strstr(message, "shader broken.frag does not compile: ") ||
        !(strstr(message, "0:3(") || strstr(message, "0(3)")))
        fail_msg("expected broken.frag and its line 3 in: %s", message);
}

static void test_backend_choice(void **state)
{
    (void)state;
    im_render_backend backend;
    assert_int_equal(im_render_backend_from_name("osmesa", &backend), IM_OK);
    assert_int_equal(backend, IM_RENDER_OSMESA);
    assert_int_equal(im_render_backend_from_name("vulkan", &backend), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "auto, egl or osmesa"));
    /* the library reads no environment: the program turns IM_RENDER_BACKEND into a backend */
    setenv("IM_RENDER_BACKEND", "directx", 1);
    im_render_context *other = NULL;
    int status = im_render_open(IM_RENDER_AUTO, &other);
    assert_int_not_equal(status, IM_EINVAL);
    assert_true(status == IM_OK || status == IM_EUNSUPPORTED);
    im_render_close(other);
    unsetenv("IM_RENDER_BACKEND");
}

/* No patch in contact: a valid picture of background, frame and circle. NaN: the bad colour. */
static void test_empty_zero_and_nan_fields(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *f = make_field(5, 4);
    f->data[2] = NAN;
    im_contact_style style = im_contact_style_default(f);
    assert_close(style.colormap.hi, 1.0, 0.0); /* nothing in contact: [0, 1] */
    style.pixels_per_patch = 1;
    style.boundary_px = 1;
    im_image image;
    assert_int_equal(im_render_contact_map(context, f, &style, &image), IM_OK);
    assert_pixel(&image, 1 + 2, 1 + 3, style.colormap.bad, 0); /* iy = 0 is the last data row */
    assert_pixel(&image, 1 + 1, 1 + 3, style.background, 0);
    assert_pixel(&image, 1 + 2, 1 + 2, style.background, 0);
    im_image_release(&image);
    im_field empty = {.nx = 0, .ny = 0, .delta = 1.0};
    assert_int_equal(im_render_contact_map(context, &empty, &style, &image), IM_EINVAL);
    assert_null(image.rgba);
    im_field_free(f);
}

static void test_bad_styles_refused(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *f = make_field(1024, 4);
    f->data[0] = 1.0;
    im_contact_style style = im_contact_style_default(f);
    im_image image;
    style.pixels_per_patch = 0; /* a zero-size image */
    assert_int_equal(im_render_contact_map(context, f, &style, &image), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "pixels_per_patch"));
    style.pixels_per_patch = 64; /* 65540 pixels wide: beyond every limit */
    assert_int_equal(im_render_contact_map(context, f, &style, &image), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "exceeds"));
    assert_null(image.rgba);
    style = im_contact_style_default(f);
    style.colormap.hi = style.colormap.lo;
    assert_int_equal(im_render_contact_map(context, f, &style, &image), IM_EINVAL);
    style = im_contact_style_default(f);
    style.colormap.logarithmic = 1; /* lo = 0 */
    assert_int_equal(im_render_contact_map(context, f, &style, &image), IM_EINVAL);
    style = im_contact_style_default(f);
    style.circle_radius = NAN;
    assert_int_equal(im_render_contact_map(context, f, &style, &image), IM_EINVAL);
    style = im_contact_style_default(f);
    style.tension.hi = NAN;
    assert_int_equal(im_render_contact_map(context, f, &style, &image), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "contact map: tension"));
    im_field_free(f);
}

/* The relative luminance of an 8-bit sRGB colour (the sRGB transfer curve and weights). */
static double luminance(const uint8_t rgb[3])
{
    const double weights[3] = {0.2126, 0.7152, 0.0722};
    double y = 0.0;
    for (int k = 0; k < 3; ++k) {
        double c = rgb[k] / 255.0;
        y += weights[k] * (c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4));
    }
    return y;
}

/* Patches under tension of several magnitudes in one row, with a compressed and a free patch: with the
 * default style each takes its tension's entry of the blue ramp (the largest the last), darker as the
 * tension grows, bluer than it is red or green, and none is the no-contact grey. The starting code drew
 * them all in one flat colour. */
static void test_tension_follows_the_ramp(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    const double forces[] = {0.0, -0.02, -0.1, -0.25, -0.45, -0.7, -1.0, 0.5};
    const int count = (int)(sizeof forces / sizeof *forces);
    im_field *f = make_field(count, 1);
    memcpy(f->data, forces, sizeof forces);
    im_contact_style style = im_contact_style_default(f);
    assert_true(style.tension.map == IM_COLORMAP_TENSION && style.tension.lo == 0.0 && style.tension.hi == 1.0);
    style.boundary_px = 0;
    im_image image;
    assert_int_equal(im_render_contact_map(context, f, &style, &image), IM_OK);
    const uint8_t(*ramp)[3] = im_colormap_table(IM_COLORMAP_TENSION);
    double previous = INFINITY;
    for (int i = 1; i < count - 1; ++i) {
        const uint8_t *p = pixel(&image, 2 * i, 0);
        uint8_t expected[3];
        im_colormap_rgb(&style.tension, -forces[i], expected);
        assert_pixel(&image, 2 * i, 0, expected, 0);
        double y = luminance(p);
        if (!(y < previous) || !(p[2] > p[0] && p[2] > p[1]) || memcmp(p, style.background, 3) == 0)
            fail_msg("tension %g: (%d, %d, %d), luminance %.4f after %.4f", -forces[i], p[0], p[1], p[2], y,
                     previous);
        previous = y;
    }
    assert_pixel(&image, 2 * (count - 2), 0, ramp[255], 0);
    assert_pixel(&image, 0, 0, style.background, 0);
    im_image_release(&image);
    im_field_free(f);
}

/* A plane h = g x lit from azimuth az at 45 degrees: Lambert's factor relative to flat ground is
 * (1 -/+ g) / sqrt(1 + g^2) for light from +x / -x; each patch's grey level scales by it. */
static void check_plane_shading(double light_azimuth, double expected_factor)
{
    const double g = 0.5;
    im_field *h = make_field(12, 5);
    for (int iy = 0; iy < 5; ++iy)
        for (int ix = 0; ix < 12; ++ix)
            h->data[iy * 12 + ix] = g * ix;
    im_height_style style = im_height_style_default(h);
    style.colormap = im_colormap_make(IM_COLORMAP_GREY, -3.0, 10.0);
    style.shading = 1.0;
    style.exaggeration = 1.0;
    style.light_azimuth = light_azimuth;
    style.light_altitude = 45.0;
    style.pixels_per_patch = 2;
    style.boundary_px = 0;
    im_image image;
    assert_int_equal(im_render_height_map(context, h, &style, &image), IM_OK);
    for (int ix = 0; ix < 12; ++ix) {
        uint8_t base[3], expected[3];
        im_colormap_rgb(&style.colormap, h->data[ix], base);
        for (int k = 0; k < 3; ++k) {
            double v = base[k] * expected_factor;
            expected[k] = (uint8_t)(v > 255.0 ? 255 : (int)lround(v));
        }
        for (int row = 0; row < image.height; ++row)
            assert_pixel(&image, 2 * ix + 1, row, expected, 1);
    }
    im_image_release(&image);
    im_field_free(h);
}

static void test_height_shading_of_a_plane(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    check_plane_shading(270.0, 1.5 / sqrt(1.25)); /* light from -x: the slope faces it */
    check_plane_shading(90.0, 0.5 / sqrt(1.25));
    check_plane_shading(0.0, 1.0 / sqrt(1.25)); /* light from +y: only the tilt counts */
}

static void test_height_flat_matches_reference_and_nan(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *h = make_field(9, 7);
    for (size_t i = 0; i < im_field_count(h); ++i)
        h->data[i] = 0.25;
    h->data[3 * 9 + 4] = NAN;
    im_height_style style = im_height_style_default(h);
    assert_close(style.colormap.lo, -0.75, 1e-15); /* flat: [h - 1, h + 1] */
    style.pixels_per_patch = 1;
    style.boundary_px = 0;
    im_image image;
    assert_int_equal(im_render_height_map(context, h, &style, &image), IM_OK);
    uint8_t expected[3];
    im_colormap_rgb(&style.colormap, 0.25, expected);
    for (int row = 0; row < 7; ++row)
        for (int column = 0; column < 9; ++column)
            assert_pixel(&image, column, row, row == 3 && column == 4 ? style.colormap.bad : expected, 1);
    im_image_release(&image);
    im_field_free(h);
}

/* A 3 x 3 block of contact patches is outlined inside its own edge, nowhere else. */
static void test_contact_outline(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *h = make_field(8, 8), *contact = make_field(8, 8);
    for (int iy = 2; iy <= 4; ++iy)
        for (int ix = 2; ix <= 4; ++ix)
            contact->data[iy * 8 + ix] = 1.0;
    im_height_style style = im_height_style_default(h);
    style.contact = contact;
    style.pixels_per_patch = 4;
    style.boundary_px = 0;
    style.outline_px = 1;
    im_image image;
    assert_int_equal(im_render_height_map(context, h, &style, &image), IM_OK);
    uint8_t plain[3];
    im_colormap_rgb(&style.colormap, 0.0, plain);
    for (int row = 0; row < 32; ++row)
        for (int column = 0; column < 32; ++column) {
            int y = 31 - row; /* pixels from the bottom */
            int inside = column >= 8 && column < 20 && y >= 8 && y < 20;
            int edge = inside && (column == 8 || column == 19 || y == 8 || y == 19);
            assert_pixel(&image, column, row, edge ? style.outline : plain, 1);
        }
    im_image_release(&image);
    contact->nx = 7; /* a different grid */
    assert_int_equal(im_render_height_map(context, h, &style, &image), IM_EINVAL);
    contact->nx = 8;
    im_field_free(h);
    im_field_free(contact);
}

/* Width in pixels of the outline along the left edge of a contact block, counted along the
 * block's middle row from its left edge. */
static int outline_width_drawn(const im_image *image, const uint8_t outline[3], int left_px, int row)
{
    int width = 0;
    while (memcmp(pixel(image, left_px + width, row), outline, 3) == 0)
        ++width;
    return width;
}

/* The default outline grows with the pixels per patch: at least 2 px from 2 pixels per patch. */
static void test_contact_outline_default_width(void **state)
{
    (void)state;
    REQUIRE_CONTEXT();
    im_field *h = make_field(12, 12), *contact = make_field(12, 12);
    for (int iy = 3; iy <= 8; ++iy)
        for (int ix = 3; ix <= 8; ++ix)
            contact->data[iy * 12 + ix] = 1.0;
    const int scales[] = {1, 2, 4, 8, 16}, widths[] = {1, 2, 2, 3, 5};
    for (int k = 0; k < 5; ++k) {
        im_height_style style = im_height_style_default(h);
        style.contact = contact;
        style.pixels_per_patch = scales[k];
        style.boundary_px = 0;
        assert_int_equal(im_height_outline_width(&style), widths[k]);
        im_image image;
        assert_int_equal(im_render_height_map(context, h, &style, &image), IM_OK);
        assert_int_equal(outline_width_drawn(&image, style.outline, 3 * scales[k], 6 * scales[k]), widths[k]);
        im_image_release(&image);
    }
    im_field_free(h);
    im_field_free(contact);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_missing_context_is_told_apart),
        cmocka_unit_test(test_backend_choice),
        cmocka_unit_test(test_shader_errors_name_the_file_and_its_line),
        cmocka_unit_test(test_colours_match_cpu_reference),
        cmocka_unit_test(test_bin_edges_match_cpu_reference),
        cmocka_unit_test(test_single_patch_lands_on_its_pixels),
        cmocka_unit_test(test_checkerboard_and_disc),
        cmocka_unit_test(test_circle_centre_and_radius),
        cmocka_unit_test(test_aliased_circle_exact_colours),
        cmocka_unit_test(test_repeated_runs_identical),
        cmocka_unit_test(test_backends_agree),
        cmocka_unit_test(test_drawing_from_several_threads),
        cmocka_unit_test(test_empty_zero_and_nan_fields),
        cmocka_unit_test(test_bad_styles_refused),
        cmocka_unit_test(test_tension_follows_the_ramp),
        cmocka_unit_test(test_height_shading_of_a_plane),
        cmocka_unit_test(test_height_flat_matches_reference_and_nan),
        cmocka_unit_test(test_contact_outline),
        cmocka_unit_test(test_contact_outline_default_width),
    };
    int failed = cmocka_run_group_tests(tests, open_context, close_context);
    if (skip_all)
        fprintf(stderr, "SKIPPED: %s\n", open_error);
    return failed ? failed : skip_all ? 77 : 0; /* 77: ctest's SKIP_RETURN_CODE */
}
