/* indentmap._core.indent_run: one indentation run into its folder, as `indentmap indent` makes it
 * (indent.h: im_indent_run), without the GIL; its lines and progress go to Python callables
 * (callbacks.c). The options come as a dict whose keys are im_indent_options' members (solver
 * options by their solver.h names), checked and named by python/indentmap/solver.py. */
#include "core.h"

#include "indentmap/indent.h"
#include "indentmap/indenter.h"
#include "indentmap/render.h"
#include "indentmap/status.h"

#include <stddef.h>
#include <string.h>

/* The numbers and flags of the options, read from the dict by name when present. */
typedef enum { REAL, INTEGER } field_kind;
typedef struct option_field {
    const char *name;
    field_kind kind;
    size_t offset;
} option_field;

#define FIELD(name, kind, member)                                                                                    \
    {                                                                                                                \
        name, kind, offsetof(im_indent_options, member)                                                              \
    }
static const option_field FIELDS[] = {
    FIELD("nx", INTEGER, nx),
    FIELD("ny", INTEGER, ny),
    FIELD("delta", REAL, delta),
    FIELD("delta_x", REAL, read.set.delta_x),
    FIELD("fill", INTEGER, read.fill),
    FIELD("resample_square", INTEGER, read.resample_square),
    FIELD("alpha", REAL, punch.alpha_degrees),
    FIELD("radius", REAL, punch.radius),
    FIELD("punch_given", INTEGER, punch_given),
    FIELD("pressures", INTEGER, pressures),
    FIELD("tol_given", INTEGER, tol_given),
    FIELD("e_star", REAL, solver.e_star),
    FIELD("hardness", REAL, solver.hardness),
    FIELD("tol", REAL, solver.tol),
    FIELD("max_iterations", INTEGER, solver.max_iterations),
    FIELD("crop", INTEGER, solver.crop),
    FIELD("periodic", INTEGER, solver.periodic),
    FIELD("adhesion_work", REAL, solver.adhesion_work),
    FIELD("adhesion_range", REAL, solver.adhesion_range),
    FIELD("adhesion_zone", REAL, solver.adhesion_zone),
    FIELD("cascade", INTEGER, solver.cascade),
    FIELD("precondition", INTEGER, solver.precondition),
    FIELD("fft_measure", INTEGER, solver.fft_measure),
    FIELD("fields", INTEGER, fields),
    FIELD("frames", INTEGER, frames),
    FIELD("distributions", INTEGER, distributions),
    FIELD("page_embed", INTEGER, page_embed),
};

static int read_field(PyObject *dict, const option_field *f, im_indent_options *o)
{
    PyObject *value = PyDict_GetItemString(dict, f->name); /* borrowed */
    if (!value)
        return 0;
    char *member = (char *)o + f->offset;
    if (f->kind == REAL)
        *(double *)member = PyFloat_AsDouble(value);
    else
        *(int *)member = (int)PyLong_AsLong(value);
    return PyErr_Occurred() ? -1 : 0;
}

/* The strings of the options: paths as the file system's bytes (kept in held until the run ends). */
typedef struct held_strings {
    PyObject *surface, *profile, *out, *wisdom, *e_star_unit, *quality;
} held_strings;

static int read_path(PyObject *dict, const char *name, PyObject **held, const char **out)
{
    PyObject *value = PyDict_GetItemString(dict, name);
    if (!value || value == Py_None)
        return 0;
    if (!PyUnicode_FSConverter(value, held))
        return -1;
    *out = PyBytes_AS_STRING(*held);
    return 0;
}

static void release(held_strings *h)
{
    Py_XDECREF(h->surface);
    Py_XDECREF(h->profile);
    Py_XDECREF(h->out);
    Py_XDECREF(h->wisdom);
    Py_XDECREF(h->e_star_unit);
    Py_XDECREF(h->quality);
}

static int read_strings(PyObject *dict, held_strings *h, im_indent_options *o)
{
    return read_path(dict, "surface", &h->surface, &o->surface_path) < 0 ||
                   read_path(dict, "profile", &h->profile, &o->profile_path) < 0 ||
                   read_path(dict, "out", &h->out, &o->out) < 0 ||
                   read_path(dict, "wisdom", &h->wisdom, &o->solver.wisdom_path) < 0 ||
                   read_path(dict, "e_star_unit", &h->e_star_unit, &o->e_star_unit) < 0 ||
                   read_path(dict, "quality", &h->quality, &o->quality) < 0
               ? -1
               : 0;
}

/* The dict's string under name (UTF-8, borrowed from it), or NULL: none there, or an error set. */
static const char *text_of(PyObject *dict, const char *name)
{
    PyObject *value = PyDict_GetItemString(dict, name);
    return value ? PyUnicode_AsUTF8(value) : NULL;
}

/* How the surface file is read, the block indented and its preparation (--channel .. --npy-order,
 * --crop, --align, --detrend), as the program reads them. */
static int read_surface_options(PyObject *dict, im_indent_options *o)
{
    const char *channel = text_of(dict, "channel"), *unit = text_of(dict, "unit"),
               *height_unit = text_of(dict, "height_unit"), *length_unit = text_of(dict, "length_unit"),
               *detrend = text_of(dict, "detrend"), *align = text_of(dict, "align");
    PyObject *npy_order = PyDict_GetItemString(dict, "npy_order"), *region = PyDict_GetItemString(dict, "region");
    if (PyErr_Occurred())
        return -1;
    const py_read_names names = {channel ? channel : "", unit ? unit : "", height_unit ? height_unit : "",
                                 length_unit ? length_unit : ""};
    if (py_surface_read_options(&names, o->read.fill, o->read.resample_square,
                                npy_order ? (int)PyLong_AsLong(npy_order) : 0, &o->read) < 0 ||
        PyErr_Occurred())
        return -1;
    if ((detrend && py_detrend_from_name(detrend, &o->detrend) < 0) ||
        (align && py_align_from_name(align, &o->align) < 0))
        return -1;
    return region && !PyArg_ParseTuple(region, "iiii", &o->crop[0], &o->crop[1], &o->crop[2], &o->crop[3]) ? -1 : 0;
}

/* The dict's axis (x, y), when it has one: the punch off the grid's centre. */
static int read_axis(PyObject *dict, im_indent_options *o)
{
    PyObject *x = PyDict_GetItemString(dict, "x"), *y = PyDict_GetItemString(dict, "y");
    if (!x || !y)
        return 0;
    o->punch.centred = 0;
    o->punch.x0 = PyFloat_AsDouble(x);
    o->punch.y0 = PyFloat_AsDouble(y);
    return PyErr_Occurred() ? -1 : 0;
}

/* --slope-definition's names: "spectral", "fd", or "" for the surface's rule (-1). */
static int slope_from_name(const char *name, int *definition)
{
    if (!name[0] || strcmp(name, "spectral") == 0 || strcmp(name, "fd") == 0) {
        *definition = !name[0] ? -1 : name[0] == 's' ? IM_SLOPE_SPECTRAL : IM_SLOPE_FINITE_DIFFERENCE;
        return 0;
    }
    PyErr_Format(PyExc_ValueError, "slope_definition '%s': expected 'spectral' or 'fd'", name);
    return -1;
}

/* The options given by name, each parsed as the program parses it. */
static int read_names(PyObject *dict, im_indent_options *o)
{
    const char *control = text_of(dict, "control"), *kind = text_of(dict, "kind"),
               *law = text_of(dict, "adhesion_law"), *device = text_of(dict, "device"),
               *backend = text_of(dict, "backend"), *slope = text_of(dict, "slope_definition");
    im_render_backend chosen = IM_RENDER_AUTO;
    if (PyErr_Occurred() || (control && py_control_from_name(control, &o->control) < 0) ||
        (slope && slope_from_name(slope, &o->slope_definition) < 0))
        return -1;
    if ((kind && im_punch_parse(kind, &o->punch.kind) != IM_OK) ||
        (law && im_adhesion_law_parse(law, &o->solver.adhesion_law) != IM_OK) ||
        (device && im_device_parse(device, &o->solver.device) != IM_OK) ||
        (backend && im_render_backend_from_name(backend, &chosen) != IM_OK)) {
        py_raise_status(IM_EINVAL);
        return -1;
    }
    o->backend = (int)chosen;
    return 0;
}

static int read_options(PyObject *dict, held_strings *h, im_indent_options *o)
{
    for (size_t i = 0; i < sizeof FIELDS / sizeof *FIELDS; ++i)
        if (read_field(dict, &FIELDS[i], o) < 0)
            return -1;
    if (read_names(dict, o) < 0 || read_strings(dict, h, o) < 0 || read_surface_options(dict, o) < 0)
        return -1;
    return read_axis(dict, o);
}

/* Runs without the GIL (Ctrl-C armed: interrupt.c); the callbacks' exception or the status raised. */
static PyObject *run(im_indent_options *o, py_callbacks *callbacks, PyObject *out)
{
    volatile sig_atomic_t stop = 0;
    callbacks->stop = &stop;
    o->stop = &stop;
    o->user = callbacks;
    o->log = callbacks->log != Py_None ? py_call_log : NULL;
    o->progress = callbacks->progress != Py_None ? py_call_progress : NULL;
    py_interrupt call;
    py_interrupt_arm(&call, &stop);
    int status;
    Py_BEGIN_ALLOW_THREADS status = im_indent_run(o);
    Py_END_ALLOW_THREADS int interrupted = py_interrupt_disarm(&call, &stop) < 0; /* KeyboardInterrupt set */
    int raised = py_callbacks_finish(callbacks, interrupted);
    if (interrupted || raised)
        return NULL;
    if (status != IM_OK)
        return py_raise_status(status);
    Py_INCREF(out);
    return out;
}

/* indent_run(options, targets, progress, log) -> options["out"] */
static PyObject *indent_run(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *dict, *targets_obj;
    py_callbacks callbacks = {0};
    if (!PyArg_ParseTuple(args, "O!OOO", &PyDict_Type, &dict, &targets_obj, &callbacks.progress, &callbacks.log))
        return NULL;
    PyArrayObject *targets = (PyArrayObject *)PyArray_FROMANY(targets_obj, NPY_DOUBLE, 1, 1, NPY_ARRAY_CARRAY_RO);
    if (!targets)
        return NULL;
    im_indent_options o = im_indent_options_default();
    o.targets = PyArray_DATA(targets);
    o.target_count = (int)PyArray_SIZE(targets);
    held_strings held = {0};
    PyObject *out = read_options(dict, &held, &o) < 0 ? NULL : run(&o, &callbacks, PyDict_GetItemString(dict, "out"));
    release(&held);
    Py_DECREF(targets);
    return out;
}

PyMethodDef py_indent_methods[] = {{"indent_run", indent_run, METH_VARARGS,
                                    "indent_run(options, targets, progress, log) -> the output folder"},
                                   {NULL, NULL, 0, NULL}};
