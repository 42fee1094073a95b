/* Rendering: contact maps and height fields as RGBA arrays, and multi-panel figures written as
 * PNG/PDF/SVG. One GL context per process, opened at first use (with the GIL) and closed at exit.
 * Drawing and writing run without the GIL, one call at a time (a context serves one call at a time,
 * from any thread: render.h), on C copies or views of what they read: no Python object is touched
 * without the GIL. */
#include "core.h"

#include "indentmap/colormap.h"
#include "indentmap/figure.h"
#include "indentmap/io.h"
#include "indentmap/render.h"
#include "indentmap/status.h"

#include <limits.h>

static im_render_context *context;
static PyThread_type_lock drawing_lock; /* held by the call that draws or writes */

static void close_context(void)
{
    PyThread_acquire_lock(drawing_lock, WAIT_LOCK); /* a daemon thread may still be drawing */
    im_render_close(context);
    context = NULL;
    PyThread_release_lock(drawing_lock);
}

int py_render_init(void)
{
    drawing_lock = PyThread_allocate_lock();
    if (!drawing_lock) {
        PyErr_NoMemory();
        return -1;
    }
    return 0;
}

/* Runs work(job) without the GIL, once the drawing call before it has ended. work touches no Python
 * object. */
static int without_gil(int (*work)(void *job), void *job)
{
    int status;
    Py_BEGIN_ALLOW_THREADS PyThread_acquire_lock(drawing_lock, WAIT_LOCK);
    status = work(job);
    PyThread_release_lock(drawing_lock);
    Py_END_ALLOW_THREADS return status;
}

/* Opens a context of `backend` and makes it the one pictures use, closing the one before (once no call
 * draws with it); on failure the one before stays. */
static int open_context(im_render_backend backend)
{
    im_render_context *opened = NULL;
    int status = im_render_open(backend, &opened);
    if (status != IM_OK) {
        py_raise_status(status);
        return -1;
    }
    PyThread_acquire_lock(drawing_lock, WAIT_LOCK);
    im_render_context *before = context;
    context = opened;
    PyThread_release_lock(drawing_lock);
    if (before)
        im_render_close(before);
    else
        Py_AtExit(close_context);
    return 0;
}

static int ensure_context(void) { return context ? 0 : open_context(IM_RENDER_AUTO); }

/* The norm of both kinds of picture: colour map by name, range, linear or logarithmic. */
static int make_norm(const char *name, double lo, double hi, int logarithmic, im_colormap *norm)
{
    im_colormap_id map;
    int status = im_colormap_from_name(name, &map);
    if (status == IM_OK) {
        *norm = im_colormap_make(map, lo, hi);
        norm->logarithmic = logarithmic;
        status = im_colormap_check(norm);
    }
    if (status != IM_OK) {
        py_raise_status(status);
        return -1;
    }
    return 0;
}

typedef struct picture_request {
    int height_map; /* 0: contact map of forces, 1: height field */
    const char *colormap;
    double lo, hi;
    int logarithmic, scale;
    double circle_radius, circle_x, circle_y; /* contact maps; radius <= 0: none */
    PyObject *contact;                        /* height fields: forces whose contact is outlined, or None */
    const char *unit;                         /* the length unit of delta ("": units of delta), for the scale bar */
    double tension; /* contact maps: the top of the tension norm shared by a figure's panels; NaN:
                                  each map's own largest tension */
} picture_request;

/* One picture's inputs, all C: the request's numbers, the norm made from it, and array views. */
typedef struct picture_job {
    const im_field *field;
    const picture_request *request;
    im_colormap norm;
    const im_field *outline; /* height fields: the contact to outline, or NULL */
    im_image *image;
} picture_job;

static int draw_picture(void *argument)
{
    const picture_job *job = argument;
    const picture_request *r = job->request;
    if (r->height_map) {
        im_height_style style = im_height_style_default(job->field);
        style.colormap = job->norm;
        style.pixels_per_patch = r->scale;
        style.contact = job->outline;
        return im_render_height_map(context, job->field, &style, job->image);
    }
    im_contact_style style = im_contact_style_default(job->field);
    style.colormap = job->norm;
    style.pixels_per_patch = r->scale;
    style.circle_radius = r->circle_radius;
    if (!isnan(r->tension))
        style.tension = im_contact_tension_norm(r->tension);
    if (r->circle_radius > 0 && !isnan(r->circle_x)) {
        style.circle_x = r->circle_x;
        style.circle_y = r->circle_y;
    }
    return im_render_contact_map(context, job->field, &style, job->image);
}

/* The picture's field: a view of array, of spacing delta in the request's unit. */
static im_field picture_field(PyArrayObject *array, double delta, const picture_request *r)
{
    im_field field = py_field_view(array, delta);
    snprintf(field.unit, sizeof field.unit, "%s", r->unit);
    return field;
}

static int render_one(const im_field *field, const picture_request *r, im_image *image)
{
    picture_job job = {.field = field, .request = r, .image = image};
    if (ensure_context() < 0 || make_norm(r->colormap, r->lo, r->hi, r->logarithmic, &job.norm) < 0)
        return -1;
    PyArrayObject *contact = r->height_map && r->contact != Py_None ? py_heights_array(r->contact, "contact") : NULL;
    if (r->height_map && r->contact != Py_None && !contact)
        return -1;
    im_field outline = contact ? py_field_view(contact, field->delta) : (im_field){0};
    job.outline = contact ? &outline : NULL;
    int status = without_gil(draw_picture, &job);
    Py_XDECREF(contact);
    if (status != IM_OK)
        py_raise_status(status);
    return status == IM_OK ? 0 : -1;
}

static int parse_request(PyObject *kwargs, picture_request *r)
{
    static char *keywords[] = {"height_map",    "colormap", "vmin",     "vmax",    "log",  "scale",
                               "circle_radius", "circle_x", "circle_y", "contact", "unit", NULL};
    *r = (picture_request){.colormap = "viridis",
                           .scale = 2,
                           .circle_x = NAN,
                           .circle_y = NAN,
                           .contact = Py_None,
                           .unit = "",
                           .tension = NAN};
    PyObject *empty = PyTuple_New(0);
    if (!empty)
        return -1;
    int ok = PyArg_ParseTupleAndKeywords(empty, kwargs, "psddpidddOs", keywords, &r->height_map, &r->colormap, &r->lo,
                                         &r->hi, &r->logarithmic, &r->scale, &r->circle_radius, &r->circle_x,
                                         &r->circle_y, &r->contact, &r->unit);
    Py_DECREF(empty);
    return ok ? 0 : -1;
}

static PyObject *array_from_image(const im_image *image)
{
    npy_intp shape[3] = {image->height, image->width, 4};
    PyObject *out = PyArray_SimpleNew(3, shape, NPY_UINT8);
    if (out)
        memcpy(PyArray_DATA((PyArrayObject *)out), image->rgba, (size_t)image->width * image->height * 4);
    return out;
}

/* render(field, delta, **request) -> (height, width, 4) uint8 array, row 0 at the top. */
static PyObject *render(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    PyObject *obj;
    double delta;
    picture_request request;
    if (!PyArg_ParseTuple(args, "Od", &obj, &delta) || parse_request(kwargs, &request) < 0)
        return NULL;
    PyArrayObject *array = py_heights_array(obj, "field");
    if (!array)
        return NULL;
    im_field field = picture_field(array, delta, &request);
    im_image image = {0};
    PyObject *out = render_one(&field, &request, &image) == 0 ? array_from_image(&image) : NULL;
    im_image_release(&image);
    Py_DECREF(array);
    return out;
}

typedef struct figure_layout {
    PyObject *labels, *titles; /* tuples of str or None, one per panel, or None */
    int columns;
    const char *colorbar_label, *tension_label; /* the force's bar, the tension's (drawn when there is any) */
    double dpi, scale_bar;
    int extend_under, extend_over; /* some force in contact lies below / above the norm (render's triangles) */
} figure_layout;

/* Notes the forces in contact (> 0) outside the norm [lo, hi], as `indentmap render` does for its colour bar. */
static void note_extremes(const im_field *field, const picture_request *r, figure_layout *layout)
{
    for (size_t i = 0; i < im_field_count(field); ++i) {
        const double f = field->data[i];
        layout->extend_under |= f > 0 && f < r->lo;
        layout->extend_over |= f > r->hi;
    }
}

/* Item i's text, kept alive by the tuple while the figure is written without the GIL. */
static const char *item_text(PyObject *tuple, Py_ssize_t i)
{
    PyObject *item = tuple != Py_None && i < PyTuple_GET_SIZE(tuple) ? PyTuple_GET_ITEM(tuple, i) : NULL;
    return item && item != Py_None ? PyUnicode_AsUTF8(item) : NULL;
}

typedef struct figure_job {
    const im_figure *figure;
    const char *path;
} figure_job;

static int write_figure_file(void *argument)
{
    const figure_job *job = argument;
    return im_figure_write(job->figure, job->path);
}

static int write_figure(const char *path, im_image *images, Py_ssize_t count, const figure_layout *layout,
                        const picture_request *request)
{
    im_figure_panel *panels = PyMem_Calloc((size_t)count, sizeof *panels);
    if (!panels) {
        PyErr_NoMemory();
        return -1;
    }
    for (Py_ssize_t i = 0; i < count; ++i)
        panels[i] = (im_figure_panel){.image = &images[i],
                                      .label = item_text(layout->labels, i),
                                      .title = item_text(layout->titles, i)};
    im_colormap norm;
    int status = make_norm(request->colormap, request->lo, request->hi, request->logarithmic, &norm) < 0 ? -1 : IM_OK;
    if (status == IM_OK && !PyErr_Occurred()) {
        im_figure figure = im_figure_default();
        figure.columns = layout->columns;
        figure.rows = (int)((count + layout->columns - 1) / layout->columns);
        figure.panels = panels;
        figure.colormap = &norm;
        figure.colorbar_label = layout->colorbar_label;
        figure.dpi = layout->dpi;
        figure.scale_bar = layout->scale_bar;
        figure.extend_under = layout->extend_under;
        figure.extend_over = layout->extend_over;
        const im_colormap tension = im_contact_tension_norm(request->tension);
        if (request->tension > 0) {
            figure.tension_colormap = &tension;
            figure.tension_label = layout->tension_label;
        }
        figure_job job = {&figure, path};
        status = figure.rows * figure.columns == count
                     ? without_gil(write_figure_file, &job)
                     : im_fail(IM_EINVAL, "figure: %ld panels do not fill %d columns", (long)count, layout->columns);
        if (status != IM_OK)
            py_raise_status(status);
    }
    PyMem_Free(panels);
    return PyErr_Occurred() ? -1 : 0;
}

/* The largest tension of the panels' fields, shared by their maps and the tension bar as `indentmap render
 * contact` shares it; -1 with an exception set if a field is not an array of heights. */
static double shared_tension(PyObject *fields, double delta, const picture_request *request)
{
    im_colormap_range tensions = im_colormap_range_empty(IM_COLORMAP_TENSIONS);
    for (Py_ssize_t i = 0; i < PyTuple_GET_SIZE(fields); ++i) {
        PyArrayObject *array = py_heights_array(PyTuple_GET_ITEM(fields, i), "panel field");
        if (!array)
            return -1;
        im_field field = picture_field(array, delta, request);
        im_colormap_range_add(&tensions, &field);
        Py_DECREF(array);
    }
    return fmax(tensions.hi, 0.0); /* 0: none under tension */
}

/* The panels' images and the figure written from them, the GIL released around each drawing call
 * (the tuples cannot change meanwhile, as lists could). */
static int draw_figure(const char *path, PyObject *fields, double delta, figure_layout *layout,
                       picture_request *request)
{
    Py_ssize_t count = PyTuple_GET_SIZE(fields);
    request->tension = shared_tension(fields, delta, request);
    if (request->tension < 0)
        return -1;
    im_image *images = PyMem_Calloc((size_t)count, sizeof *images);
    int failed = images ? 0 : (PyErr_NoMemory(), -1);
    for (Py_ssize_t i = 0; i < count && !failed; ++i) {
        PyArrayObject *array = py_heights_array(PyTuple_GET_ITEM(fields, i), "panel field");
        im_field field = array ? picture_field(array, delta, request) : (im_field){0};
        failed = !array || render_one(&field, request, &images[i]) < 0;
        if (!failed)
            note_extremes(&field, request, layout);
        Py_XDECREF(array);
    }
    if (!failed)
        failed = write_figure(path, images, count, layout, request) < 0;
    for (Py_ssize_t i = 0; images && i < count; ++i)
        im_image_release(&images[i]);
    PyMem_Free(images);
    return failed;
}

/* A new reference: None as it is, a sequence as a tuple (NULL with TypeError for anything else). */
static PyObject *frozen(PyObject *sequence)
{
    return sequence == Py_None ? Py_NewRef(Py_None) : PySequence_Tuple(sequence);
}

/* figure(path, fields, delta, labels, titles, columns, colorbar_label, tension_label, dpi, scale_bar, **request) */
static PyObject *figure(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    PyObject *path_bytes, *fields, *labels, *titles;
    double delta;
    figure_layout layout = {0};
    picture_request request;
    if (!PyArg_ParseTuple(args, "O&O!dOOissdd", PyUnicode_FSConverter, &path_bytes, &PyList_Type, &fields, &delta,
                          &labels, &titles, &layout.columns, &layout.colorbar_label, &layout.tension_label,
                          &layout.dpi, &layout.scale_bar) ||
        parse_request(kwargs, &request) < 0)
        return NULL;
    if (layout.columns < 1 || PyList_Size(fields) < 1) {
        Py_DECREF(path_bytes);
        return PyErr_Format(PyExc_ValueError, "figure: %ld panels in %d columns: expected at least one of each",
                            (long)PyList_Size(fields), layout.columns);
    }
    PyObject *panels = PySequence_Tuple(fields);
    layout.labels = frozen(labels);
    layout.titles = frozen(titles);
    int failed = !panels || !layout.labels || !layout.titles ||
                 draw_figure(PyBytes_AS_STRING(path_bytes), panels, delta, &layout, &request);
    Py_XDECREF(panels);
    Py_XDECREF(layout.labels);
    Py_XDECREF(layout.titles);
    Py_DECREF(path_bytes);
    return failed ? NULL : Py_NewRef(Py_None);
}

typedef struct png_job {
    const char *path;
    const uint8_t *rgba;
    int width, height;
    const im_png_text *texts;
    int text_count;
} png_job;

static int write_png_file(void *argument)
{
    const png_job *job = argument;
    im_png_options options = {.texts = job->texts, .text_count = job->text_count, .compression = 6};
    return im_png_write(job->path, job->rgba, job->width, job->height, 4, (size_t)job->width * 4, &options);
}

/* The (key, value) pairs of a tuple as PNG text chunks, kept alive by the tuple, with `spare` more slots
 * after them; NULL with an exception set for an item that is not a pair of str. */
static im_png_text *png_texts(PyObject *pairs, int spare)
{
    Py_ssize_t count = PyTuple_GET_SIZE(pairs);
    im_png_text *texts = PyMem_Calloc((size_t)count + (size_t)spare + 1, sizeof *texts);
    if (!texts) {
        PyErr_NoMemory();
        return NULL;
    }
    for (Py_ssize_t i = 0; i < count; ++i)
        if (!PyArg_ParseTuple(PyTuple_GET_ITEM(pairs, i), "ss;write_png: texts: expected (key, value) pairs of str",
                              &texts[i].key, &texts[i].value)) {
            PyMem_Free(texts);
            return NULL;
        }
    return texts;
}

/* obj as a C-contiguous (height, width, 4) uint8 array; NULL with an exception set otherwise. */
static PyArrayObject *rgba_array(PyObject *obj)
{
    PyArrayObject *rgba = (PyArrayObject *)PyArray_FromAny(obj, PyArray_DescrFromType(NPY_UINT8), 3, 3,
                                                           NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED, NULL);
    if (rgba && PyArray_DIMS(rgba)[2] != 4) {
        PyErr_SetString(PyExc_ValueError, "expected an (height, width, 4) RGBA array");
        Py_CLEAR(rgba);
    }
    return rgba;
}

/* write_png(path, rgba, texts): an (height, width, 4) uint8 array as a PNG file (atomic, level 6) with the
 * (key, value) pairs of the tuple texts as tEXt chunks. */
static PyObject *write_png(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *path_bytes, *obj, *pairs;
    if (!PyArg_ParseTuple(args, "O&OO!", PyUnicode_FSConverter, &path_bytes, &obj, &PyTuple_Type, &pairs))
        return NULL;
    im_png_text *texts = png_texts(pairs, 0);
    if (!texts) {
        Py_DECREF(path_bytes);
        return NULL;
    }
    PyArrayObject *rgba = rgba_array(obj);
    int status = IM_OK;
    if (rgba) {
        png_job job = {PyBytes_AS_STRING(path_bytes),
                       PyArray_DATA(rgba),
                       (int)PyArray_DIMS(rgba)[1],
                       (int)PyArray_DIMS(rgba)[0],
                       texts,
                       (int)PyTuple_GET_SIZE(pairs)};
        status = without_gil(write_png_file, &job);
    }
    PyMem_Free(texts);
    Py_XDECREF(rgba);
    Py_DECREF(path_bytes);
    if (PyErr_Occurred())
        return NULL;
    return status == IM_OK ? Py_NewRef(Py_None) : py_raise_status(status);
}

typedef struct gif_job {
    const char *path;
    const im_image *frames;
    int count;
    double seconds_per_frame;
} gif_job;

static int write_gif_file(void *argument)
{
    const gif_job *job = argument;
    return im_animation_gif(job->frames, job->count, job->seconds_per_frame, job->path);
}

/* The frames of the sequence as (height, width, 4) uint8 arrays (new references in arrays[]) and images
 * borrowing their pixels; -1 with a ValueError naming the first frame that is not one. */
static int gif_frames(PyObject *items, Py_ssize_t count, PyArrayObject **arrays, im_image *frames)
{
    for (Py_ssize_t i = 0; i < count; ++i) {
        arrays[i] = rgba_array(PySequence_Fast_GET_ITEM(items, i));
        if (!arrays[i]) {
            PyErr_Format(PyExc_ValueError, "frames[%zd]: expected an (height, width, 4) uint8 RGBA array", i);
            return -1;
        }
        frames[i] = (im_image){.width = (int)PyArray_DIMS(arrays[i])[1],
                               .height = (int)PyArray_DIMS(arrays[i])[0],
                               .rgba = PyArray_DATA(arrays[i])};
    }
    return 0;
}

/* write_gif(path, frames, seconds_per_frame): the (height, width, 4) uint8 arrays of the sequence frames as
 * a looping GIF, as `render animate --out FILE.gif` writes its frames (figure.h: im_animation_gif). */
static PyObject *write_gif(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *path_bytes, *sequence;
    double seconds_per_frame;
    if (!PyArg_ParseTuple(args, "O&Od", PyUnicode_FSConverter, &path_bytes, &sequence, &seconds_per_frame))
        return NULL;
    PyObject *items = PySequence_Fast(sequence, "frames: expected a sequence of (height, width, 4) uint8 arrays");
    Py_ssize_t count = items ? PySequence_Fast_GET_SIZE(items) : 0;
    if (items && (count < 1 || count > INT_MAX))
        PyErr_Format(PyExc_ValueError, "frames: %zd frames: expected 1 to %d", count, INT_MAX);
    PyArrayObject **arrays = PyErr_Occurred() ? NULL : PyMem_Calloc((size_t)count, sizeof *arrays);
    im_image *frames = arrays ? PyMem_Calloc((size_t)count, sizeof *frames) : NULL;
    int status = IM_OK;
    if (frames && gif_frames(items, count, arrays, frames) == 0) {
        gif_job job = {PyBytes_AS_STRING(path_bytes), frames, (int)count, seconds_per_frame};
        status = without_gil(write_gif_file, &job);
    } else if (!PyErr_Occurred())
        PyErr_NoMemory();
    for (Py_ssize_t i = 0; arrays && i < count; ++i)
        Py_XDECREF(arrays[i]);
    PyMem_Free(arrays);
    PyMem_Free(frames);
    Py_XDECREF(items);
    Py_DECREF(path_bytes);
    if (PyErr_Occurred())
        return NULL;
    return status == IM_OK ? Py_NewRef(Py_None) : py_raise_status(status);
}

typedef struct view3d_job {
    const im_field *height, *force; /* force: NULL for no contact colours */
    const im_indenter *punch;       /* NULL: none */
    im_view3d_style style;
    int fit_distance; /* the nearest perspective camera that shows it all */
    im_image *image;
} view3d_job;

static int draw_view3d(void *argument)
{
    view3d_job *job = argument;
    int status = job->fit_distance
                     ? im_view3d_fit_distance(job->height, job->punch, &job->style, &job->style.camera.distance)
                     : IM_OK;
    return status == IM_OK ? im_render_view3d(context, job->height, job->force, job->punch, &job->style, job->image)
                           : status;
}

/* The punch of a 3-D view (as `render view3d --punch --alpha --radius --x --y`): kind "none" is NULL. */
static int view3d_punch(const char *kind, double alpha, double radius, PyObject *axis, im_indenter *punch,
                        const im_indenter **drawn)
{
    *drawn = punch;
    if (strcmp(kind, "cone") == 0)
        *punch = im_indenter_cone(alpha);
    else if (strcmp(kind, "sphere") == 0)
        *punch = im_indenter_sphere(radius);
    else if (strcmp(kind, "flat") == 0)
        *punch = im_indenter_flat(radius);
    else if (strcmp(kind, "none") == 0)
        *drawn = NULL;
    else {
        PyErr_Format(PyExc_ValueError, "punch '%s': expected 'cone', 'sphere', 'flat' or 'none'", kind);
        return -1;
    }
    punch->centred = axis == Py_None;
    return axis == Py_None || PyArg_ParseTuple(axis, "dd", &punch->x0, &punch->y0) ? 0 : -1;
}

/* view3d(height, delta, force, punch, alpha, radius, axis, **style) -> (height, width, 4) uint8 array:
 * render.h's im_render_view3d, with render view3d's options */
static PyObject *view3d(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *keywords[] = {"height",    "delta",        "force",        "punch",     "alpha",       "radius",
                               "axis",      "punch_mode",   "azimuth",      "elevation", "distance",    "fov",
                               "ortho",     "ortho_height", "exaggeration", "width",     "pixels_high", "samples",
                               "mesh_side", "colormap",     "vmin",         "vmax",      "log",         NULL};
    PyObject *height_obj, *force_obj, *axis, *distance;
    double delta, alpha, radius, lo, hi;
    const char *kind, *colormap;
    int ortho, logarithmic, punch_mode;
    im_view3d_style style = im_view3d_style_default(NULL);
    im_view3d_camera *camera = &style.camera;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs,
                                     "OdOsddOiddOdpdd"
                                     "iiiisddp",
                                     keywords, &height_obj, &delta, &force_obj, &kind, &alpha, &radius, &axis,
                                     &punch_mode, &camera->azimuth, &camera->elevation, &distance,
                                     &camera->field_of_view, &ortho, &camera->ortho_height, &style.exaggeration,
                                     &style.width, &style.height, &style.samples, &style.mesh_side, &colormap, &lo,
                                     &hi, &logarithmic))
        return NULL;
    camera->projection = ortho ? IM_VIEW3D_ORTHOGRAPHIC : IM_VIEW3D_PERSPECTIVE;
    style.punch_mode = (im_view3d_punch)punch_mode; /* checked by im_render_view3d */
    if (distance != Py_None && (camera->distance = PyFloat_AsDouble(distance), PyErr_Occurred()))
        return NULL;
    im_indenter punch;
    view3d_job job = {.fit_distance = distance == Py_None && !ortho};
    if (view3d_punch(kind, alpha, radius, axis, &punch, &job.punch) < 0 ||
        make_norm(colormap, lo, hi, logarithmic, &style.colormap) < 0 || ensure_context() < 0)
        return NULL;
    PyArrayObject *height = py_heights_array(height_obj, "height");
    PyArrayObject *force = height && force_obj != Py_None ? py_heights_array(force_obj, "force") : NULL;
    PyObject *out = NULL;
    if (height && (force || force_obj == Py_None)) {
        im_field height_view = py_field_view(height, delta),
                 force_view = force ? py_field_view(force, delta) : (im_field){0};
        im_image image = {0};
        job.height = &height_view;
        job.force = force ? &force_view : NULL;
        job.style = style;
        if (force) /* as render view3d: the tension ramp over 0 .. the largest tension */
            job.style.tension = im_contact_tension_norm(im_contact_largest_tension(&force_view));
        job.image = &image;
        int status = without_gil(draw_view3d, &job);
        out = status == IM_OK ? array_from_image(&image) : py_raise_status(status);
        im_image_release(&image);
    }
    Py_XDECREF(height);
    Py_XDECREF(force);
    return out;
}

typedef struct view3d_figure_request {
    const char *title, *colormap, *unit;
    double exaggeration, lo, hi, dpi;
    int logarithmic;
} view3d_figure_request;

/* The figure render view3d writes around its image (without --raw): the title with the exaggeration,
 * the force's colour bar (and the tension's where the force has tension) in the unit, no scale bar. */
static int write_view3d_figure(const char *path, const im_image *image, const im_field *force,
                               const view3d_figure_request *r, im_png_text *texts, int text_count)
{
    char exaggeration[96], title[256], label[128], tension_label[128];
    im_view3d_exaggeration_text(r->exaggeration, exaggeration, sizeof exaggeration);
    snprintf(title, sizeof title, "%s%s%s", r->title, *r->title ? ", " : "", exaggeration);
    texts[text_count++] = (im_png_text){"Vertical exaggeration", exaggeration};
    im_colormap norm;
    if (make_norm(r->colormap, r->lo, r->hi, r->logarithmic, &norm) < 0)
        return -1;
    int status = im_figure_colorbar_label("force", r->unit, label, sizeof label);
    if (status == IM_OK)
        status = im_figure_colorbar_label("tension", r->unit, tension_label, sizeof tension_label);
    double largest_tension = force ? im_contact_largest_tension(force) : 0.0;
    const im_colormap tension = im_contact_tension_norm(largest_tension);
    im_figure_panel panel = {image, NULL, title};
    im_figure figure = im_figure_default();
    figure.panels = &panel;
    figure.colormap = force ? &norm : NULL;
    figure.colorbar_label = label;
    figure.extend_under = norm.logarithmic;
    if (largest_tension > 0.0) {
        figure.tension_colormap = &tension;
        figure.tension_label = tension_label;
    }
    figure.scale_bar = -1.0; /* a perspective view has no single scale */
    figure.dpi = r->dpi;
    figure.texts = texts;
    figure.text_count = text_count;
    figure_job job = {&figure, path};
    if (status == IM_OK)
        status = without_gil(write_figure_file, &job);
    return status == IM_OK ? 0 : (py_raise_status(status), -1);
}

/* view3d_figure(path, rgba, force, texts, **request): view3d's image in render view3d's figure. */
static PyObject *view3d_figure(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *keywords[] = {"path", "rgba", "force", "texts", "title", "exaggeration", "colormap", "vmin",
                               "vmax", "log",  "dpi",   "unit",  NULL};
    PyObject *path_bytes, *rgba_obj, *force_obj, *pairs;
    view3d_figure_request r;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O&OOO!sdsddpds", keywords, PyUnicode_FSConverter, &path_bytes,
                                     &rgba_obj, &force_obj, &PyTuple_Type, &pairs, &r.title, &r.exaggeration,
                                     &r.colormap, &r.lo, &r.hi, &r.logarithmic, &r.dpi, &r.unit))
        return NULL;
    im_png_text *texts = png_texts(pairs, 1);
    PyArrayObject *rgba = texts ? rgba_array(rgba_obj) : NULL;
    PyArrayObject *force = rgba && force_obj != Py_None ? py_heights_array(force_obj, "force") : NULL;
    int failed = !rgba || (force_obj != Py_None && !force);
    if (!failed) {
        npy_intp *shape = PyArray_DIMS(rgba);
        im_image image = {.width = (int)shape[1], .height = (int)shape[0], .rgba = PyArray_DATA(rgba)};
        im_field force_view = force ? py_field_view(force, 1.0) : (im_field){0};
        failed = write_view3d_figure(PyBytes_AS_STRING(path_bytes), &image, force ? &force_view : NULL, &r, texts,
                                     (int)PyTuple_GET_SIZE(pairs)) < 0;
    }
    Py_XDECREF(force);
    Py_XDECREF(rgba);
    PyMem_Free(texts);
    Py_DECREF(path_bytes);
    return failed ? NULL : Py_NewRef(Py_None);
}

/* read_png(path) -> (height, width, 4) uint8 array of an 8-bit RGB or RGBA PNG (io.h: im_png_read; RGB
 * made opaque RGBA) */
static PyObject *read_png(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *path_bytes;
    if (!PyArg_ParseTuple(args, "O&", PyUnicode_FSConverter, &path_bytes))
        return NULL;
    uint8_t *pixels = NULL;
    int width = 0, height = 0, channels = 0, status;
    Py_BEGIN_ALLOW_THREADS status = im_png_read(PyBytes_AS_STRING(path_bytes), &pixels, &width, &height, &channels);
    Py_END_ALLOW_THREADS Py_DECREF(path_bytes);
    if (status != IM_OK)
        return py_raise_status(status);
    npy_intp shape[3] = {height, width, 4};
    PyObject *out = PyArray_SimpleNew(3, shape, NPY_UINT8);
    uint8_t *rgba = out ? PyArray_DATA((PyArrayObject *)out) : NULL;
    for (size_t i = 0; rgba && i < (size_t)width * (size_t)height; ++i)
        for (int c = 0; c < 4; ++c)
            rgba[4 * i + (size_t)c] = c < channels ? pixels[(size_t)channels * i + (size_t)c] : 255;
    free(pixels);
    return out;
}

/* colorbar_label(quantity, unit) -> the colour bar's label of a field in its units (figure.h) */
static PyObject *colorbar_label(PyObject *self, PyObject *args)
{
    (void)self;
    const char *quantity, *unit;
    char text[128];
    if (!PyArg_ParseTuple(args, "ss", &quantity, &unit))
        return NULL;
    int status = im_figure_colorbar_label(quantity, unit, text, sizeof text);
    return status == IM_OK ? PyUnicode_FromString(text) : py_raise_status(status);
}

static PyObject *renderer(PyObject *self, PyObject *unused)
{
    (void)self, (void)unused;
    if (ensure_context() < 0)
        return NULL;
    return Py_BuildValue("{s:s,s:s,s:s}", "backend", im_render_backend_name(context), "gl_renderer",
                         im_render_gl_renderer(context), "gl_version", im_render_gl_version(context));
}

static PyObject *use_backend(PyObject *self, PyObject *args)
{
    const char *name;
    im_render_backend backend;
    if (!PyArg_ParseTuple(args, "s", &name))
        return NULL;
    int status = im_render_backend_from_name(name, &backend);
    if (status != IM_OK)
        return py_raise_status(status);
    return open_context(backend) < 0 ? NULL : renderer(self, NULL);
}

/* use(fields, count, user) over field views of the sequence's arrays (TypeError naming `what` for one that is
 * not a 2-D array of numbers); its status, raised as the library's error where it is not IM_OK. 0 or -1. */
typedef int fields_use(im_field **fields, int count, void *user);
static int with_field_views(PyObject *sequence, const char *what, fields_use *use, void *user)
{
    const Py_ssize_t count = PySequence_Fast_GET_SIZE(sequence);
    PyArrayObject **arrays = PyMem_Calloc((size_t)count + 1, sizeof *arrays);
    im_field *views = PyMem_Calloc((size_t)count + 1, sizeof *views),
             **fields = PyMem_Calloc((size_t)count + 1, sizeof *fields);
    Py_ssize_t made = 0;
    for (; arrays && views && fields && made < count; ++made) {
        arrays[made] = py_heights_array(PySequence_Fast_GET_ITEM(sequence, made), what);
        if (!arrays[made])
            break;
        views[made] = py_field_view(arrays[made], 1.0);
        fields[made] = &views[made];
    }
    int status = !arrays || !views || !fields ? (PyErr_NoMemory(), IM_ENOMEM)
                 : made < count               ? IM_EINVAL /* py_heights_array's TypeError set */
                                              : use(fields, (int)count, user);
    if (arrays && views && fields && made == count && status != IM_OK)
        py_raise_status(status);
    for (Py_ssize_t i = 0; arrays && i < made; ++i)
        Py_DECREF(arrays[i]);
    PyMem_Free(arrays);
    PyMem_Free(views);
    PyMem_Free(fields);
    return status == IM_OK ? 0 : -1;
}

typedef struct clipped_range {
    im_colormap_values values;
    double clip;
    im_colormap_range range;
} clipped_range;

static int clip_range(im_field **fields, int count, void *user)
{
    clipped_range *r = user;
    return im_colormap_range_clipped(r->values, fields, count, r->clip, &r->range);
}

/* The fields' range of values of the given kind with clip percent cut at each end (colormap.h). 0 or -1. */
static int fields_range(PyObject *sequence, const char *what, im_colormap_values values, double clip,
                        im_colormap_range *range)
{
    clipped_range r = {values, clip, {0}};
    const int failed = with_field_views(sequence, what, clip_range, &r);
    *range = r.range;
    return failed;
}

typedef struct outlier_note_text {
    const char *unit; /* of the heights, said in the text */
    char text[512];
    int farthest;
} outlier_note_text;

static int note_outliers(im_field **fields, int count, void *user)
{
    outlier_note_text *note = user;
    for (int i = 0; i < count; ++i) /* our views: the unit the caller gave the arrays */
        snprintf(fields[i]->unit, sizeof fields[i]->unit, "%s", note->unit);
    return im_colormap_outlier_note(fields, count, note->text, sizeof note->text, &note->farthest);
}

/* outlier_note(fields, what, unit) -> (text, farthest, percent): render's notice that a few outliers set the fields'
 * default range of heights (colormap.h: im_colormap_outlier_note; "" and -1 where they do not), in `unit`. */
static PyObject *outlier_note(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *fields;
    const char *what, *unit;
    if (!PyArg_ParseTuple(args, "Oss", &fields, &what, &unit))
        return NULL;
    PyObject *sequence = PySequence_Fast(fields, "fields: expected a sequence of arrays");
    if (!sequence)
        return NULL;
    outlier_note_text note = {unit, "", -1};
    const int failed = with_field_views(sequence, what, note_outliers, &note);
    Py_DECREF(sequence);
    return failed ? NULL : Py_BuildValue("sid", note.text, note.farthest, IM_COLORMAP_OUTLIER_PERCENT);
}

/* norm_range(fields, what, heights, vmin, vmax, log, clip) -> (lo, hi): the default norm every front end gives
 * the fields together (colormap.h: im_colormap_range_norm), forces or (heights) heights, `clip` percent cut at
 * each end (render --clip), with vmin / vmax (None: not given); TypeError naming `what` for a field that is not
 * a 2-D array of numbers, InvalidArgument for a clip outside [0, 50). */
static PyObject *norm_range(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *fields, *vmin_obj, *vmax_obj;
    const char *what;
    int heights, logarithmic;
    double clip;
    if (!PyArg_ParseTuple(args, "OspOOpd", &fields, &what, &heights, &vmin_obj, &vmax_obj, &logarithmic, &clip))
        return NULL;
    double vmin = vmin_obj == Py_None ? NAN : PyFloat_AsDouble(vmin_obj);
    double vmax = vmax_obj == Py_None ? NAN : PyFloat_AsDouble(vmax_obj);
    PyObject *sequence = PyErr_Occurred() ? NULL : PySequence_Fast(fields, "fields: expected a sequence of arrays");
    if (!sequence)
        return NULL;
    im_colormap_range range;
    const int failed = fields_range(sequence, what, heights ? IM_COLORMAP_HEIGHTS : IM_COLORMAP_FORCES, clip,
                                    &range) != 0;
    Py_DECREF(sequence);
    if (failed)
        return NULL;
    const im_colormap norm = im_colormap_range_norm(&range, IM_COLORMAP_VIRIDIS, vmin, vmax, logarithmic);
    return Py_BuildValue("dd", norm.lo, norm.hi);
}

PyMethodDef py_render_methods[] = {
    {"norm_range", norm_range, METH_VARARGS,
     "norm_range(fields, what, heights, vmin, vmax, log, clip) -> (lo, hi): the fields' shared default norm"},
    {"outlier_note", outlier_note, METH_VARARGS,
     "outlier_note(fields, what, unit) -> (text, farthest, percent): whether a few outliers set the heights' range"},
    {"render", (PyCFunction)(void (*)(void))render, METH_VARARGS | METH_KEYWORDS, "render a field to RGBA"},
    {"figure", (PyCFunction)(void (*)(void))figure, METH_VARARGS | METH_KEYWORDS, "write a multi-panel figure"},
    {"write_png", write_png, METH_VARARGS, "write_png(path, rgba, texts)"},
    {"write_gif", write_gif, METH_VARARGS, "write_gif(path, frames, seconds_per_frame): an animated GIF"},
    {"colorbar_label", colorbar_label, METH_VARARGS, "colorbar_label(quantity, unit) -> the colour bar's label"},
    {"read_png", read_png, METH_VARARGS, "read_png(path) -> (height, width, 4) uint8 RGBA"},
    {"view3d", (PyCFunction)(void (*)(void))view3d, METH_VARARGS | METH_KEYWORDS,
     "view3d(height, delta, force, punch, alpha, radius, axis, **style) -> RGBA: the deformed surface in 3-D"},
    {"view3d_figure", (PyCFunction)(void (*)(void))view3d_figure, METH_VARARGS | METH_KEYWORDS,
     "view3d_figure(path, rgba, force, texts, **request): render view3d's figure around view3d's image"},
    {"renderer", renderer, METH_NOARGS, "the GL backend and renderer in use"},
    {"use_backend", use_backend, METH_VARARGS, "use_backend(name) -> renderer(): opens that backend for pictures"},
    {NULL, NULL, 0, NULL}};
