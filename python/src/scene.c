/* Scenes: load and run a scene file (scene.h) without the GIL; its log lines and progress go to
 * Python callables, called with the GIL taken back for each call. */
#include "core.h"

#include "indentmap/scene.h"
#include "indentmap/status.h"

#include <signal.h>

/* The Python side of a run's callbacks, and the first exception one of them raised (which stops
 * the run at its next check, and is raised by run_scene). */
typedef struct scene_callbacks {
    PyObject *progress;  /* callable(stage, done, total), or NULL */
    PyObject *log;       /* callable(level, message) with logging's levels (INFO, WARNING), or NULL */
    volatile sig_atomic_t *stop;
    PyObject *error_type, *error_value, *error_traceback;
} scene_callbacks;

/* After a call that raised (GIL held): keeps the first exception and asks the run to stop. */
static void keep_error(scene_callbacks *c)
{
    if (c->error_type) {
        PyErr_Clear();
        return;
    }
    PyErr_Fetch(&c->error_type, &c->error_value, &c->error_traceback);
    *c->stop = SIGINT; /* any non-zero value stops the run; its message is replaced by the exception */
}

static void call_progress(void *user, const char *stage, int done, int total)
{
    scene_callbacks *c = user;
    PyGILState_STATE gil = PyGILState_Ensure();
    PyObject *result = c->error_type ? NULL : PyObject_CallFunction(c->progress, "sii", stage, done, total);
    if (result)
        Py_DECREF(result);
    else if (!c->error_type)
        keep_error(c);
    PyGILState_Release(gil);
}

static void call_log(void *user, im_log_level level, const char *message)
{
    scene_callbacks *c = user;
    PyGILState_STATE gil = PyGILState_Ensure();
    PyObject *text = PyUnicode_DecodeUTF8(message, (Py_ssize_t)strlen(message), "backslashreplace");
    PyObject *result = c->error_type || !text ? NULL
                       : PyObject_CallFunction(c->log, "iO", level == IM_LOG_WARNING ? 30 : 20, text);
    Py_XDECREF(text);
    if (result)
        Py_DECREF(result);
    else if (!c->error_type)
        keep_error(c);
    PyGILState_Release(gil);
}

/* Loads and runs the scene without the GIL (Ctrl-C armed: interrupt.c); IM_OK or a status. */
static int load_and_run(const char *path, im_scene *scene, const im_scene_run_options *options,
                        volatile sig_atomic_t *stop, py_interrupt *call)
{
    int status;
    py_interrupt_arm(call, stop);
    Py_BEGIN_ALLOW_THREADS
    status = im_scene_load(path, scene);
    if (status == IM_OK)
        status = im_scene_run(scene, options);
    Py_END_ALLOW_THREADS
    return status;
}

static PyObject *run_scene(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *keywords[] = {"path", "resume", "quiet", "progress", "log", NULL};
    PyObject *path_bytes, *progress = Py_None, *log = Py_None;
    int resume = 0, quiet = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O&|ppOO", keywords, PyUnicode_FSConverter, &path_bytes, &resume,
                                     &quiet, &progress, &log))
        return NULL;
    im_scene *scene = PyMem_Calloc(1, sizeof *scene);
    if (!scene) {
        Py_DECREF(path_bytes);
        return PyErr_NoMemory();
    }
    volatile sig_atomic_t stop = 0;
    scene_callbacks callbacks = {.progress = progress, .log = log, .stop = &stop};
    im_scene_run_options options = {.resume = resume, .quiet = quiet, .stop = &stop, .user = &callbacks,
                                     .progress = progress != Py_None ? call_progress : NULL,
                                     .log = log != Py_None ? call_log : NULL};
    py_interrupt call;
    int status = load_and_run(PyBytes_AS_STRING(path_bytes), scene, &options, &stop, &call);
    Py_DECREF(path_bytes);
    int interrupted = py_interrupt_disarm(&call, &stop) < 0; /* KeyboardInterrupt is set */
    if (callbacks.error_type && !interrupted)
        PyErr_Restore(callbacks.error_type, callbacks.error_value, callbacks.error_traceback);
    else {
        Py_XDECREF(callbacks.error_type);
        Py_XDECREF(callbacks.error_value);
        Py_XDECREF(callbacks.error_traceback);
    }
    PyObject *out = interrupted || callbacks.error_type ? NULL
                    : status == IM_OK                     ? PyUnicode_DecodeFSDefault(scene->output_dir)
                                                          : py_raise_status(status);
    PyMem_Free(scene);
    return out;
}

PyMethodDef py_scene_methods[] = {
    {"run_scene", (PyCFunction)(void (*)(void))run_scene, METH_VARARGS | METH_KEYWORDS,
     "run_scene(path, resume=False, quiet=False, progress=None, log=None) -> output folder"},
    {NULL, NULL, 0, NULL}};
