/* indentmap._core: the CPython extension over libindentmap. One file per library module
 * (surface.c, solver.c, theory.c, render.c), arrays.c for numpy <-> im_field, module.c for the
 * module and its exceptions. Every function raises the library's status as an indentmap.Error
 * subclass with the library's message; long computations release the GIL. */
#ifndef INDENTMAP_PY_CORE_H
#define INDENTMAP_PY_CORE_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>

#ifndef IM_PY_DEFINES_NUMPY_API /* module.c holds numpy's API table; the others refer to it */
#define NO_IMPORT_ARRAY
#endif
#define PY_ARRAY_UNIQUE_SYMBOL indentmap_numpy_api
#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#include <numpy/arrayobject.h>

#include "indentmap/field.h"
#include "indentmap/formats.h"
#include "indentmap/history.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <signal.h>

/* Sets the Python exception for a library status (with im_last_error()) and returns NULL. */
PyObject *py_raise_status(int status);

/* A C-contiguous, aligned float64 2-D view of obj: borrowed when obj already is one, else a
 * converted copy (any array-like castable to float64 without loss of kind: bool, ints, floats).
 * New reference; NULL with TypeError/ValueError set otherwise. `what` names the argument. */
PyArrayObject *py_heights_array(PyObject *obj, const char *what);

/* An im_field header over the array's memory (no copy; valid while the array lives). */
im_field py_field_view(PyArrayObject *array, double delta);

/* A new (ny, nx) float64 array owning field (freed with the array); field is consumed, also on
 * failure. */
PyObject *py_array_from_field(im_field *field);

/* A new 1-D float64 array copied from n doubles. */
PyObject *py_array_from_doubles(const double *values, npy_intp n);

/* Ctrl-C during a call without the GIL (interrupt.c). py_interrupt_arm (GIL held, before the call)
 * clears flag and, on the main thread where Python handles SIGINT, makes SIGINT also set flag (the
 * library's stop flag for the call); py_interrupt_disarm (GIL held, after it) restores Python's
 * handler and, if the signal came, lets Python act on it: -1 with KeyboardInterrupt (or what the
 * application's handler raised) set, else 0. A call made from a progress or log callback of an armed
 * call (nested) shares the installed handler: SIGINT then stops the inner call, whose
 * KeyboardInterrupt, raised in the callback, stops the outer one. py_interrupt_init (module import)
 * finds the main thread. */
typedef struct py_interrupt {
    int armed;                         /* this call installed the handler (the outermost call) */
    volatile sig_atomic_t *outer_flag; /* a call made from a callback of an armed call: the outer
                                           call's flag, armed again when this one returns */
} py_interrupt;
int py_interrupt_init(void);
void py_interrupt_arm(py_interrupt *call, volatile sig_atomic_t *flag);
int py_interrupt_disarm(py_interrupt *call, volatile sig_atomic_t *flag);

/* The Python side of a run's callbacks (callbacks.c), and the first exception one of them raised (which
 * stops the run at its next check: *stop is set). py_call_progress and py_call_log are status.h's
 * im_progress_fn and im_log_fn with a py_callbacks as user (log gets logging's levels, INFO or WARNING).
 * py_callbacks_finish (GIL held, after the run): 1 with the kept exception raised again (or, when
 * interrupted, dropped: KeyboardInterrupt is the one raised), 0 when no callback raised. */
typedef struct py_callbacks {
    PyObject *progress; /* callable(stage, done, total), or NULL */
    PyObject *log;      /* callable(level, message), or NULL */
    volatile sig_atomic_t *stop;
    PyObject *error_type, *error_value, *error_traceback;
} py_callbacks;
void py_call_progress(void *user, const char *stage, int done, int total);
void py_call_log(void *user, im_log_level level, const char *message);
int py_callbacks_finish(py_callbacks *c, int interrupted);

/* Makes the lock that lets one drawing call at a time run without the GIL (render.c; module import). */
int py_render_init(void);

/* A control's name ("displacement", "load", "mean_gap", solver.h) into *control; -1 with ValueError set
 * (solver.c). */
int py_control_from_name(const char *name, enum im_control *control);

/* Rows as a new (count, IM_HISTORY_COLUMN_COUNT) float64 array of their columns' numbers as history.csv
 * holds them (written by im_history_format and read back by im_history_parse: residual and seconds to 7
 * digits), and rows (*rows, freed by the caller) from such an array-like; -1 with the error set
 * (history.c). */
PyObject *py_history_values(const im_history_row *rows, int count);
int py_history_rows(PyObject *values, im_history_row **rows, int *count);

/* How a surface file is read, as `indent --channel --unit --height-unit --length-unit --fill
 * --resample-square --npy-order` take it, into those members of options (surface.c): the names UTF-8 ("" for the file's own), npy_order an
 * enum im_npy_order; -1 with ValueError naming the parameter (an unknown unit) or the status's error set. */
typedef struct py_read_names {
    const char *channel, *unit, *height_unit, *length_unit;
} py_read_names;
int py_surface_read_options(const py_read_names *names, int fill, int resample_square, int npy_order,
                            im_surface_read_options *options);
/* `--detrend` and `--align` by name (surface.c); -1 with the error set naming the parameter. */
int py_detrend_from_name(const char *name, enum im_detrend *detrend);
int py_align_from_name(const char *name, enum im_row_alignment *align);

/* Module tables, defined per file. */
extern PyMethodDef py_surface_methods[], py_theory_methods[], py_render_methods[], py_scene_methods[],
    py_solver_methods[], py_indent_methods[], py_history_methods[];
extern PyTypeObject py_indentation_type, py_plan_type;

#endif
