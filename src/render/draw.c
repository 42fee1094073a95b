/* Drawing fields with the GL context: shader programs, textures, framebuffer, read-back. */
#include "render/context.h"
#include "core/args.h"
#include "render/shaders.h"

#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_PIXELS_PER_PATCH = 64, MAX_BOUNDARY_PX = 64, MAX_IMAGE_SIDE = 32768 };

/* Every shader is compiled as GLSL 3.30 core: the #version line is stated here, once. A "#line 1"
 * before the shader's own source makes the compiler's messages give that file's line numbers. */
static const char GLSL_VERSION[] = "#version 330 core\n";

static int compile_shader(const im_gl *gl, GLenum stage, const char *prelude, const char *source, const char *name,
                          GLuint *out)
{
    const char *parts[] = {GLSL_VERSION, prelude ? prelude : "", "#line 1\n", source};
    GLuint shader = gl->CreateShader(stage);
    gl->ShaderSource(shader, 4, parts, NULL);
    gl->CompileShader(shader);
    GLint ok = GL_FALSE;
    gl->GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        gl->GetShaderInfoLog(shader, sizeof log, NULL, log);
        gl->DeleteShader(shader);
        return im_fail(IM_EUNSUPPORTED, "shader %s does not compile: %s", name, log);
    }
    *out = shader;
    return IM_OK;
}

int render_link_program(const im_gl *gl, const char *vertex_source, const char *vertex_name,
                        const char *fragment_prelude, const char *fragment_source, const char *name, GLuint *out)
{
    GLuint vertex, fragment;
    int status = compile_shader(gl, GL_VERTEX_SHADER, NULL, vertex_source, vertex_name, &vertex);
    if (status != IM_OK)
        return status;
    status = compile_shader(gl, GL_FRAGMENT_SHADER, fragment_prelude, fragment_source, name, &fragment);
    if (status != IM_OK) {
        gl->DeleteShader(vertex);
        return status;
    }
    GLuint program = gl->CreateProgram();
    gl->AttachShader(program, vertex);
    gl->AttachShader(program, fragment);
    gl->LinkProgram(program);
    gl->DeleteShader(vertex);
    gl->DeleteShader(fragment);
    GLint ok = GL_FALSE;
    gl->GetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        gl->GetProgramInfoLog(program, sizeof log, NULL, log);
        gl->DeleteProgram(program);
        return im_fail(IM_EUNSUPPORTED, "shader program %s does not link: %s", name, log);
    }
    *out = program;
    return IM_OK;
}

int render_setup(im_render_context *c)
{
    const im_gl *gl = &c->gl;
    gl->GetIntegerv(GL_MAX_TEXTURE_SIZE, &c->max_texture_size);
    gl->GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &c->max_renderbuffer_size);
    gl->GetIntegerv(GL_MAX_VIEWPORT_DIMS, c->max_viewport);
    gl->GetIntegerv(GL_MAX_SAMPLES, &c->max_samples);
    int status = render_link_program(gl, im_shader_fullscreen_vert, "fullscreen.vert", im_shader_patch_colour,
                                     im_shader_contact_frag, "contact.frag", &c->contact_program);
    if (status == IM_OK)
        status = render_link_program(gl, im_shader_fullscreen_vert, "fullscreen.vert", im_shader_patch_colour,
                                     im_shader_height_frag, "height.frag", &c->height_program);
    if (status == IM_OK)
        status = render_view3d_setup(c);
    if (status != IM_OK)
        return status;
    gl->GenVertexArrays(1, &c->vertex_array);
    gl->BindVertexArray(c->vertex_array);
    GLenum error = gl->GetError();
    return error == GL_NO_ERROR ? IM_OK : im_fail(IM_EUNSUPPORTED, "GL setup failed: error 0x%x", error);
}

void render_teardown(im_render_context *c)
{
    if (!c->gl.DeleteProgram)
        return;
    c->gl.DeleteProgram(c->contact_program);
    c->gl.DeleteProgram(c->height_program);
    c->gl.DeleteProgram(c->surface_program);
    c->gl.DeleteProgram(c->punch_program);
    c->gl.DeleteProgram(c->wall_program);
    c->gl.DeleteVertexArrays(1, &c->vertex_array);
}

void im_image_release(im_image *image)
{
    if (!image)
        return;
    free(image->rgba);
    memset(image, 0, sizeof *image);
}

/* ---- validation ---- */

long render_image_limit(const im_render_context *c)
{
    long limit = c->max_renderbuffer_size;
    limit = limit < c->max_viewport[0] ? limit : c->max_viewport[0];
    limit = limit < c->max_viewport[1] ? limit : c->max_viewport[1];
    return limit < MAX_IMAGE_SIDE ? limit : MAX_IMAGE_SIDE;
}

static int check_layout(const im_render_context *c, const im_field *field, int scale, int border, const char *what)
{
    if (!field || field->nx < 1 || field->ny < 1)
        return im_fail(IM_EINVAL, "%s: empty field: expected at least 1 x 1 patches", what);
    if (scale < 1 || scale > MAX_PIXELS_PER_PATCH)
        return im_fail(IM_EINVAL, "%s: pixels_per_patch = %d: expected 1..%d", what, scale, MAX_PIXELS_PER_PATCH);
    if (border < 0 || border > MAX_BOUNDARY_PX)
        return im_fail(IM_EINVAL, "%s: boundary_px = %d: expected 0..%d", what, border, MAX_BOUNDARY_PX);
    if (field->nx > c->max_texture_size || field->ny > c->max_texture_size)
        return im_fail(IM_EINVAL, "%s: grid %d x %d exceeds GL_MAX_TEXTURE_SIZE %d of %s", what, field->nx, field->ny,
                       c->max_texture_size, c->renderer);
    long limit = render_image_limit(c);
    long width = (long)field->nx * scale + 2L * border, height = (long)field->ny * scale + 2L * border;
    if (width > limit || height > limit)
        return im_fail(IM_EINVAL,
                       "%s: image %ld x %ld pixels exceeds the limit %ld (GL limits of %s); "
                       "use fewer pixels per patch",
                       what, width, height, limit, c->renderer);
    return im_memory_check(4.0 * (double)width * (double)height + 6.0 * (double)im_field_count(field), what);
}

/* ---- GL objects ---- */

GLuint render_texture(const im_gl *gl, int unit, GLint internal, int width, int height, GLenum format, GLenum type,
                      const void *data)
{
    GLuint texture;
    gl->GenTextures(1, &texture);
    gl->ActiveTexture(GL_TEXTURE0 + unit);
    gl->BindTexture(GL_TEXTURE_2D, texture);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl->TexImage2D(GL_TEXTURE_2D, 0, internal, width, height, 0, format, type, data);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

GLuint render_table_texture(const im_gl *gl, int unit, im_colormap_id map)
{
    const uint8_t(*table)[3] = im_colormap_table(map);
    uint8_t rgba[256][4];
    for (int i = 0; i < 256; ++i) {
        memcpy(rgba[i], table[i], 3);
        rgba[i][3] = 255;
    }
    return render_texture(gl, unit, GL_RGBA8, 256, 1, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
}

void render_set_colour(const im_gl *gl, GLuint program, const char *name, const uint8_t rgb[3])
{
    gl->Uniform3f(gl->GetUniformLocation(program, name), rgb[0] / 255.0f, rgb[1] / 255.0f, rgb[2] / 255.0f);
}

void render_set_int(const im_gl *gl, GLuint program, const char *name, int value)
{
    gl->Uniform1i(gl->GetUniformLocation(program, name), value);
}

static void set_common(const im_gl *gl, GLuint program, const im_colormap *colormap, const im_field *field, int scale,
                       int border, const uint8_t line[3])
{
    render_set_colour(gl, program, "under_colour", colormap->under);
    render_set_colour(gl, program, "over_colour", colormap->over);
    render_set_colour(gl, program, "bad_colour", colormap->bad);
    render_set_colour(gl, program, "line_colour", line);
    gl->Uniform2i(gl->GetUniformLocation(program, "grid"), field->nx, field->ny);
    render_set_int(gl, program, "scale", scale);
    render_set_int(gl, program, "border", border);
}

/* Draws the bound program into a width x height framebuffer and reads it back, top row first. */
static int draw_and_read(const im_render_context *c, int width, int height, uint8_t *rgba)
{
    const im_gl *gl = &c->gl;
    GLuint framebuffer, colour;
    gl->GenFramebuffers(1, &framebuffer);
    gl->BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    gl->GenRenderbuffers(1, &colour);
    gl->BindRenderbuffer(GL_RENDERBUFFER, colour);
    gl->RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
    int status = IM_OK;
    GLenum complete = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (complete != GL_FRAMEBUFFER_COMPLETE) {
        status = im_fail(IM_EUNSUPPORTED, "framebuffer %d x %d incomplete (0x%x)", width, height, complete);
    } else {
        gl->Viewport(0, 0, width, height);
        gl->DrawArrays(GL_TRIANGLES, 0, 3);
        gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl->ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
        GLenum error = gl->GetError();
        if (error != GL_NO_ERROR)
            status = im_fail(IM_EUNSUPPORTED, "drawing %d x %d pixels: GL error 0x%x", width, height, error);
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->DeleteRenderbuffers(1, &colour);
    gl->DeleteFramebuffers(1, &framebuffer);
    return status == IM_OK ? render_flip_rows(rgba, width, height) : status;
}

int render_flip_rows(uint8_t *rgba, int width, int height)
{
    size_t stride = (size_t)width * 4;
    uint8_t *row = malloc(stride);
    if (!row)
        return im_fail(IM_ENOMEM, "image read-back: out of memory");
    for (int top = 0, bottom = height - 1; top < bottom; ++top, --bottom) {
        memcpy(row, rgba + top * stride, stride);
        memcpy(rgba + top * stride, rgba + bottom * stride, stride);
        memcpy(rgba + bottom * stride, row, stride);
    }
    free(row);
    return IM_OK;
}

static int allocate_image(const im_field *field, int scale, int border, im_image *image)
{
    memset(image, 0, sizeof *image);
    image->width = field->nx * scale + 2 * border;
    image->height = field->ny * scale + 2 * border;
    image->rgba = malloc((size_t)image->width * image->height * 4);
    if (!image->rgba)
        return im_fail(IM_ENOMEM, "image %d x %d: out of memory", image->width, image->height);
    image->data_x = image->data_y = border;
    image->pixels_per_patch = scale;
    image->nx = field->nx;
    image->ny = field->ny;
    image->delta = field->delta;
    memcpy(image->unit, field->unit, sizeof image->unit);
    return IM_OK;
}

int render_patch_code(const im_colormap *colormap, double value)
{
    int index = im_colormap_index(colormap, value);
    return index == -2 ? IM_CODE_BAD : index == -1 ? IM_CODE_UNDER : index == 256 ? IM_CODE_OVER : index;
}

int render_force_code(const im_colormap *compression, const im_colormap *tension, double force)
{
    return isnan(force)  ? IM_CODE_BAD
           : force > 0.0 ? render_patch_code(compression, force)
           : force < 0.0 ? IM_CODE_TENSION + render_patch_code(tension, -force)
                         : IM_CODE_BACKGROUND;
}

GLuint render_tension_texture(const im_gl *gl, GLuint program, int unit, const im_colormap *tension)
{
    render_set_int(gl, program, "tension_table", unit);
    render_set_colour(gl, program, "tension_under", tension->under);
    render_set_colour(gl, program, "tension_over", tension->over);
    return render_table_texture(gl, unit, tension->map);
}

static int finish(const im_render_context *c, int status, GLuint *textures, int texture_count, uint16_t *codes,
                  im_image *image)
{
    c->gl.DeleteTextures(texture_count, textures);
    free(codes);
    if (status != IM_OK)
        im_image_release(image);
    return status;
}

/* ---- contact map ---- */

/* Both through the tension range (colormap.h), which the frames and panels of several fields share. */
im_colormap im_contact_tension_norm(double largest)
{
    im_colormap_range tensions = im_colormap_range_empty(IM_COLORMAP_TENSIONS);
    if (isfinite(largest))
        tensions.hi = largest;
    return im_colormap_range_norm(&tensions, IM_COLORMAP_TENSION, NAN, NAN, 0);
}

double im_contact_largest_tension(const im_field *force)
{
    im_colormap_range tensions = im_colormap_range_empty(IM_COLORMAP_TENSIONS);
    if (arg_view(__func__, "force", force) == IM_OK)
        im_colormap_range_add(&tensions, force);
    return fmax(tensions.hi, 0.0);
}

im_contact_style im_contact_style_default(const im_field *force)
{
    im_colormap_range forces = im_colormap_range_empty(IM_COLORMAP_FORCES);
    int valid = arg_view(__func__, "force", force) == IM_OK;
    size_t count = valid ? im_field_count(force) : 0; /* invalid: empty */
    if (valid)
        im_colormap_range_add(&forces, force);
    im_contact_style style = {.colormap = im_colormap_range_norm(&forces, IM_COLORMAP_VIRIDIS, NAN, NAN, 0),
                              .tension = im_contact_tension_norm(valid ? im_contact_largest_tension(force) : 0.0),
                              .pixels_per_patch = 2,
                              .boundary_px = 2,
                              .background = {230, 230, 230},
                              .line = {0, 0, 0},
                              .circle_radius = 0.0,
                              .circle_x = count ? 0.5 * force->nx : 0.0,
                              .circle_y = count ? 0.5 * force->ny : 0.0,
                              .circle_width_px = 2.0};
    return style;
}

/* IM_EINVAL naming the first patch (x, y) of force holding +-Inf: a force is finite (NaN marks no data), and
 * an infinite one drawn in the over colour would pass for a large one (S10). */
static int check_finite_force(const im_field *force)
{
    for (int iy = 0; iy < force->ny; ++iy)
        for (int ix = 0; ix < force->nx; ++ix) {
            const double f = force->data[(size_t)iy * force->nx + ix];
            if (isinf(f))
                return im_fail(IM_EINVAL,
                               "contact map: force %g at patch (%d, %d): expected a finite force (NaN marks no data)",
                               f, ix, iy);
        }
    return IM_OK;
}

static int check_contact_style(const im_contact_style *s)
{
    int status = im_colormap_check(&s->colormap);
    if (status != IM_OK)
        return im_fail_context(status, "contact map");
    status = im_colormap_check(&s->tension);
    if (status != IM_OK)
        return im_fail_context(status, "contact map: tension");
    if (!isfinite(s->circle_radius) || !isfinite(s->circle_x) || !isfinite(s->circle_y))
        return im_fail(IM_EINVAL, "contact map: circle (%g, %g) radius %g: expected finite values", s->circle_x,
                       s->circle_y, s->circle_radius);
    if (!(s->circle_width_px > 0.0 && s->circle_width_px <= 1000.0))
        return im_fail(IM_EINVAL, "contact map: circle_width_px = %g: expected (0, 1000]", s->circle_width_px);
    return IM_OK;
}

/* With the context current and the inputs checked. */
static int draw_contact_map(const im_render_context *c, const im_field *force, const im_contact_style *s,
                            im_image *image)
{
    size_t count = im_field_count(force);
    uint16_t *codes = malloc(count * sizeof *codes);
    if (!codes || allocate_image(force, s->pixels_per_patch, s->boundary_px, image) != IM_OK) {
        free(codes);
        im_image_release(image);
        return im_fail(IM_ENOMEM, "contact map %d x %d: out of memory", force->nx, force->ny);
    }
    for (size_t i = 0; i < count; ++i)
        codes[i] = (uint16_t)render_force_code(&s->colormap, &s->tension, force->data[i]);
    const im_gl *gl = &c->gl;
    GLuint program = c->contact_program, textures[3];
    gl->UseProgram(program);
    textures[0] = render_texture(gl, 0, GL_R16UI, force->nx, force->ny, GL_RED_INTEGER, GL_UNSIGNED_SHORT, codes);
    textures[1] = render_table_texture(gl, 1, s->colormap.map);
    textures[2] = render_tension_texture(gl, program, 2, &s->tension);
    render_set_int(gl, program, "codes", 0);
    render_set_int(gl, program, "table", 1);
    set_common(gl, program, &s->colormap, force, s->pixels_per_patch, s->boundary_px, s->line);
    render_set_colour(gl, program, "background", s->background);
    double scale = s->pixels_per_patch;
    gl->Uniform3f(gl->GetUniformLocation(program, "circle"), (float)(s->circle_x * scale),
                  (float)(s->circle_y * scale), (float)(s->circle_radius * scale));
    gl->Uniform1f(gl->GetUniformLocation(program, "circle_width"), (float)s->circle_width_px);
    render_set_int(gl, program, "circle_aliased", s->circle_aliased != 0);
    int status = draw_and_read(c, image->width, image->height, image->rgba);
    return finish(c, status, textures, 3, codes, image);
}

int im_render_contact_map(im_render_context *c, const im_field *force, const im_contact_style *s, im_image *image)
{
    ARG_REQUIRE(c, "context");
    ARG_VIEW(force, "force");
    ARG_REQUIRE(s, "style");
    ARG_REQUIRE(image, "image");
    memset(image, 0, sizeof *image);
    int status = check_contact_style(s);
    if (status == IM_OK)
        status = check_finite_force(force);
    if (status == IM_OK)
        status = check_layout(c, force, s->pixels_per_patch, s->boundary_px, "contact map");
    if (status == IM_OK)
        status = render_make_current(c);
    if (status != IM_OK)
        return status;
    status = draw_contact_map(c, force, s, image);
    render_release_current(c);
    return status;
}

/* ---- height field ---- */

/* rms of forward-difference slopes over finite pairs, heights / delta; 0 if none. */
static double slope_rms(const im_field *h)
{
    double sum = 0.0;
    size_t pairs = 0;
    for (int iy = 0; iy < h->ny; ++iy)
        for (int ix = 0; ix < h->nx; ++ix) {
            double own = h->data[(size_t)iy * h->nx + ix];
            double right = ix + 1 < h->nx ? h->data[(size_t)iy * h->nx + ix + 1] : NAN;
            double up = iy + 1 < h->ny ? h->data[(size_t)(iy + 1) * h->nx + ix] : NAN;
            if (isfinite(own) && isfinite(right))
                sum += (right - own) * (right - own), ++pairs;
            if (isfinite(own) && isfinite(up))
                sum += (up - own) * (up - own), ++pairs;
        }
    /* Each pair gives one component; |grad h|^2 has two. */
    return pairs ? sqrt(2.0 * sum / (double)pairs) / h->delta : 0.0;
}

im_height_style im_height_style_default(const im_field *height)
{
    im_colormap_range heights = im_colormap_range_empty(IM_COLORMAP_HEIGHTS);
    size_t count = arg_view(__func__, "height", height) == IM_OK ? im_field_count(height) : 0; /* invalid: empty */
    if (count)
        im_colormap_range_add(&heights, height);
    double slope = count ? slope_rms(height) : 0.0;
    im_height_style style = {.colormap = im_colormap_range_norm(&heights, IM_COLORMAP_VIRIDIS, NAN, NAN, 0),
                             .pixels_per_patch = 2,
                             .boundary_px = 2,
                             .line = {0, 0, 0},
                             .shading = 0.6,
                             .light_azimuth = 315.0,
                             .light_altitude = 45.0,
                             .exaggeration = slope > 0.0 ? 0.5 / slope : 1.0,
                             .contact = NULL,
                             .outline = {255, 255, 255},
                             .outline_px = 0};
    return style;
}

int im_height_outline_width(const im_height_style *style)
{
    ARG_REQUIRE_OR(style, "style", 0);
    if (style->outline_px > 0)
        return style->outline_px;
    int scale = style->pixels_per_patch;
    if (scale < 2)
        return 1;
    int third = (scale + 1) / 3; /* round(scale / 3) */
    return third > 2 ? third : 2;
}

/* The renderer draws heights / delta in float32: a height beyond its range (or one whose slopes
 * overflow) is named, not reported as the exaggeration it would make 0 (issue 32). */
static int check_height_range(const im_field *height)
{
    for (size_t i = 0; height && i < im_field_count(height); ++i) {
        const double h = height->data[i] / height->delta;
        if (isfinite(h) && fabs(h) > 1e18)
            return im_fail(IM_EINVAL,
                           "height map: height %g (%g delta) at patch (%zu, %zu): expected |h| <= "
                           "1e18 delta (drawn in float32, with slopes squared)",
                           height->data[i], h, i % (size_t)height->nx, i / (size_t)height->nx);
    }
    return IM_OK;
}

static int check_height_style(const im_height_style *s, const im_field *height)
{
    int status = check_height_range(height);
    if (status != IM_OK)
        return status;
    status = im_colormap_check(&s->colormap);
    if (status != IM_OK)
        return im_fail_context(status, "height map");
    if (!(s->shading >= 0.0 && s->shading <= 1.0))
        return im_fail(IM_EINVAL, "height map: shading = %g: expected [0, 1]", s->shading);
    if (!(s->light_altitude > 0.0 && s->light_altitude <= 90.0) || !isfinite(s->light_azimuth))
        return im_fail(IM_EINVAL,
                       "height map: light altitude %g, azimuth %g: expected altitude in "
                       "(0, 90] degrees and a finite azimuth",
                       s->light_altitude, s->light_azimuth);
    if (!(s->exaggeration > 0.0 && isfinite(s->exaggeration)))
        return im_fail(IM_EINVAL, "height map: exaggeration = %g: expected > 0", s->exaggeration);
    if (s->outline_px < 0 || s->outline_px > MAX_PIXELS_PER_PATCH)
        return im_fail(IM_EINVAL, "height map: outline_px = %d: expected 0 (automatic) .. %d", s->outline_px,
                       MAX_PIXELS_PER_PATCH);
    if (s->contact && height && (s->contact->nx != height->nx || s->contact->ny != height->ny))
        return im_fail(IM_EINVAL, "height map: contact field %d x %d: expected the grid of the heights, %d x %d",
                       s->contact->nx, s->contact->ny, height->nx, height->ny);
    return IM_OK;
}

/* Heights / delta as float32, codes and contact flags for the shader. */
static void height_inputs(const im_field *h, const im_height_style *s, uint16_t *codes, float *scaled,
                          uint8_t *contact)
{
    for (size_t i = 0; i < im_field_count(h); ++i) {
        codes[i] = (uint16_t)render_patch_code(&s->colormap, h->data[i]);
        scaled[i] = (float)(h->data[i] / h->delta);
        contact[i] = s->contact && s->contact->data[i] > 0.0;
    }
}

/* With the context current and the inputs checked. */
static int draw_height_map(const im_render_context *c, const im_field *height, const im_height_style *s,
                           im_image *image)
{
    size_t count = im_field_count(height);
    /* One block: codes (2 bytes), heights (4), contact flags (1) per patch. */
    uint16_t *codes = malloc(count * 7 + 4);
    if (!codes || allocate_image(height, s->pixels_per_patch, s->boundary_px, image) != IM_OK) {
        free(codes);
        im_image_release(image);
        return im_fail(IM_ENOMEM, "height map %d x %d: out of memory", height->nx, height->ny);
    }
    float *scaled = (float *)(codes + 2 * ((count + 1) / 2));
    uint8_t *contact = (uint8_t *)(scaled + count);
    height_inputs(height, s, codes, scaled, contact);
    const im_gl *gl = &c->gl;
    GLuint program = c->height_program, textures[4];
    gl->UseProgram(program);
    textures[0] = render_texture(gl, 0, GL_R16UI, height->nx, height->ny, GL_RED_INTEGER, GL_UNSIGNED_SHORT, codes);
    textures[1] = render_texture(gl, 1, GL_R32F, height->nx, height->ny, GL_RED, GL_FLOAT, scaled);
    textures[2] = render_texture(gl, 2, GL_R8UI, height->nx, height->ny, GL_RED_INTEGER, GL_UNSIGNED_BYTE, contact);
    textures[3] = render_table_texture(gl, 3, s->colormap.map);
    render_set_int(gl, program, "codes", 0);
    render_set_int(gl, program, "heights", 1);
    render_set_int(gl, program, "contact", 2);
    render_set_int(gl, program, "table", 3);
    render_set_int(gl, program, "tension_table", 3); /* no tension codes: any sampler2D unit, not the codes' */
    set_common(gl, program, &s->colormap, height, s->pixels_per_patch, s->boundary_px, s->line);
    render_set_colour(gl, program, "outline_colour", s->outline);
    render_set_int(gl, program, "outline_width", im_height_outline_width(s));
    double azimuth = s->light_azimuth * M_PI / 180.0, altitude = s->light_altitude * M_PI / 180.0;
    gl->Uniform3f(gl->GetUniformLocation(program, "light"), (float)(cos(altitude) * sin(azimuth)),
                  (float)(cos(altitude) * cos(azimuth)), (float)sin(altitude));
    gl->Uniform1f(gl->GetUniformLocation(program, "shading"), (float)s->shading);
    gl->Uniform1f(gl->GetUniformLocation(program, "exaggeration"), (float)s->exaggeration);
    int status = draw_and_read(c, image->width, image->height, image->rgba);
    return finish(c, status, textures, 4, codes, image);
}

int im_render_height_map(im_render_context *c, const im_field *height, const im_height_style *s, im_image *image)
{
    ARG_REQUIRE(c, "context");
    ARG_VIEW(height, "height");
    ARG_REQUIRE(s, "style");
    ARG_REQUIRE(image, "image");
    if (s->contact)
        ARG_VIEW(s->contact, "style->contact");
    memset(image, 0, sizeof *image);
    int status = check_height_style(s, height);
    if (status == IM_OK)
        status = check_layout(c, height, s->pixels_per_patch, s->boundary_px, "height map");
    if (status == IM_OK)
        status = render_make_current(c);
    if (status != IM_OK)
        return status;
    status = draw_height_map(c, height, s, image);
    render_release_current(c);
    return status;
}
