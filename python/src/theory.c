/* The paper's theory (theory.h), element by element over numpy arrays that the Python layer has
 * already broadcast to one shape: _core.theory(name, a, b, params) -> array. */
#include "core.h"

#include <stdint.h>

#include "indentmap/status.h"
#include "indentmap/theory.h"

typedef struct theory_params {
    im_theory_interface rough; /* slope_rms is overwritten per element where a function takes it */
    double alpha, radius;
} theory_params;

typedef int (*theory_function)(const theory_params *p, double a, double b, double *out);

static int rho_c(const theory_params *p, double slope, double alpha, double *out)
{
    im_theory_interface rough = p->rough;
    rough.slope_rms = slope;
    return im_theory_cone_rho(&rough, alpha, out);
}
static int beta(const theory_params *p, double rho, double unused, double *out)
{
    (void)unused;
    return im_theory_erf_scale(rho, p->rough.normalisation, p->rough.k, out);
}
static int ratio_eq6(const theory_params *p, double b, double unused, double *out)
{
    (void)p, (void)unused;
    return im_theory_cone_area_ratio_constant(b, out);
}
static int ratio_eq12(const theory_params *p, double b, double unused, double *out)
{
    (void)p, (void)unused;
    return im_theory_cone_area_ratio_variable(b, out);
}
static int ratio_eq19(const theory_params *p, double b, double unused, double *out)
{
    (void)p, (void)unused;
    return im_theory_cone_area_ratio_greenwood(b, out);
}
static int gamma_eq10(const theory_params *p, double b, double r_over_a, double *out)
{
    (void)p;
    return im_theory_cone_contact_density(b, r_over_a, out);
}
static int pressure_eq11(const theory_params *p, double r_over_a, double unused, double *out)
{
    (void)p, (void)unused;
    return im_theory_cone_pressure(r_over_a, out);
}
static int flat_eq1(const theory_params *p, double slope, double p_mean, double *out)
{
    im_theory_interface rough = p->rough;
    rough.slope_rms = slope;
    return im_theory_flat_area_ratio(&rough, p_mean, out);
}
static int sphere_eq3(const theory_params *p, double slope, double load, double *out)
{
    im_theory_interface rough = p->rough;
    rough.slope_rms = slope;
    return im_theory_sphere_area(&rough, load, p->radius, out);
}
static int hertz_area(const theory_params *p, double load, double unused, double *out)
{
    (void)unused;
    return im_theory_hertz_area(load, p->radius, p->rough.e_star, out);
}
static int cone_area(const theory_params *p, double load, double unused, double *out)
{
    (void)unused;
    return im_theory_cone_area(load, p->alpha, p->rough.e_star, out);
}

typedef struct named_function {
    const char *name;
    theory_function function;
} named_function;

static const named_function functions[] = {
    {"rho_c", rho_c},
    {"beta", beta},
    {"area_ratio_eq6", ratio_eq6},
    {"area_ratio_eq12", ratio_eq12},
    {"area_ratio_eq19", ratio_eq19},
    {"gamma", gamma_eq10},
    {"cone_pressure", pressure_eq11},
    {"flat_area_ratio", flat_eq1},
    {"sphere_area", sphere_eq3},
    {"hertz_area", hertz_area},
    {"cone_area", cone_area},
};

static theory_function find_function(const char *name)
{
    for (size_t i = 0; i < sizeof functions / sizeof *functions; ++i)
        if (strcmp(functions[i].name, name) == 0)
            return functions[i].function;
    PyErr_Format(PyExc_ValueError, "theory function '%s' is not known", name);
    return NULL;
}

static int parse_params(PyObject *dict, theory_params *p)
{
    const char *normalisation = "pr";
    static char *keywords[] = {"alpha", "k", "e_star", "normalisation", "radius", NULL};
    PyObject *empty = PyTuple_New(0);
    if (!empty)
        return -1;
    int ok = PyArg_ParseTupleAndKeywords(empty, dict, "|dddsd", keywords, &p->alpha, &p->rough.k, &p->rough.e_star,
                                         &normalisation, &p->radius);
    Py_DECREF(empty);
    if (!ok)
        return -1;
    if (strcmp(normalisation, "pr") == 0)
        p->rough.normalisation = IM_THEORY_NORMALISATION_PR;
    else if (strcmp(normalisation, "mg") == 0)
        p->rough.normalisation = IM_THEORY_NORMALISATION_MG;
    else {
        PyErr_Format(PyExc_ValueError, "normalisation '%s': expected 'pr' or 'mg'", normalisation);
        return -1;
    }
    return 0;
}

static PyObject *theory(PyObject *self, PyObject *args)
{
    (void)self;
    const char *name;
    PyArrayObject *a, *b;
    PyObject *params_dict;
    if (!PyArg_ParseTuple(args, "sO!O!O!", &name, &PyArray_Type, &a, &PyArray_Type, &b, &PyDict_Type, &params_dict))
        return NULL;
    theory_function function = find_function(name);
    theory_params p = {.rough = im_theory_interface_default(0.0), .alpha = 80.0, .radius = 1.0};
    if (!function || parse_params(params_dict, &p) < 0)
        return NULL;
    npy_intp n = PyArray_SIZE(a);
    if (PyArray_TYPE(a) != NPY_DOUBLE || PyArray_TYPE(b) != NPY_DOUBLE || !PyArray_IS_C_CONTIGUOUS(a) ||
        !PyArray_IS_C_CONTIGUOUS(b) || PyArray_SIZE(b) != n)
        return PyErr_Format(PyExc_TypeError, "theory: expected two contiguous float64 arrays of one size");
    PyObject *out = PyArray_SimpleNew(PyArray_NDIM(a), PyArray_DIMS(a), NPY_DOUBLE);
    if (!out)
        return NULL;
    const double *x = PyArray_DATA(a), *y = PyArray_DATA(b);
    double *result = PyArray_DATA((PyArrayObject *)out);
    for (npy_intp i = 0; i < n; ++i) {
        int status = function(&p, x[i], y[i], &result[i]);
        if (status != IM_OK) {
            Py_DECREF(out);
            return py_raise_status(status);
        }
    }
    return out;
}

/* fit_k(pressure_ratio, area_fraction): two contiguous float64 arrays of one size -> dict (theory.h) */
static PyObject *fit_k(PyObject *self, PyObject *args)
{
    (void)self;
    PyArrayObject *x, *area;
    if (!PyArg_ParseTuple(args, "O!O!", &PyArray_Type, &x, &PyArray_Type, &area))
        return NULL;
    npy_intp n = PyArray_SIZE(x);
    if (PyArray_TYPE(x) != NPY_DOUBLE || PyArray_TYPE(area) != NPY_DOUBLE || !PyArray_IS_C_CONTIGUOUS(x) ||
        !PyArray_IS_C_CONTIGUOUS(area) || PyArray_SIZE(area) != n || n < 1 || n > INT32_MAX) {
        PyErr_SetString(PyExc_ValueError, "fit_k: expected two float64 arrays of one size >= 1");
        return NULL;
    }
    im_theory_k_fit fit;
    int status = im_theory_fit_k(PyArray_DATA(x), PyArray_DATA(area), (int)n, &fit);
    if (status != IM_OK)
        return py_raise_status(status);
    return Py_BuildValue("{s:d,s:d,s:d,s:i,s:d}", "k", fit.k, "k_error", fit.k_error, "k_linear", fit.k_linear,
                         "linear_points", fit.linear_points, "rms_residual", fit.rms_residual);
}

PyMethodDef py_theory_methods[] = {
    {"theory", theory, METH_VARARGS, "theory(name, a, b, params) -> array (see indentmap.theory)"},
    {"fit_k", fit_k, METH_VARARGS, "fit_k(pressure_ratio, area_fraction) -> dict (see indentmap.theory.fit_k)"},
    {NULL, NULL, 0, NULL}};
