/* The module: its exceptions, one per library status, and the tables of the other files. */
#define IM_PY_DEFINES_NUMPY_API
#include "core.h"

#include "indentmap/field.h"
#include "indentmap/history.h"
#include "indentmap/info.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/version.h"

/* indentmap.Error and its subclasses, indexed by status (IM_EINVAL .. IM_EINTERRUPTED). */
static PyObject *base_error;
static PyObject *status_errors[IM_EINTERRUPTED + 1];

typedef struct error_kind {
    int status;
    const char *name;   /* indentmap.NAME */
    PyObject **builtin; /* the built-in exception it also derives from, or NULL */
    const char *doc;    /* what it means, for help() and docs/python-reference.md */
} error_kind;

static const error_kind error_kinds[] = {
    {IM_EINVAL, "InvalidArgument", &PyExc_ValueError,
     "An argument out of its range or of the wrong kind, named in the message (also a ValueError).\n\n"
     "Example: ``im.generate(0)`` raises it: 'n = 0: expected ...'."},
    {IM_EIO, "FileError", &PyExc_OSError,
     "A file that cannot be read or written, named in the message (also an OSError); nothing is left half "
     "written.\n\nExample: ``im.read('missing.npy')`` raises it."},
    {IM_EFORMAT, "FormatError", &PyExc_ValueError,
     "A file whose contents are not what its format says, with the file and the place (also a ValueError)."
     "\n\nExample: ``im.read('notes.txt')`` on a file that is no surface raises it."},
    {IM_ENOMEM, "OutOfMemory", &PyExc_MemoryError,
     "Work that would not fit in the memory available or the cap (``memory_limit``), refused before it starts, "
     "naming what and how much (also a MemoryError).\n\nExample: ``im.memory_limit(1 << 20); "
     "im.generate(4096)`` raises it."},
    {IM_ENUMERIC, "NumericError", &PyExc_ArithmeticError,
     "A value that is NaN or infinite where a finite one is needed, naming the first (also an ArithmeticError)."
     "\n\nExample: ``im.statistics(np.full((8, 8), np.nan))`` raises it."},
    {IM_ENOCONV, "NotConverged", NULL,
     "The solver did not reach its tolerance within ``max_iterations``; the message gives the residual.\n\n"
     "Example: ``im.indent(h, approaches=[2.0], max_iterations=1)`` raises it."},
    {IM_EEDGE, "EdgeContact", NULL,
     "The contact reached the edge of the grid: the surface is too small for the target (a larger surface or "
     "a smaller load).\n\nExample: ``im.indent(im.generate(32), approaches=[50.0])`` raises it."},
    {IM_EUNSUPPORTED, "Unsupported", NULL,
     "What this build or machine cannot do (no OpenGL 3.3 context, no GPU engine), with the reason.\n\n"
     "Example: ``im.indent(h, approaches=[1.0], device='gpu')`` raises it in a build without the GPU engine."},
    {IM_EINTERRUPTED, "Interrupted", NULL,
     "A call stopped by its stop flag or a callback; Ctrl-C raises KeyboardInterrupt instead.\n\n"
     "Example: a ``progress`` callback of ``run_scene`` that raises stops the run with its own exception."},
};

PyObject *py_raise_status(int status)
{
    PyObject *type = status > IM_OK && status <= IM_EINTERRUPTED && status_errors[status] ? status_errors[status]
                                                                                          : base_error;
    const char *message = im_last_error();
    PyObject *text = PyUnicode_DecodeUTF8(message, (Py_ssize_t)strlen(message), "backslashreplace");
    PyObject *error = text ? PyObject_CallOneArg(type, text) : NULL;
    PyObject *code = error ? PyLong_FromLong(status) : NULL;
    if (code && PyObject_SetAttrString(error, "status", code) == 0)
        PyErr_SetObject(type, error);
    Py_XDECREF(code);
    Py_XDECREF(error);
    Py_XDECREF(text);
    return NULL;
}

static int add_errors(PyObject *module)
{
    base_error = PyErr_NewExceptionWithDoc(
        "indentmap.Error",
        "An error reported by libindentmap: str() is its message, .status the library's status code.\n\n"
        "Example: ``try: im.read(path) except im.Error as e: print(e.status, e)``.",
        NULL, NULL);
    if (!base_error || PyModule_AddObjectRef(module, "Error", base_error) < 0)
        return -1;
    for (size_t i = 0; i < sizeof error_kinds / sizeof *error_kinds; ++i) {
        const error_kind *kind = &error_kinds[i];
        char qualified[64];
        snprintf(qualified, sizeof qualified, "indentmap.%s", kind->name);
        PyObject *bases = kind->builtin ? PyTuple_Pack(2, base_error, *kind->builtin) : PyTuple_Pack(1, base_error);
        if (!bases)
            return -1;
        PyObject *type = PyErr_NewExceptionWithDoc(qualified, kind->doc, bases, NULL);
        Py_DECREF(bases);
        if (!type || PyModule_AddObjectRef(module, kind->name, type) < 0)
            return -1;
        status_errors[kind->status] = type;
    }
    return 0;
}

static int add_methods(PyObject *module, PyMethodDef *methods) { return PyModule_AddFunctions(module, methods); }

/* memory_limit([bytes]) -> the cap in bytes (0: none); with an argument, sets it first (0 removes it). */
static PyObject *memory_limit(PyObject *self, PyObject *args)
{
    (void)self;
    long long bytes = -1;
    if (!PyArg_ParseTuple(args, "|L", &bytes))
        return NULL;
    if (PyTuple_GET_SIZE(args) == 1) {
        if (bytes < 0) {
            PyErr_Format(PyExc_ValueError, "memory limit %lld bytes: expected >= 0 (0: none)", bytes);
            return NULL;
        }
        im_memory_set_limit((size_t)bytes);
    }
    return PyLong_FromSize_t(im_memory_limit());
}

/* The text of a build report (info.h), made without the GIL; raises the library's error where the program
 * exits 1. */
static PyObject *report_text(int (*make)(void *argument, char **text), void *argument)
{
    char *text = NULL;
    int status;
    Py_BEGIN_ALLOW_THREADS status = make(argument, &text);
    Py_END_ALLOW_THREADS PyObject *out = status == IM_OK ? PyUnicode_FromString(text) : py_raise_status(status);
    free(text);
    return out;
}

static int make_info(void *backend, char **text) { return im_info_text(*(im_render_backend *)backend, text); }

static int make_formats(void *unused, char **text)
{
    (void)unused;
    return im_formats_text(text);
}

/* info_text(backend) -> `indentmap info`'s text for backend "auto", "egl" or "osmesa" */
static PyObject *info_text(PyObject *self, PyObject *args)
{
    (void)self;
    const char *name;
    im_render_backend backend;
    if (!PyArg_ParseTuple(args, "s", &name))
        return NULL;
    int status = im_render_backend_from_name(name, &backend);
    return status == IM_OK ? report_text(make_info, &backend) : py_raise_status(status);
}

/* formats_text() -> `indentmap formats`' text */
static PyObject *formats_text(PyObject *self, PyObject *unused)
{
    (void)self, (void)unused;
    return report_text(make_formats, NULL);
}

/* heights_array(obj, what) -> obj as the library takes a field: a 2-D float64 array (safe casts only), a
 * Topography refused naming what (arrays.c), for the Python code that works on a field before the library */
static PyObject *heights_array(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *obj;
    const char *what;
    if (!PyArg_ParseTuple(args, "Os", &obj, &what))
        return NULL;
    return (PyObject *)py_heights_array(obj, what);
}

static PyMethodDef core_methods[] = {
    {"heights_array", heights_array, METH_VARARGS, "heights_array(obj, what) -> a 2-D float64 array of obj"},
    {"memory_limit", memory_limit, METH_VARARGS, "memory_limit([bytes]) -> the cap in bytes (0: none)"},
    {"info_text", info_text, METH_VARARGS, "info_text(backend) -> indentmap info's text"},
    {"formats_text", formats_text, METH_NOARGS, "formats_text() -> indentmap formats' text"},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef module_definition = {PyModuleDef_HEAD_INIT,
                                               "indentmap._core",
                                               "The C extension over libindentmap; use the indentmap package "
                                               "instead.",
                                               -1,
                                               NULL,
                                               NULL,
                                               NULL,
                                               NULL,
                                               NULL};

PyMODINIT_FUNC PyInit__core(void)
{
    import_array();
    PyObject *module = PyModule_Create(&module_definition);
    if (!module)
        return NULL;
    if (py_interrupt_init() < 0 || py_render_init() < 0 || add_errors(module) < 0 ||
        add_methods(module, core_methods) < 0 || add_methods(module, py_surface_methods) < 0 ||
        add_methods(module, py_theory_methods) < 0 || add_methods(module, py_render_methods) < 0 ||
        add_methods(module, py_scene_methods) < 0 || add_methods(module, py_solver_methods) < 0 ||
        add_methods(module, py_indent_methods) < 0 || add_methods(module, py_history_methods) < 0 ||
        PyType_Ready(&py_indentation_type) < 0 ||
        PyModule_AddObjectRef(module, "Indentation", (PyObject *)&py_indentation_type) < 0 ||
        PyType_Ready(&py_plan_type) < 0 || PyModule_AddObjectRef(module, "Plan", (PyObject *)&py_plan_type) < 0 ||
        PyModule_AddStringConstant(module, "library_version", im_version()) < 0 ||
        PyModule_AddStringConstant(module, "history_columns", im_history_columns()) < 0 ||
        PyModule_AddStringConstant(module, "history_integer_columns", im_history_integer_columns()) < 0 ||
        PyModule_AddStringConstant(module, "header_version", IM_VERSION_STRING) < 0 ||
        PyModule_AddIntConstant(module, "field_max_side", IM_FIELD_MAX_SIDE) < 0 ||
        /* the one default tolerance of the library and its front ends (solver.h) */
        PyModule_AddObject(module, "default_tol", PyFloat_FromDouble(im_quality_default_tolerance())) < 0) {
        Py_DECREF(module);
        return NULL;
    }
    return module;
}
