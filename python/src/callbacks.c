/* A run's log lines and progress (status.h's callbacks) handed to Python callables, with the GIL taken
 * back for each call (core.h: py_callbacks). */
#include "core.h"

#include "indentmap/status.h"

#include <signal.h>

/* After a call that raised (GIL held): keeps the first exception and asks the run to stop. */
static void keep_error(py_callbacks *c)
{
    if (c->error_type) {
        PyErr_Clear();
        return;
    }
    PyErr_Fetch(&c->error_type, &c->error_value, &c->error_traceback);
    *c->stop = SIGINT; /* any non-zero value stops the run; its message is replaced by the exception */
}

void py_call_progress(void *user, const char *stage, int done, int total)
{
    py_callbacks *c = user;
    PyGILState_STATE gil = PyGILState_Ensure();
    PyObject *result = c->error_type ? NULL : PyObject_CallFunction(c->progress, "sii", stage, done, total);
    if (result)
        Py_DECREF(result);
    else if (!c->error_type)
        keep_error(c);
    PyGILState_Release(gil);
}

void py_call_log(void *user, im_log_level level, const char *message)
{
    py_callbacks *c = user;
    PyGILState_STATE gil = PyGILState_Ensure();
    PyObject *text = PyUnicode_DecodeUTF8(message, (Py_ssize_t)strlen(message), "backslashreplace");
    PyObject *result = c->error_type || !text
                           ? NULL
                           : PyObject_CallFunction(c->log, "iO", level == IM_LOG_WARNING ? 30 : 20, text);
    Py_XDECREF(text);
    if (result)
        Py_DECREF(result);
    else if (!c->error_type)
        keep_error(c);
    PyGILState_Release(gil);
}

int py_callbacks_finish(py_callbacks *c, int interrupted)
{
    const int raised = c->error_type != NULL;
    if (raised && !interrupted) {
        PyErr_Restore(c->error_type, c->error_value, c->error_traceback);
        return 1;
    }
    Py_XDECREF(c->error_type);
    Py_XDECREF(c->error_value);
    Py_XDECREF(c->error_traceback);
    return raised;
}
