/* indentmap._core.Indentation: an indentation history on one surface (im_indentation of
 * solver.h): created once (plan, window), stepped many times with warm starts; and
 * indentmap._core.Plan: the bare solver on a grid (im_solver_plan), for gaps of the caller's own. */
#include "core.h"

#include "indentmap/history.h"
#include "indentmap/indenter.h"
#include "indentmap/measure.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

typedef struct py_indentation {
    PyObject_HEAD im_indentation *run;
    im_profile *profile; /* a profile punch's shape: the run borrows it, so it is freed after the run */
    /* the history of the steps solved, measured as every front end does (history.h) */
    im_indenter punch;
    im_theory_interface rough; /* the surface's spectral h'rms and E*, as `indent`'s theory columns */
    int periodic;              /* no half-space theory beside a periodic cell */
    double tol;                /* the solver's tolerance (the history's area_ratio: im_history_measure) */
    double gap_scale;          /* the distributions' gap unit: the surface's h_rms (delta when flat) */
    char wisdom[4096];         /* the FFTW wisdom file the plan reads and updates ("": none) */
    im_history_row *rows;
    int row_count, row_capacity;
    int busy; /* a call (creation, step, fields) runs without the GIL: no second thread may enter it */
    volatile sig_atomic_t stop; /* the solver's stop flag (interrupt.c): set by Ctrl-C during a step */
} py_indentation;

/* A profile punch's shape from a numpy array (copied by the library): an (n, 2) array of rows (r, z)
 * is an axisymmetric table; any other 2-D array a height field on the surface's spacing delta. */
static int profile_from_array(PyObject *obj, double delta, im_profile **out)
{
    PyArrayObject *array = py_heights_array(obj, "profile");
    if (!array)
        return -1;
    npy_intp *shape = PyArray_DIMS(array);
    const double *data = PyArray_DATA(array);
    int status = IM_OK;
    if (shape[1] == 2) {
        double *r = malloc(sizeof(double) * (size_t)shape[0]), *z = malloc(sizeof(double) * (size_t)shape[0]);
        if (!r || !z)
            status = im_fail(IM_ENOMEM, "profile of %ld samples", (long)shape[0]);
        for (npy_intp i = 0; r && z && i < shape[0]; ++i) {
            r[i] = data[2 * i];
            z[i] = data[2 * i + 1];
        }
        if (r && z)
            status = im_profile_axisymmetric(r, z, (int)shape[0], out);
        free(r);
        free(z);
    } else {
        im_field view = py_field_view(array, delta);
        status = im_profile_field(&view, out);
    }
    Py_DECREF(array);
    if (status != IM_OK) {
        py_raise_status(status);
        return -1;
    }
    return 0;
}

static int punch_from_arguments(const char *kind, double alpha, double radius, PyObject *x, PyObject *y,
                                const im_profile *profile, im_indenter *punch)
{
    if (strcmp(kind, "profile") == 0)
        *punch = im_indenter_from_profile(profile);
    else if (strcmp(kind, "cone") == 0)
        *punch = im_indenter_cone(alpha);
    else if (strcmp(kind, "sphere") == 0)
        *punch = im_indenter_sphere(radius);
    else if (strcmp(kind, "flat") == 0)
        *punch = im_indenter_flat(radius);
    else {
        PyErr_Format(PyExc_ValueError, "punch '%s': expected 'cone', 'sphere', 'flat' or 'profile'", kind);
        return -1;
    }
    if (x != Py_None || y != Py_None) {
        if (x == Py_None || y == Py_None) {
            PyErr_SetString(PyExc_ValueError, "axis: give both x and y, or neither (the centre of the grid)");
            return -1;
        }
        punch->centred = 0;
        punch->x0 = PyFloat_AsDouble(x);
        punch->y0 = PyFloat_AsDouble(y);
        if (PyErr_Occurred())
            return -1;
    }
    return 0;
}

int py_control_from_name(const char *name, enum im_control *control)
{
    if (strcmp(name, "displacement") == 0)
        *control = IM_CONTROL_DISPLACEMENT;
    else if (strcmp(name, "load") == 0)
        *control = IM_CONTROL_LOAD;
    else if (strcmp(name, "mean_gap") == 0)
        *control = IM_CONTROL_MEAN_GAP;
    else {
        PyErr_Format(PyExc_ValueError, "control '%s': expected 'displacement', 'load' or 'mean_gap'", name);
        return -1;
    }
    return 0;
}

static int check_idle(py_indentation *self);

/* The wisdom file (bytes, or NULL for none) into self->wisdom and options, checked as `indent --wisdom`
 * checks it before planning (solver.h: im_solver_wisdom_check); -1 with the error set. */
static int set_wisdom(py_indentation *self, PyObject *wisdom, im_solver_options *o)
{
    const char *path = wisdom ? PyBytes_AS_STRING(wisdom) : "";
    if (strlen(path) >= sizeof self->wisdom) {
        PyErr_Format(PyExc_ValueError, "wisdom: a path of %zu bytes, expected fewer than %zu", strlen(path),
                     sizeof self->wisdom);
        return -1;
    }
    snprintf(self->wisdom, sizeof self->wisdom, "%s", path);
    o->wisdom_path = self->wisdom[0] ? self->wisdom : NULL;
    int status = im_solver_wisdom_check(o);
    if (status != IM_OK) {
        py_raise_status(im_fail_context(status, "wisdom %s", path));
        return -1;
    }
    return 0;
}

/* The surface's h_rms, the unit of `indent --distributions`' gaps (its delta when the surface is flat). */
static int gap_scale(const im_field *surface, double *scale)
{
    im_surface_stats stats;
    int status = im_surface_statistics(surface, &stats);
    if (status == IM_OK)
        *scale = stats.height_rms > 0.0 ? stats.height_rms : surface->delta;
    return status;
}

/* What _core.Indentation and _core.indentation_window take, parsed and checked: the heights (a new
 * reference), the punch (with its profile, owned until handed to a run), the control, the largest
 * target, the solver's options and the theory's slope definition. */
typedef struct indentation_arguments {
    PyArrayObject *heights;
    double delta, largest;
    im_profile *profile;
    im_indenter punch;
    enum im_control control;
    im_solver_options options;
    enum im_slope_definition slope_definition;
} indentation_arguments;

static void release_arguments(indentation_arguments *a)
{
    Py_CLEAR(a->heights);
    im_profile_free(a->profile);
    a->profile = NULL;
}

/* The options that are names, into *o and a->slope_definition; -1 with ValueError set. */
static int parse_named_options(const char *law, const char *slope_name, const char *device, indentation_arguments *a)
{
    im_solver_options *o = &a->options;
    if (im_adhesion_law_parse(law, &o->adhesion_law) != IM_OK) {
        PyErr_Format(PyExc_ValueError, "adhesion_law '%s': expected 'maugis-dugdale' or 'exponential'", law);
        return -1;
    }
    /* the theory's h'rms (as indent --slope-definition): spectral for a periodic cell, else forward
     * differences (an array may be measured: its edges would count in the spectrum) */
    a->slope_definition = o->periodic ? IM_SLOPE_SPECTRAL : IM_SLOPE_FINITE_DIFFERENCE;
    if (strcmp(slope_name, "spectral") == 0 || strcmp(slope_name, "fd") == 0)
        a->slope_definition = slope_name[0] == 's' ? IM_SLOPE_SPECTRAL : IM_SLOPE_FINITE_DIFFERENCE;
    else if (slope_name[0]) {
        PyErr_Format(PyExc_ValueError, "slope_definition '%s': expected 'spectral' or 'fd'", slope_name);
        return -1;
    }
    if (im_device_parse(device, &o->device) != IM_OK) {
        PyErr_Format(PyExc_ValueError, "device '%s': expected 'cpu', 'gpu' or 'auto'", device);
        return -1;
    }
    return 0;
}

/* *wisdom: the wisdom file's path (bytes, a new reference) or NULL; -1 with the error set (nothing held). */
static int parse_arguments(PyObject *args, PyObject *kwargs, indentation_arguments *a, PyObject **wisdom)
{
    static char *keywords[] = {"heights",
                               "delta",
                               "punch",
                               "alpha",
                               "radius",
                               "control",
                               "largest",
                               "e_star",
                               "tol",
                               "max_iterations",
                               "crop",
                               "window_margin",
                               "x",
                               "y",
                               "profile",
                               "device",
                               "hardness",
                               "periodic",
                               "slope_definition",
                               "adhesion_work",
                               "adhesion_range",
                               "plain_pk",
                               "measure",
                               "wisdom",
                               "adhesion_law",
                               "adhesion_zone",
                               NULL};
    PyObject *obj, *x = Py_None, *y = Py_None, *profile_obj = Py_None;
    int plain_pk = 0;
    double alpha, radius;
    const char *kind, *control_name, *device = "cpu", *slope_name = "", *law = "maugis-dugdale";
    *a = (indentation_arguments){.options = im_solver_options_default()};
    im_solver_options *o = &a->options;
    *wisdom = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "Odsddsd|ddipiOOOsdpsddppO&sd", keywords, &obj, &a->delta, &kind,
                                     &alpha, &radius, &control_name, &a->largest, &o->e_star, &o->tol,
                                     &o->max_iterations, &o->crop, &o->window_margin, &x, &y, &profile_obj, &device,
                                     &o->hardness, &o->periodic, &slope_name, &o->adhesion_work, &o->adhesion_range,
                                     &plain_pk, &o->fft_measure, PyUnicode_FSConverter, wisdom, &law,
                                     &o->adhesion_zone))
        return -1;
    o->cascade = o->precondition = !plain_pk; /* indent --plain-pk */
    int ok = parse_named_options(law, slope_name, device, a);
    if (ok == 0 && (strcmp(kind, "profile") == 0) != (profile_obj != Py_None)) {
        PyErr_SetString(PyExc_ValueError, "punch 'profile' and a profile array go together");
        ok = -1;
    }
    if (ok == 0 &&
        ((profile_obj != Py_None && profile_from_array(profile_obj, a->delta, &a->profile) < 0) ||
         punch_from_arguments(kind, alpha, radius, x, y, a->profile, &a->punch) < 0 ||
         py_control_from_name(control_name, &a->control) < 0 || !(a->heights = py_heights_array(obj, "heights"))))
        ok = -1;
    if (ok < 0) {
        release_arguments(a);
        Py_CLEAR(*wisdom);
    }
    return ok;
}

static int indentation_init(py_indentation *self, PyObject *args, PyObject *kwargs)
{
    indentation_arguments a;
    PyObject *wisdom;
    if (parse_arguments(args, kwargs, &a, &wisdom) < 0)
        return -1;
    int ready = check_idle(self) < 0 ? -1 : set_wisdom(self, wisdom, &a.options); /* a running step reads it */
    Py_XDECREF(wisdom);
    if (ready < 0) {
        release_arguments(&a);
        return -1;
    }
    a.options.stop = &self->stop;
    im_field surface = py_field_view(a.heights, a.delta);
    im_indentation_free(self->run);
    self->run = NULL;
    im_profile_free(self->profile); /* after the run that borrowed it */
    self->profile = a.profile;
    a.profile = NULL;
    self->row_count = 0;
    int status;
    double slope = 0;
    self->busy = 1;
    Py_BEGIN_ALLOW_THREADS /* planning: the library serialises FFTW's planner itself */
        status = im_indentation_create(&surface, &a.punch, a.control, a.largest, &a.options, &self->run);
    if (status == IM_OK)
        status = im_surface_slope_rms(&surface, a.slope_definition, &slope);
    if (status == IM_OK)
        status = gap_scale(&surface, &self->gap_scale);
    Py_END_ALLOW_THREADS self->busy = 0;
    if (status == IM_OK) {
        self->punch = a.punch;
        self->rough = im_theory_interface_default(slope);
        self->rough.e_star = a.options.e_star;
        self->periodic = a.options.periodic;
        self->tol = a.options.tol;
    }
    release_arguments(&a);
    if (status != IM_OK) {
        py_raise_status(status);
        return -1;
    }
    return 0;
}

static void indentation_dealloc(py_indentation *self)
{
    free(self->rows);
    im_indentation_free(self->run);
    im_profile_free(self->profile); /* after the run that borrowed it */
    Py_TYPE(self)->tp_free((PyObject *)self);
}

static int check_idle(py_indentation *self)
{
    if (self->busy) {
        PyErr_SetString(PyExc_RuntimeError, "Indentation: a call on this history is running in another thread");
        return -1;
    }
    return 0;
}

static int check_ready(py_indentation *self)
{
    if (!self->run) {
        PyErr_SetString(PyExc_RuntimeError, "Indentation: not initialised");
        return -1;
    }
    return check_idle(self);
}

static PyObject *step_dict(const im_step_result *r)
{
    return Py_BuildValue("{s:d,s:d,s:d,s:l,s:d,s:d,s:d,s:i,s:i,s:i,s:d,s:d,s:l,s:d,s:d,s:d,s:d,s:l,s:l,s:d}",
                         "approach", r->approach, "load", r->load, "load_star", r->load_star, "contact_patches",
                         r->contact_patches, "area_ratio", r->area_ratio, "mean_pressure", r->mean_pressure,
                         "max_pressure", r->max_pressure, "iterations", r->iterations, "coarse_iterations",
                         r->coarse_iterations, "convolutions", r->convolutions, "residual", r->residual, "seconds",
                         r->seconds, "yielding_patches", r->yielding_patches, "plastic_depth", r->plastic_depth,
                         "plastic_work", r->plastic_work, "residual_approach", r->residual_approach, "tensile_force",
                         r->tensile_force, "adhesive_patches", r->adhesive_patches, "repulsive_patches",
                         r->repulsive_patches, "mean_gap", r->mean_gap);
}

/* The solved step as the next row of the history, measured as `indent` measures it (history.h). */
static int record_row(py_indentation *self, const im_step_result *result)
{
    if (self->row_count == self->row_capacity) {
        int capacity = self->row_capacity ? 2 * self->row_capacity : 16;
        im_history_row *rows = realloc(self->rows, sizeof *rows * (size_t)capacity);
        if (!rows)
            return im_fail(IM_ENOMEM, "history of %d steps", capacity);
        self->rows = rows;
        self->row_capacity = capacity;
    }
    self->rows[self->row_count].result = *result;
    int status = im_history_measure(&self->punch, self->periodic ? NULL : &self->rough, self->run, self->tol,
                                    self->rows, self->row_count);
    self->row_count += status == IM_OK;
    return status;
}

/* The history of the steps solved as an array of its columns' numbers (history.c). */
static PyObject *indentation_history_values(py_indentation *self, PyObject *unused)
{
    (void)unused;
    return check_ready(self) < 0 ? NULL : py_history_values(self->rows, self->row_count);
}

static PyObject *indentation_step(py_indentation *self, PyObject *arg)
{
    double target = PyFloat_AsDouble(arg);
    if (PyErr_Occurred() || check_ready(self) < 0)
        return NULL;
    im_step_result result;
    int status;
    py_interrupt call;
    self->busy = 1;
    py_interrupt_arm(&call, &self->stop);
    Py_BEGIN_ALLOW_THREADS status = im_indentation_step(self->run, target, &result);
    Py_END_ALLOW_THREADS self->busy = 0;
    if (py_interrupt_disarm(&call, &self->stop) < 0)
        return NULL;
    if (status == IM_OK)
        status = record_row(self, &result);
    return status == IM_OK ? step_dict(&result) : py_raise_status(status);
}

static PyObject *indentation_fields(py_indentation *self, PyObject *unused)
{
    (void)unused;
    if (check_ready(self) < 0)
        return NULL;
    im_field *force = NULL, *gap = NULL, *displacement = NULL;
    int status;
    self->busy = 1;
    Py_BEGIN_ALLOW_THREADS /* a convolution on the full grid, planned under the library's planner lock */
        status = im_indentation_fields_full(self->run, &force, &gap, &displacement);
    Py_END_ALLOW_THREADS self->busy = 0;
    if (status != IM_OK)
        return py_raise_status(status);
    return Py_BuildValue("(NNN)", py_array_from_field(force), py_array_from_field(gap),
                         py_array_from_field(displacement));
}

static PyObject *indentation_plastic(py_indentation *self, PyObject *unused)
{
    (void)unused;
    if (check_ready(self) < 0)
        return NULL;
    im_field *plastic = NULL;
    int status = im_indentation_plastic(self->run, &plastic);
    return status == IM_OK ? py_array_from_field(plastic) : py_raise_status(status);
}

/* The last step's distributions, as `indent --distributions` writes them (measure.h). */
static int write_distributions(py_indentation *self, const char *prefix)
{
    im_field *force = NULL, *gap = NULL;
    int status = im_indentation_fields_full(self->run, &force, &gap, NULL);
    if (status == IM_OK)
        status = im_measure_write_distributions(force, gap, self->gap_scale, IM_MEASURE_GAP_BINS, prefix);
    im_field_free(force);
    im_field_free(gap);
    return status;
}

/* write_distributions(prefix): the last step's gap and patch-size distributions into
 * PREFIX_{gaps,patches,patch_list}.csv */
static PyObject *indentation_write_distributions(py_indentation *self, PyObject *arg)
{
    if (check_ready(self) < 0)
        return NULL;
    if (self->row_count == 0)
        return py_raise_status(im_fail(IM_EINVAL, "write_distributions: no step solved yet"));
    PyObject *prefix = NULL;
    if (!PyUnicode_FSConverter(arg, &prefix))
        return NULL;
    int status;
    self->busy = 1;
    Py_BEGIN_ALLOW_THREADS /* the full grid's fields: one convolution */
        status = write_distributions(self, PyBytes_AS_STRING(prefix));
    Py_END_ALLOW_THREADS self->busy = 0;
    Py_DECREF(prefix);
    return status == IM_OK ? Py_NewRef(Py_None) : py_raise_status(status);
}

static PyObject *indentation_window(py_indentation *self, void *closure)
{
    (void)closure;
    if (check_ready(self) < 0)
        return NULL;
    im_window w = im_indentation_window(self->run);
    return Py_BuildValue("(iiii)", w.x0, w.y0, w.nx, w.ny);
}

/* A solve's memory (solver.h: im_solver_memory) as the dict solver_memory() returns. */
static PyObject *memory_dict(const im_solver_memory *m)
{
    return Py_BuildValue("{s:O,s:d,s:d,s:d,s:s,s:s}", "gpu", m->gpu ? Py_True : Py_False, "host_bytes", m->host_bytes,
                         "device_bytes", m->device_bytes, "device_memory", m->device_memory, "device", m->device,
                         "note", m->note);
}

/* The memory of a plan as made (solver.h: im_solver_plan_memory), as a dict. The estimate may open the
 * engine's device: without the GIL, the owner marked *busy meanwhile (no thread may free the plan). */
static PyObject *plan_memory_dict(const im_solver_plan *plan, int *busy)
{
    im_solver_memory m;
    int status;
    *busy = 1;
    Py_BEGIN_ALLOW_THREADS status = im_solver_plan_memory(plan, &m);
    Py_END_ALLOW_THREADS *busy = 0;
    return status == IM_OK ? memory_dict(&m) : py_raise_status(status);
}

static PyObject *indentation_memory(py_indentation *self, PyObject *unused)
{
    (void)unused;
    return check_ready(self) < 0 ? NULL : plan_memory_dict(im_indentation_plan(self->run), &self->busy);
}

static PyMethodDef indentation_methods[] = {
    {"step", (PyCFunction)indentation_step, METH_O, "step(target) -> dict: solve the next step"},
    {"fields", (PyCFunction)indentation_fields, METH_NOARGS,
     "fields() -> (force, gap, displacement) of the last step on the full grid"},
    {"plastic", (PyCFunction)indentation_plastic, METH_NOARGS,
     "plastic() -> the plastic depth accumulated so far on the full grid"},
    {"history_values", (PyCFunction)indentation_history_values, METH_NOARGS,
     "history_values() -> the steps solved as an array of the history's columns' numbers"},
    {"write_distributions", (PyCFunction)indentation_write_distributions, METH_O,
     "write_distributions(prefix): the last step's PREFIX_{gaps,patches,patch_list}.csv"},
    {"memory", (PyCFunction)indentation_memory, METH_NOARGS,
     "memory() -> dict: the memory of the run's plan as made (its window and options)"},
    {NULL, NULL, 0, NULL}};

static PyGetSetDef indentation_getset[] = {{"window", (getter)indentation_window, NULL,
                                            "(x0, y0, nx, ny) of the solved sub-grid", NULL},
                                           {NULL, NULL, NULL, NULL, NULL}};

/* ---- Plan ---- */
typedef struct py_plan {
    PyObject_HEAD im_solver_plan *plan;
    int nx, ny, busy;
    volatile sig_atomic_t stop; /* the solver's stop flag (interrupt.c): set by Ctrl-C during a solve */
} py_plan;

static int plan_init(py_plan *self, PyObject *args, PyObject *kwargs)
{
    static char *keywords[] = {"nx", "ny", "delta", "e_star", "tol", "max_iterations", "device", NULL};
    im_solver_options o = im_solver_options_default();
    double delta = 1.0;
    int nx, ny;
    const char *device = "cpu";
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "ii|dddis", keywords, &nx, &ny, &delta, &o.e_star, &o.tol,
                                     &o.max_iterations, &device))
        return -1;
    if (im_device_parse(device, &o.device) != IM_OK) {
        PyErr_Format(PyExc_ValueError, "device '%s': expected 'cpu', 'gpu' or 'auto'", device);
        return -1;
    }
    if (self->busy) {
        PyErr_SetString(PyExc_RuntimeError, "Plan: a solve on this plan is running in another thread");
        return -1;
    }
    o.stop = &self->stop;
    im_solver_plan *plan = NULL;
    int status;
    self->busy = 1;
    Py_BEGIN_ALLOW_THREADS /* the library serialises FFTW's planner itself */
        status = im_solver_plan_create(nx, ny, delta, &o, &plan);
    Py_END_ALLOW_THREADS self->busy = 0;
    if (status != IM_OK) {
        py_raise_status(status);
        return -1;
    }
    im_solver_plan_free(self->plan); /* only now: a failed re-initialisation keeps the plan it had */
    self->plan = plan;
    self->nx = nx;
    self->ny = ny;
    return 0;
}

static void plan_dealloc(py_plan *self)
{
    im_solver_plan_free(self->plan);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

static PyObject *solve_dict(const im_solve_result *r)
{
    return Py_BuildValue("{s:d,s:d,s:l,s:d,s:d,s:i,s:i,s:i,s:d,s:d}", "approach", r->approach, "load", r->load,
                         "contact_patches", r->contact_patches, "mean_pressure", r->mean_pressure, "max_pressure",
                         r->max_pressure, "iterations", r->iterations, "coarse_iterations", r->coarse_iterations,
                         "convolutions", r->convolutions, "residual", r->residual, "seconds", r->seconds);
}

/* A new (ny, nx) float64 array: a copy of obj (checked against the plan's grid), or zeros. */
static PyArrayObject *grid_array(py_plan *self, PyObject *obj, const char *what)
{
    npy_intp shape[2] = {self->ny, self->nx};
    if (obj == Py_None)
        return (PyArrayObject *)PyArray_ZEROS(2, shape, NPY_DOUBLE, 0);
    PyArrayObject *given = py_heights_array(obj, what);
    if (given && (PyArray_DIMS(given)[0] != self->ny || PyArray_DIMS(given)[1] != self->nx)) {
        PyErr_Format(PyExc_ValueError, "%s: shape (%ld, %ld), the plan's grid is (%d, %d)", what,
                     (long)PyArray_DIMS(given)[0], (long)PyArray_DIMS(given)[1], self->ny, self->nx);
        Py_CLEAR(given);
    }
    PyArrayObject *copy = given ? (PyArrayObject *)PyArray_NewCopy(given, NPY_CORDER) : NULL;
    Py_XDECREF(given);
    return copy;
}

static PyObject *plan_solve(py_plan *self, PyObject *args, PyObject *kwargs)
{
    static char *keywords[] = {"gap0", "target", "control", "pressure", NULL};
    PyObject *gap_obj, *start = Py_None;
    double target;
    const char *control_name = "displacement";
    enum im_control control;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "Od|sO", keywords, &gap_obj, &target, &control_name, &start) ||
        py_control_from_name(control_name, &control) < 0)
        return NULL;
    if (!self->plan)
        return PyErr_Format(PyExc_RuntimeError, "Plan: not initialised");
    if (self->busy)
        return PyErr_Format(PyExc_RuntimeError, "Plan: a solve on this plan is running in another thread");
    PyArrayObject *gap0 = grid_array(self, gap_obj, "gap0");
    PyArrayObject *pressure = gap0 ? grid_array(self, start, "pressure") : NULL;
    PyArrayObject *displacement = pressure ? grid_array(self, Py_None, "displacement") : NULL;
    if (!displacement) {
        Py_XDECREF(gap0);
        Py_XDECREF(pressure);
        return NULL;
    }
    im_solve_result result;
    int status;
    py_interrupt call;
    self->busy = 1;
    py_interrupt_arm(&call, &self->stop);
    Py_BEGIN_ALLOW_THREADS status = im_solver_solve(self->plan, PyArray_DATA(gap0), control, target,
                                                    PyArray_DATA(pressure), PyArray_DATA(displacement), &result);
    Py_END_ALLOW_THREADS self->busy = 0;
    Py_DECREF(gap0);
    int interrupted = py_interrupt_disarm(&call, &self->stop) < 0; /* KeyboardInterrupt is set */
    if (interrupted || status != IM_OK) {
        Py_DECREF(pressure);
        Py_DECREF(displacement);
        return interrupted ? NULL : py_raise_status(status);
    }
    return Py_BuildValue("(NNN)", pressure, displacement, solve_dict(&result));
}

static PyObject *plan_memory(py_plan *self, PyObject *unused)
{
    (void)unused;
    if (!self->plan)
        return PyErr_Format(PyExc_RuntimeError, "Plan: not initialised");
    if (self->busy)
        return PyErr_Format(PyExc_RuntimeError, "Plan: a solve on this plan is running in another thread");
    return plan_memory_dict(self->plan, &self->busy);
}

static PyMethodDef plan_methods[] = {{"solve", (PyCFunction)(void (*)(void))plan_solve, METH_VARARGS | METH_KEYWORDS,
                                      "solve(gap0, target, control='displacement', pressure=None) -> (pressure, "
                                      "displacement, result)"},
                                     {"memory", (PyCFunction)plan_memory, METH_NOARGS,
                                      "memory() -> dict: the memory of this plan as made"},
                                     {NULL, NULL, 0, NULL}};

PyTypeObject py_plan_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "indentmap._core.Plan",
    .tp_basicsize = sizeof(py_plan),
    .tp_dealloc = (destructor)plan_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "The contact solver on one grid (solver.h's im_solver_plan): plan once, solve many.",
    .tp_methods = plan_methods,
    .tp_init = (initproc)plan_init,
    .tp_new = PyType_GenericNew,
};

PyTypeObject py_indentation_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "indentmap._core.Indentation",
    .tp_basicsize = sizeof(py_indentation),
    .tp_dealloc = (destructor)indentation_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "An indentation history on one surface (solver.h's im_indentation).",
    .tp_methods = indentation_methods,
    .tp_getset = indentation_getset,
    .tp_init = (initproc)indentation_init,
    .tp_new = PyType_GenericNew,
};

/* ---- the indentation analysis (measure.h) ---- */

static int double_vector(PyObject *obj, npy_intp n, const char *what, PyArrayObject **out)
{
    *out = (PyArrayObject *)PyArray_FROMANY(obj, NPY_DOUBLE, 1, 1, NPY_ARRAY_IN_ARRAY);
    if (!*out)
        return -1;
    if (n >= 0 && PyArray_SIZE(*out) != n) {
        PyErr_Format(PyExc_ValueError, "%s: %ld values, expected %ld (one per step)", what, (long)PyArray_SIZE(*out),
                     (long)n);
        Py_CLEAR(*out);
        return -1;
    }
    return 0;
}

/* A branch's values and its note (measure.h: im_measure_unloading_note: why S is NaN, "" where measured). */
static PyObject *branch_dict(const im_unloading_branch *b)
{
    char note[512];
    int status = im_measure_unloading_note(b, note, sizeof note);
    if (status != IM_OK)
        return py_raise_status(status);
    return Py_BuildValue("{s:i,s:i,s:i,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:s}", "top_step", b->top_step,
                         "last_step", b->last_step, "loading_from", b->loading_from, "approach_max", b->approach_max,
                         "load_max", b->load_max, "stiffness", b->stiffness, "epsilon", b->epsilon, "contact_depth",
                         b->contact_depth, "area_projected", b->area_projected, "hardness_it", b->hardness,
                         "modulus_reduced", b->modulus, "residual_approach", b->residual_approach, "work_in",
                         b->work_in, "work_out", b->work_out, "note", note);
}

static PyObject *branches_list(const im_unloading_branch *b, int found)
{
    PyObject *list = PyList_New(found);
    for (int k = 0; list && k < found; ++k) {
        PyObject *item = branch_dict(&b[k]);
        if (!item) {
            Py_CLEAR(list);
            break;
        }
        PyList_SET_ITEM(list, k, item);
    }
    return list;
}

/* unloading(punch, alpha, radius, approach, load, residual, profile, delta) -> list of dicts */
static PyObject *unloading(PyObject *self, PyObject *args)
{
    (void)self;
    const char *kind;
    double alpha, radius, delta;
    PyObject *approach_obj, *load_obj, *residual_obj, *profile_obj;
    if (!PyArg_ParseTuple(args, "sddOOOOd", &kind, &alpha, &radius, &approach_obj, &load_obj, &residual_obj,
                          &profile_obj, &delta))
        return NULL;
    PyArrayObject *approach = NULL, *load = NULL, *residual = NULL;
    im_profile *profile = NULL;
    im_indenter punch;
    PyObject *result = NULL;
    if (double_vector(approach_obj, -1, "approach", &approach) < 0 ||
        double_vector(load_obj, PyArray_SIZE(approach), "load", &load) < 0 ||
        (residual_obj != Py_None &&
         double_vector(residual_obj, PyArray_SIZE(approach), "residual_approach", &residual) < 0) ||
        (profile_obj != Py_None && profile_from_array(profile_obj, delta, &profile) < 0) ||
        punch_from_arguments(kind, alpha, radius, Py_None, Py_None, profile, &punch) < 0)
        goto done;
    int count = (int)PyArray_SIZE(approach), found = 0;
    im_unloading_branch *b = malloc(sizeof *b * (size_t)(count > 0 ? count : 1));
    if (!b) {
        PyErr_NoMemory();
        goto done;
    }
    int status = im_measure_unloading(&punch, PyArray_DATA(approach), PyArray_DATA(load),
                                      residual ? PyArray_DATA(residual) : NULL, count, b, count, &found);
    result = status == IM_OK ? branches_list(b, found) : py_raise_status(status);
    free(b);
done:
    Py_XDECREF(approach);
    Py_XDECREF(load);
    Py_XDECREF(residual);
    im_profile_free(profile);
    return result;
}

/* write_analysis(dir, punch, alpha, radius, profile, history_values, delta, e_star, length_unit, force_unit)
 * -> branches (history.h: im_history_write_analysis) */
static PyObject *write_analysis(PyObject *self, PyObject *args)
{
    (void)self;
    const char *kind, *length_unit, *force_unit;
    double alpha, radius, delta, e_star;
    PyObject *dir, *profile_obj, *values;
    if (!PyArg_ParseTuple(args, "O&sddOOddss", PyUnicode_FSConverter, &dir, &kind, &alpha, &radius, &profile_obj,
                          &values, &delta, &e_star, &length_unit, &force_unit))
        return NULL;
    im_profile *profile = NULL;
    im_indenter punch;
    im_history_row *rows = NULL;
    int count = 0, branches = 0;
    PyObject *result = NULL;
    if ((profile_obj == Py_None || profile_from_array(profile_obj, delta, &profile) == 0) &&
        punch_from_arguments(kind, alpha, radius, Py_None, Py_None, profile, &punch) == 0 &&
        py_history_rows(values, &rows, &count) == 0) {
        int status = im_history_write_analysis(PyBytes_AS_STRING(dir), &punch, rows, count, delta, e_star,
                                               length_unit, force_unit, &branches);
        result = status == IM_OK ? PyLong_FromLong(branches) : py_raise_status(status);
    }
    free(rows);
    im_profile_free(profile);
    Py_DECREF(dir);
    return result;
}

/* adhesion(approach, load, contact, loads_given) -> dict (measure.h: im_measure_adhesion); NaN where there
 * is none */
static PyObject *adhesion(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *approach_obj, *load_obj, *contact_obj;
    int loads_given;
    if (!PyArg_ParseTuple(args, "OOOp", &approach_obj, &load_obj, &contact_obj, &loads_given))
        return NULL;
    PyArrayObject *approach = NULL, *load = NULL, *contact = NULL;
    PyObject *result = NULL;
    long *patches = NULL;
    if (double_vector(approach_obj, -1, "approach", &approach) < 0 ||
        double_vector(load_obj, PyArray_SIZE(approach), "load", &load) < 0 ||
        double_vector(contact_obj, PyArray_SIZE(approach), "contact_patches", &contact) < 0)
        goto done;
    const int count = (int)PyArray_SIZE(approach);
    if (!(patches = malloc(sizeof *patches * (size_t)(count > 0 ? count : 1)))) {
        PyErr_NoMemory();
        goto done;
    }
    for (int k = 0; k < count; ++k)
        patches[k] = (long)((const double *)PyArray_DATA(contact))[k];
    im_adhesion_summary a;
    int status = im_measure_adhesion(PyArray_DATA(approach), PyArray_DATA(load), patches, count, loads_given, &a);
    result = status != IM_OK
                 ? py_raise_status(status)
                 : Py_BuildValue("{s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d}", "pull_off_force", a.pull_off_force,
                                 "pull_off_approach", a.pull_off_approach, "most_tensile_load", a.most_tensile_load,
                                 "most_tensile_approach", a.most_tensile_approach, "jump_in_approach",
                                 a.jump_in_approach, "jump_out_approach", a.jump_out_approach, "work_done",
                                 a.work_done, "hysteresis_work", a.hysteresis_work, "hysteresis_error",
                                 a.hysteresis_error);
done:
    free(patches);
    Py_XDECREF(approach);
    Py_XDECREF(load);
    Py_XDECREF(contact);
    return result;
}

/* units_record(length_unit, e_star_unit, periodic) -> JSON text of run.json's "units" block (history.h) */
static PyObject *units_record(PyObject *self, PyObject *args)
{
    (void)self;
    const char *length_unit, *e_star_unit;
    int periodic;
    if (!PyArg_ParseTuple(args, "ssp", &length_unit, &e_star_unit, &periodic))
        return NULL;
    char text[16384];
    int status = im_history_units_json(length_unit, e_star_unit, periodic, text, sizeof text);
    return status == IM_OK ? PyUnicode_FromString(text) : py_raise_status(status);
}

/* quality_tolerance(name) -> tol (solver.h: im_quality_tolerance): draft, standard or publication */
static PyObject *quality_tolerance(PyObject *self, PyObject *args)
{
    (void)self;
    const char *name;
    double tol = 0.0;
    if (!PyArg_ParseTuple(args, "s", &name))
        return NULL;
    int status = im_quality_tolerance(name, &tol);
    return status == IM_OK ? PyFloat_FromDouble(tol) : py_raise_status(status);
}

/* solver_memory(nx, ny, periodic, device) -> dict (solver.h: im_solver_memory_needed); device = gpu that
 * the device would not hold raises OutOfMemory naming it */
static PyObject *solver_memory(PyObject *self, PyObject *args)
{
    (void)self;
    int nx, ny, periodic;
    const char *device;
    im_solver_options o = im_solver_options_default();
    if (!PyArg_ParseTuple(args, "iips", &nx, &ny, &periodic, &device))
        return NULL;
    int status = im_device_parse(device, &o.device);
    o.periodic = periodic;
    im_solver_memory m;
    if (status == IM_OK)
        status = im_solver_memory_needed(nx, ny, &o, &m);
    return status == IM_OK ? memory_dict(&m) : py_raise_status(status);
}

/* indentation_window(same arguments as Indentation) -> (x0, y0, nx, ny) (solver.h:
 * im_indentation_window_for): the window a run would solve on, without its plan. */
static PyObject *indentation_window_for(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    indentation_arguments a;
    PyObject *wisdom; /* read by planning only: not here */
    if (parse_arguments(args, kwargs, &a, &wisdom) < 0)
        return NULL;
    Py_XDECREF(wisdom);
    im_field surface = py_field_view(a.heights, a.delta);
    im_window w;
    int status;
    Py_BEGIN_ALLOW_THREADS /* the undeformed gap of the whole grid */
        status = im_indentation_window_for(&surface, &a.punch, a.control, a.largest, &a.options, &w);
    Py_END_ALLOW_THREADS release_arguments(&a);
    return status == IM_OK ? Py_BuildValue("(iiii)", w.x0, w.y0, w.nx, w.ny) : py_raise_status(status);
}

PyMethodDef py_solver_methods[] = {
    {"indentation_window", (PyCFunction)(void (*)(void))indentation_window_for, METH_VARARGS | METH_KEYWORDS,
     "indentation_window(the arguments of Indentation) -> (x0, y0, nx, ny): the window it would solve on"},
    {"solver_memory", solver_memory, METH_VARARGS,
     "solver_memory(nx, ny, periodic, device) -> dict: the memory a solve's plan needs (host; device on the GPU)"},
    {"units_record", units_record, METH_VARARGS,
     "units_record(length_unit, e_star_unit, periodic) -> run.json's \"units\" block as JSON text"},
    {"quality_tolerance", quality_tolerance, METH_VARARGS,
     "quality_tolerance(name) -> the solver tolerance of a quality preset (draft, standard, publication)"},
    {"write_analysis", write_analysis, METH_VARARGS,
     "write_analysis(dir, punch, alpha, radius, profile, history_values, delta, e_star, length_unit, force_unit) -> "
     "branches: indentation.csv and load_displacement.{png,pdf} in dir"},
    {"adhesion", adhesion, METH_VARARGS,
     "adhesion(approach, load, contact_patches) -> dict: pull-off force and approach, jumps, work lost"},
    {"unloading", unloading, METH_VARARGS,
     "unloading(punch, alpha, radius, approach, load, residual, profile, delta) -> [dict per unloading branch]"},
    {NULL, NULL, 0, NULL}};
