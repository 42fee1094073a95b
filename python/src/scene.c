/* Scenes: load and run a scene file (scene.h) without the GIL; its log lines and progress go to
 * Python callables, called with the GIL taken back for each call (callbacks.c). */
#include "core.h"

#include "indentmap/render.h"
#include "indentmap/scene.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"

#include <signal.h>
#include <stdlib.h>

/* Where a scene comes from (a scene file, or a run's record: from_record) and where it writes (out,
 * NULL for its own output folder). */
typedef struct scene_source {
    const char *path, *out;
    int from_record;
    const char *wisdom; /* the FFTW wisdom file of its solves, NULL for none */
} scene_source;

/* The scene of a file or a record into *scene (NULL on an error); out replaces its output folder. */
static int load_scene(const scene_source *source, im_scene **scene)
{
    int status = source->from_record ? im_scene_load_record(source->path, scene) : im_scene_load(source->path, scene);
    if (status == IM_OK && source->wisdom) {
        im_scene_set_wisdom_path(*scene, source->wisdom);
        im_solver_options check = {.wisdom_path = source->wisdom};
        status = im_solver_wisdom_check(&check);
        if (status != IM_OK)
            im_fail_context(status, "wisdom");
    }
    if (status != IM_OK || !source->out)
        return status;
    status = im_scene_set_output_dir(*scene, source->out);
    return status == IM_OK ? IM_OK : im_fail_context(status, "out");
}

/* Loads and runs the scene without the GIL (Ctrl-C armed: interrupt.c); IM_OK or a status. The caller
 * frees *scene. */
static int load_and_run(const scene_source *source, im_scene **scene, const im_scene_run_options *options,
                        volatile sig_atomic_t *stop, py_interrupt *call)
{
    int status;
    py_interrupt_arm(call, stop);
    Py_BEGIN_ALLOW_THREADS status = load_scene(source, scene);
    if (status == IM_OK)
        status = im_scene_run(*scene, options);
    Py_END_ALLOW_THREADS return status;
}

/* PyArg's converter of an optional path: None leaves *out NULL, else PyUnicode_FSConverter's bytes. */
static int optional_path(PyObject *object, void *out)
{
    if (object == Py_None)
        return 1;
    return PyUnicode_FSConverter(object, out);
}

static PyObject *run_scene(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *keywords[] = {"path", "resume",      "quiet",  "progress", "log",
                               "out",  "from_record", "wisdom", "backend",  NULL};
    PyObject *path_bytes, *progress = Py_None, *log = Py_None, *out_bytes = NULL, *wisdom_bytes = NULL;
    int resume = 0, quiet = 0, from_record = 0;
    const char *backend_name = "auto";
    im_render_backend backend;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O&|ppOOO&pO&s", keywords, PyUnicode_FSConverter, &path_bytes,
                                     &resume, &quiet, &progress, &log, optional_path, &out_bytes, &from_record,
                                     optional_path, &wisdom_bytes, &backend_name))
        return NULL;
    if (im_render_backend_from_name(backend_name, &backend) != IM_OK) {
        Py_DECREF(path_bytes);
        Py_XDECREF(out_bytes);
        Py_XDECREF(wisdom_bytes);
        return py_raise_status(IM_EINVAL);
    }
    volatile sig_atomic_t stop = 0;
    py_callbacks callbacks = {.progress = progress, .log = log, .stop = &stop};
    im_scene_run_options options = {.resume = resume,
                                    .quiet = quiet,
                                    .stop = &stop,
                                    .user = &callbacks,
                                    .progress = progress != Py_None ? py_call_progress : NULL,
                                    .log = log != Py_None ? py_call_log : NULL,
                                    .backend = (int)backend};
    py_interrupt call;
    scene_source source = {PyBytes_AS_STRING(path_bytes), out_bytes ? PyBytes_AS_STRING(out_bytes) : NULL,
                           from_record, wisdom_bytes ? PyBytes_AS_STRING(wisdom_bytes) : NULL};
    im_scene *scene = NULL;
    int status = load_and_run(&source, &scene, &options, &stop, &call);
    Py_DECREF(path_bytes);
    Py_XDECREF(out_bytes);
    Py_XDECREF(wisdom_bytes);
    int interrupted = py_interrupt_disarm(&call, &stop) < 0; /* KeyboardInterrupt is set */
    int raised = py_callbacks_finish(&callbacks, interrupted);
    PyObject *out = interrupted || raised ? NULL
                    : status == IM_OK     ? PyUnicode_DecodeFSDefault(im_scene_output_dir(scene))
                                          : py_raise_status(status);
    im_scene_free(scene);
    return out;
}

/* Loads and checks the scene without the GIL (scene.h: im_scene_check, one process); the report into
 * *report (the caller frees it). The caller frees *scene. */
static int load_and_check(const scene_source *source, im_scene **scene, const im_scene_run_options *options,
                          char **report)
{
    int status;
    Py_BEGIN_ALLOW_THREADS status = load_scene(source, scene);
    if (status == IM_OK)
        status = im_scene_check(*scene, options, 1, report);
    Py_END_ALLOW_THREADS return status;
}

static PyObject *check_scene(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *keywords[] = {"path", "log", "out", "from_record", "wisdom", NULL};
    PyObject *path_bytes, *log = Py_None, *out_bytes = NULL, *wisdom_bytes = NULL;
    int from_record = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O&|OO&pO&", keywords, PyUnicode_FSConverter, &path_bytes, &log,
                                     optional_path, &out_bytes, &from_record, optional_path, &wisdom_bytes))
        return NULL;
    volatile sig_atomic_t stop = 0; /* set by a log callback that raised: its exception is kept */
    py_callbacks callbacks = {.log = log, .stop = &stop};
    im_scene_run_options options = {.stop = &stop, .user = &callbacks, .log = log != Py_None ? py_call_log : NULL};
    scene_source source = {PyBytes_AS_STRING(path_bytes), out_bytes ? PyBytes_AS_STRING(out_bytes) : NULL,
                           from_record, wisdom_bytes ? PyBytes_AS_STRING(wisdom_bytes) : NULL};
    im_scene *scene = NULL;
    char *report = NULL;
    int status = load_and_check(&source, &scene, &options, &report);
    Py_DECREF(path_bytes);
    Py_XDECREF(out_bytes);
    Py_XDECREF(wisdom_bytes);
    int raised = py_callbacks_finish(&callbacks, 0);
    PyObject *out = raised ? NULL : status == IM_OK ? PyUnicode_DecodeFSDefault(report) : py_raise_status(status);
    free(report);
    im_scene_free(scene);
    return out;
}

PyMethodDef py_scene_methods[] = {{"run_scene", (PyCFunction)(void (*)(void))run_scene, METH_VARARGS | METH_KEYWORDS,
                                   "run_scene(path, resume=False, quiet=False, progress=None, log=None, out=None, "
                                   "from_record=False, "
                                   "wisdom=None, backend='auto') -> output folder"},
                                  {"check_scene", (PyCFunction)(void (*)(void))check_scene,
                                   METH_VARARGS | METH_KEYWORDS,
                                   "check_scene(path, log=None, out=None, from_record=False, wisdom=None) -> report"},
                                  {NULL, NULL, 0, NULL}};
