/* Scenes: load and run a scene file (scene.h) without the GIL. */
#include "core.h"

#include "indentmap/scene.h"
#include "indentmap/status.h"

#include <signal.h>

static PyObject *run_scene(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *keywords[] = {"path", "resume", "quiet", NULL};
    PyObject *path_bytes;
    int resume = 0, quiet = 1;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O&|pp", keywords, PyUnicode_FSConverter, &path_bytes, &resume,
                                     &quiet))
        return NULL;
    im_scene *scene = PyMem_Calloc(1, sizeof *scene);
    if (!scene) {
        Py_DECREF(path_bytes);
        return PyErr_NoMemory();
    }
    im_scene_run_options options = {.resume = resume, .quiet = quiet};
    int status;
    Py_BEGIN_ALLOW_THREADS
    status = im_scene_load(PyBytes_AS_STRING(path_bytes), scene);
    if (status == IM_OK)
        status = im_scene_run(scene, &options);
    Py_END_ALLOW_THREADS
    Py_DECREF(path_bytes);
    PyObject *out = status == IM_OK ? PyUnicode_DecodeFSDefault(scene->output_dir) : py_raise_status(status);
    PyMem_Free(scene);
    return out;
}

PyMethodDef py_scene_methods[] = {
    {"run_scene", (PyCFunction)(void (*)(void))run_scene, METH_VARARGS | METH_KEYWORDS,
     "run_scene(path, resume=False, quiet=True) -> output folder"},
    {NULL, NULL, 0, NULL}};
