/* Histories as arrays of their columns' numbers (history.h: one schema, one writer and one reader): a
 * history's text read by the library's reader, rows as the library gives their values, and rows back
 * from such values. python/indentmap/solver.py names and types the columns. */
#include "core.h"

#include "indentmap/history.h"

#include <stdlib.h>

/* Rows as a new (count, IM_HISTORY_COLUMN_COUNT) float64 array of their columns' numbers. */
static PyObject *values_of(const im_history_row *rows, int count)
{
    npy_intp shape[2] = {count, IM_HISTORY_COLUMN_COUNT};
    PyArrayObject *array = (PyArrayObject *)PyArray_SimpleNew(2, shape, NPY_DOUBLE);
    for (int i = 0; array && i < count; ++i)
        im_history_row_values(&rows[i], (double *)PyArray_DATA(array) + (size_t)i * IM_HISTORY_COLUMN_COUNT);
    return (PyObject *)array;
}

/* The text read by im_history_parse (any punch's area) as values_of's array; ValueError "SOURCE: why" for
 * another version's columns or a damaged row. */
static PyObject *read_values(const char *text, const char *source)
{
    int capacity = 1, count = 0;
    for (const char *p = text; *p; ++p)
        capacity += *p == '\n';
    im_history_row *rows = malloc(sizeof *rows * (size_t)capacity);
    if (!rows)
        return PyErr_NoMemory();
    char why[256];
    PyObject *out = NULL;
    if (im_history_parse(text, IM_HISTORY_AREA_ANY, rows, capacity, &count, why, sizeof why))
        out = values_of(rows, count);
    else
        PyErr_Format(PyExc_ValueError, "%s: %s", source, why);
    free(rows);
    return out;
}

PyObject *py_history_values(const im_history_row *rows, int count)
{
    size_t size = IM_HISTORY_LINE_MAX * (size_t)(count + 1), used = 0;
    char *text = malloc(size);
    if (!text)
        return PyErr_NoMemory();
    used += (size_t)snprintf(text, size, "%s\n", im_history_columns());
    for (int i = 0; i < count; ++i)
        used += (size_t)im_history_format(&rows[i], text + used, size - used);
    PyObject *out = read_values(text, "history");
    free(text);
    return out;
}

int py_history_rows(PyObject *values, im_history_row **rows, int *count)
{
    PyArrayObject *array = (PyArrayObject *)PyArray_FROMANY(values, NPY_DOUBLE, 2, 2, NPY_ARRAY_CARRAY_RO);
    if (!array)
        return -1;
    int status = PyArray_DIM(array, 1) == IM_HISTORY_COLUMN_COUNT ? IM_OK : IM_EINVAL;
    if (status != IM_OK)
        PyErr_Format(PyExc_ValueError, "history: %ld columns, expected %d", (long)PyArray_DIM(array, 1),
                     IM_HISTORY_COLUMN_COUNT);
    *count = (int)PyArray_DIM(array, 0);
    *rows = status == IM_OK ? calloc((size_t)*count + 1, sizeof **rows) : NULL;
    if (status == IM_OK && !*rows) {
        status = IM_ENOMEM;
        PyErr_NoMemory();
    }
    const double *data = PyArray_DATA(array);
    for (int i = 0; status == IM_OK && i < *count; ++i)
        if ((status = im_history_row_from_values(data + (size_t)i * IM_HISTORY_COLUMN_COUNT, &(*rows)[i])) != IM_OK)
            py_raise_status(status);
    Py_DECREF(array);
    return status == IM_OK ? 0 : -1;
}

/* history_values(text, source) -> (rows, columns) float64 array (read_values) */
static PyObject *history_values(PyObject *self, PyObject *args)
{
    (void)self;
    const char *text, *source;
    return PyArg_ParseTuple(args, "ss", &text, &source) ? read_values(text, source) : NULL;
}

PyMethodDef py_history_methods[] = {{"history_values", history_values, METH_VARARGS,
                                     "history_values(text, source) -> the history's rows as an array of its columns' "
                                     "numbers"},
                                    {NULL, NULL, 0, NULL}};
