/* numpy arrays <-> im_field: borrowed views in, arrays that own the library's fields out. */
#include "core.h"

#include "indentmap/status.h"

/* im.read's Topography (heights, delta, unit) is a tuple: numpy would try it as a ragged array and say
 * nothing a user can act on. It is named, with what to pass instead. */
static int refuse_topography(PyObject *obj, const char *what)
{
    if (PyArray_Check(obj) || !PyObject_HasAttrString(obj, "heights") || !PyObject_HasAttrString(obj, "delta"))
        return 0;
    PyErr_Format(PyExc_TypeError,
                 "%s: got a %s (im.read's heights, delta and unit): expected its 2-D array of heights, "
                 "top.heights, with its spacing as delta=top.delta (and length_unit=top.unit where taken)",
                 what, Py_TYPE(obj)->tp_name);
    return 1;
}

PyArrayObject *py_heights_array(PyObject *obj, const char *what)
{
    if (refuse_topography(obj, what))
        return NULL;
    PyArray_Descr *float64 = PyArray_DescrFromType(NPY_DOUBLE);
    /* Safe casting only: complex, object and string arrays are refused, not silently cut. */
    PyArrayObject *array = (PyArrayObject *)PyArray_FromAny(obj, float64, 2, 2,
                                                            NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED, NULL);
    if (!array) {
        PyObject *type, *value, *traceback;
        PyErr_Fetch(&type, &value, &traceback);
        PyErr_Format(PyExc_TypeError,
                     "%s: expected a 2-D array of real numbers (float64, or castable to it "
                     "without loss: bool, integers, float32), got %R",
                     what, value ? value : Py_None);
        Py_XDECREF(type);
        Py_XDECREF(value);
        Py_XDECREF(traceback);
        return NULL;
    }
    npy_intp *shape = PyArray_DIMS(array);
    if (shape[0] < 1 || shape[1] < 1 || shape[0] > IM_FIELD_MAX_SIDE || shape[1] > IM_FIELD_MAX_SIDE) {
        PyErr_Format(PyExc_ValueError, "%s: shape (%ld, %ld): each side must be 1 .. %d", what, (long)shape[0],
                     (long)shape[1], IM_FIELD_MAX_SIDE);
        Py_DECREF(array);
        return NULL;
    }
    return array;
}

im_field py_field_view(PyArrayObject *array, double delta)
{
    npy_intp *shape = PyArray_DIMS(array);
    return (im_field){.nx = (int)shape[1], .ny = (int)shape[0], .delta = delta, .data = PyArray_DATA(array)};
}

static void free_field_capsule(PyObject *capsule) { im_field_free(PyCapsule_GetPointer(capsule, "indentmap.field")); }

PyObject *py_array_from_field(im_field *field)
{
    npy_intp shape[2] = {field->ny, field->nx};
    PyObject *array = PyArray_SimpleNewFromData(2, shape, NPY_DOUBLE, field->data);
    PyObject *owner = array ? PyCapsule_New(field, "indentmap.field", free_field_capsule) : NULL;
    if (!owner) {
        Py_XDECREF(array);
        im_field_free(field);
        return NULL;
    }
    if (PyArray_SetBaseObject((PyArrayObject *)array, owner) < 0) { /* steals owner */
        Py_DECREF(array);
        return NULL;
    }
    return array;
}

PyObject *py_array_from_doubles(const double *values, npy_intp n)
{
    PyObject *array = PyArray_SimpleNew(1, &n, NPY_DOUBLE);
    if (array && n > 0)
        memcpy(PyArray_DATA((PyArrayObject *)array), values, (size_t)n * sizeof(double));
    return array;
}
