/* Surfaces: synthesis, statistics, PSD, histograms, reading and writing files. */
#include "core.h"

#include "indentmap/io.h"
#include "indentmap/formats.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

static int slope_definition_from_name(const char *name, enum im_slope_definition *definition)
{
    if (strcmp(name, "spectral") == 0)
        *definition = IM_SLOPE_SPECTRAL;
    else if (strcmp(name, "fd") == 0)
        *definition = IM_SLOPE_FINITE_DIFFERENCE;
    else {
        PyErr_Format(PyExc_ValueError, "slope_definition '%s': expected 'spectral' or 'fd'", name);
        return -1;
    }
    return 0;
}

/* generate's and generator_record's arguments as the library's parameters; -1 with the exception set. */
static int params_from_arguments(PyObject *args, PyObject *kwargs, im_surface_params *p)
{
    static char *keywords[] = {"nx",       "ny",       "delta", "hurst",      "lambda_s",
                               "lambda_r", "lambda_0", "slope", "height_rms", "slope_definition",
                               "seed",     NULL};
    *p = im_surface_params_default();
    PyObject *height_rms = Py_None;
    const char *definition = "spectral";
    unsigned long long seed = p->seed;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "ii|ddddddOsK", keywords, &p->nx, &p->ny, &p->delta, &p->hurst,
                                     &p->lambda_s, &p->lambda_r, &p->lambda_0, &p->slope_rms, &height_rms,
                                     &definition, &seed))
        return -1;
    if (height_rms != Py_None) {
        p->target = IM_TARGET_HEIGHT;
        p->height_rms = PyFloat_AsDouble(height_rms);
        if (PyErr_Occurred())
            return -1;
    }
    p->seed = seed;
    return slope_definition_from_name(definition, &p->slope_definition);
}

static PyObject *generate(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    im_surface_params p;
    if (params_from_arguments(args, kwargs, &p) < 0)
        return NULL;
    im_field *field = NULL;
    int status;
    Py_BEGIN_ALLOW_THREADS status = im_surface_generate(&p, &field);
    Py_END_ALLOW_THREADS return status == IM_OK ? py_array_from_field(field) : py_raise_status(status);
}

/* generator_record(generate's arguments) -> the record `surface --out` writes in its sidecar, as JSON text */
static PyObject *generator_record(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    im_surface_params p;
    char *text = NULL;
    if (params_from_arguments(args, kwargs, &p) < 0)
        return NULL;
    int status = im_surface_generator_record(&p, &text);
    if (status != IM_OK)
        return py_raise_status(status);
    PyObject *record = PyUnicode_FromString(text);
    free(text);
    return record;
}

static PyObject *stats_dict(const im_surface_stats *s)
{
    return Py_BuildValue("{s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d}", "mean", s->mean, "height_rms",
                         s->height_rms, "slope_rms_spectral", s->slope_rms_spectral, "slope_rms_fd", s->slope_rms_fd,
                         "curvature_rms", s->curvature_rms, "m0", s->m0, "m2", s->m2, "m4", s->m4, "nayak", s->nayak,
                         "height_min", s->height_min, "height_max", s->height_max);
}

static int taper_from_name(const char *name, double alpha, im_taper *taper)
{
    if (strcmp(name, "none") == 0)
        *taper = (im_taper){IM_TAPER_NONE, 0.0};
    else if (strcmp(name, "hann") == 0)
        *taper = (im_taper){IM_TAPER_HANN, 1.0};
    else if (strcmp(name, "tukey") == 0)
        *taper = (im_taper){IM_TAPER_TUKEY, alpha};
    else {
        PyErr_Format(PyExc_ValueError, "window '%s': expected 'none', 'hann' or 'tukey'", name);
        return -1;
    }
    return 0;
}

/* statistics(heights, delta, window, alpha): spectral quantities from the windowed surface. */
static PyObject *statistics(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *obj;
    double delta, alpha;
    const char *window;
    im_taper taper;
    if (!PyArg_ParseTuple(args, "Odsd", &obj, &delta, &window, &alpha) || taper_from_name(window, alpha, &taper) < 0)
        return NULL;
    PyArrayObject *array = py_heights_array(obj, "heights");
    if (!array)
        return NULL;
    im_field field = py_field_view(array, delta);
    im_surface_stats stats;
    int status;
    Py_BEGIN_ALLOW_THREADS status = im_surface_statistics_tapered(&field, &taper, &stats);
    Py_END_ALLOW_THREADS Py_DECREF(array);
    return status == IM_OK ? stats_dict(&stats) : py_raise_status(status);
}

/* The number of wavevectors averaged in each shell of a PSD, as int64. */
static PyObject *shell_counts(const im_psd *psd)
{
    npy_intp n = psd->bins;
    PyObject *array = PyArray_SimpleNew(1, &n, NPY_INT64);
    if (array)
        for (npy_intp i = 0; i < n; ++i)
            ((npy_int64 *)PyArray_DATA((PyArrayObject *)array))[i] = psd->counts[i];
    return array;
}

static PyObject *psd(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *obj;
    double delta;
    int bins;
    if (!PyArg_ParseTuple(args, "Odi", &obj, &delta, &bins))
        return NULL;
    PyArrayObject *array = py_heights_array(obj, "heights");
    if (!array)
        return NULL;
    im_field field = py_field_view(array, delta);
    im_psd *result = NULL;
    int status;
    Py_BEGIN_ALLOW_THREADS status = im_surface_psd(&field, bins, &result);
    Py_END_ALLOW_THREADS Py_DECREF(array);
    if (status != IM_OK)
        return py_raise_status(status);
    PyObject *out = Py_BuildValue("(NNN)", py_array_from_doubles(result->q, result->bins),
                                  py_array_from_doubles(result->c, result->bins), shell_counts(result));
    im_psd_free(result);
    return out;
}

static PyObject *histogram(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *obj;
    double delta;
    int quantity, bins;
    if (!PyArg_ParseTuple(args, "Odii", &obj, &delta, &quantity, &bins))
        return NULL;
    PyArrayObject *array = py_heights_array(obj, "heights");
    if (!array)
        return NULL;
    im_field field = py_field_view(array, delta);
    im_histogram *result = NULL;
    int status = im_surface_histogram(&field, (enum im_histogram_quantity)quantity, bins, &result);
    Py_DECREF(array);
    if (status != IM_OK)
        return py_raise_status(status);
    PyObject *out = Py_BuildValue("(NN)", py_array_from_doubles(result->centre, result->bins),
                                  py_array_from_doubles(result->density, result->bins));
    im_histogram_free(result);
    return out;
}

int py_detrend_from_name(const char *name, enum im_detrend *detrend)
{
    if (strcmp(name, "none") == 0)
        *detrend = IM_DETREND_NONE;
    else if (strcmp(name, "plane") == 0)
        *detrend = IM_DETREND_PLANE;
    else if (strcmp(name, "curvature") == 0)
        *detrend = IM_DETREND_CURVATURE;
    else {
        PyErr_Format(PyExc_ValueError, "detrend '%s': expected 'none', 'plane' or 'curvature'", name);
        return -1;
    }
    return 0;
}

int py_align_from_name(const char *name, enum im_row_alignment *out)
{
    static const char *const NAMES[] = {"none", "median", "mean", "line"};
    for (int i = 0; i < 4; ++i)
        if (strcmp(name, NAMES[i]) == 0) {
            *out = (enum im_row_alignment)i;
            return 0;
        }
    py_raise_status(im_fail(IM_EINVAL, "align '%.40s': expected 'none', 'median', 'mean' or 'line'", name));
    return -1;
}

/* prepare(heights, detrend, fill, align) -> (new heights, points filled) */
static PyObject *prepare(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *obj;
    const char *detrend_name, *align_name;
    int fill;
    enum im_detrend detrend;
    enum im_row_alignment align;
    if (!PyArg_ParseTuple(args, "Osps", &obj, &detrend_name, &fill, &align_name) ||
        py_detrend_from_name(detrend_name, &detrend) < 0 || py_align_from_name(align_name, &align) < 0)
        return NULL;
    PyArrayObject *array = py_heights_array(obj, "heights");
    if (!array)
        return NULL;
    im_field view = py_field_view(array, 1.0), *copy = NULL;
    int status = im_field_clone(&view, &copy);
    Py_DECREF(array);
    long filled = 0;
    if (status == IM_OK && fill)
        status = im_surface_fill_missing(copy, &filled);
    if (status == IM_OK)
        status = im_field_check_finite(copy, "heights (fill=True fills missing points)");
    if (status == IM_OK)
        status = im_surface_align_rows(copy, align);
    if (status == IM_OK)
        status = im_surface_detrend(copy, detrend);
    if (status != IM_OK) {
        im_field_free(copy);
        return py_raise_status(status);
    }
    return Py_BuildValue("(Nl)", py_array_from_field(copy), filled);
}

/* A length unit the caller named for `parameter` in its canonical spelling (formats.h: im_length_unit_metres), or
 * "" for none; -1 with ValueError naming the parameter otherwise. */
static int length_unit_argument(const char *parameter, const char *text, char out[16])
{
    const char *canonical = text;
    out[0] = '\0';
    if (!text[0])
        return 0;
    if (strlen(text) >= 16 || im_length_unit_metres(text, &canonical) == 0.0) {
        /* the units as an argument: PyErr_Format's format must be ASCII */
        PyErr_Format(PyExc_ValueError, "%s '%.40s': expected a length unit (%s)", parameter, text,
                     "m, cm, mm, \u00b5m or um, nm, pm, \u00c5");
        return -1;
    }
    snprintf(out, 16, "%s", canonical);
    return 0;
}

/* length_unit(parameter, text) -> text's canonical spelling ("" stays ""); ValueError naming the parameter */
static PyObject *length_unit(PyObject *self, PyObject *args)
{
    (void)self;
    const char *parameter, *text;
    char canonical[16];
    if (!PyArg_ParseTuple(args, "ss", &parameter, &text) || length_unit_argument(parameter, text, canonical) < 0)
        return NULL;
    return PyUnicode_FromString(canonical);
}

int py_surface_read_options(const py_read_names *names, int fill, int resample_square, int npy_order,
                            im_surface_read_options *options)
{
    options->fill = fill;
    options->resample_square = resample_square;
    options->npy_order = (enum im_npy_order)npy_order;
    if (length_unit_argument("unit", names->unit, options->set.lateral) < 0 ||
        length_unit_argument("height_unit", names->height_unit, options->set.height) < 0 ||
        length_unit_argument("length_unit", names->length_unit, options->express_in) < 0)
        return -1;
    if (strlen(names->channel) >= sizeof options->channel) {
        py_raise_status(im_fail(IM_EINVAL, "channel '%.70s': expected an index or title of at most %zu bytes",
                                names->channel, sizeof options->channel - 1));
        return -1;
    }
    snprintf(options->channel, sizeof options->channel, "%s", names->channel);
    return 0;
}

/* read_surface(path, channel, fill, resample_square, npy_order, unit, height_unit, length_unit)
 * -> (heights, delta, unit, assumed: what was taken that the file does not state, "" if nothing); npy_order is an enum im_npy_order (0: the sidecar's, 1: yx, 2: xy); the
 * units as `indent --unit --height-unit --length-unit` ("": the file's) */
static PyObject *read_surface(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *path_bytes;
    py_read_names names;
    int fill, resample_square, npy_order;
    if (!PyArg_ParseTuple(args, "O&sppisss", PyUnicode_FSConverter, &path_bytes, &names.channel, &fill,
                          &resample_square, &npy_order, &names.unit, &names.height_unit, &names.length_unit))
        return NULL;
    im_surface_read_options options = {0};
    if (py_surface_read_options(&names, fill, resample_square, npy_order, &options) < 0) {
        Py_DECREF(path_bytes);
        return NULL;
    }
    im_field *field = NULL;
    im_surface_read_info info;
    int status;
    Py_BEGIN_ALLOW_THREADS status = im_surface_read_with(PyBytes_AS_STRING(path_bytes), &options, &field, &info);
    Py_END_ALLOW_THREADS Py_DECREF(path_bytes);
    if (status != IM_OK)
        return py_raise_status(status);
    double delta = field->delta;
    PyObject *unit_text = PyUnicode_DecodeUTF8(field->unit, (Py_ssize_t)strlen(field->unit), "replace");
    PyObject *assumed = PyUnicode_DecodeUTF8(info.assumed, (Py_ssize_t)strlen(info.assumed), "replace");
    return Py_BuildValue("(NdNN)", py_array_from_field(field), delta, unit_text, assumed);
}

/* The generator's parameters, checked against the heights they are written with: a record of another grid
 * or spacing would tell the readers of the file that it is a surface it is not. */
static int generator_for_heights(const char *text, const im_field *field, im_surface_params *params)
{
    int status = im_surface_generator_parse(text, params);
    if (status == IM_OK) /* the record's statistics are of every point: a generated surface misses none */
        status = im_field_check_finite(field, "heights written with a generator");
    if (status == IM_OK && (params->nx != field->nx || params->ny != field->ny))
        status = im_fail(IM_EINVAL, "generator: nx = %d, ny = %d: expected the heights' shape, %d x %d (ny x nx)",
                         params->nx, params->ny, field->ny, field->nx);
    if (status == IM_OK && params->delta != field->delta)
        status = im_fail(IM_EINVAL, "generator: delta = %.17g: expected delta = %.17g, the spacing written",
                         params->delta, field->delta);
    return status;
}

/* write_surface(path, heights, delta, unit, generator: its record as JSON text, or None) */
static PyObject *write_surface(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *path_bytes, *obj;
    double delta;
    const char *unit, *generator_text = NULL;
    if (!PyArg_ParseTuple(args, "O&Odsz", PyUnicode_FSConverter, &path_bytes, &obj, &delta, &unit, &generator_text))
        return NULL;
    PyArrayObject *array = py_heights_array(obj, "heights");
    if (!array || strlen(unit) >= sizeof((im_field *)NULL)->unit) {
        if (array)
            PyErr_Format(PyExc_ValueError, "unit '%s': at most %zu bytes", unit, sizeof((im_field *)NULL)->unit - 1);
        Py_XDECREF(array);
        Py_DECREF(path_bytes);
        return NULL;
    }
    im_field field = py_field_view(array, delta);
    snprintf(field.unit, sizeof field.unit, "%s", unit);
    im_surface_params generator;
    int status = generator_text ? generator_for_heights(generator_text, &field, &generator) : IM_OK;
    if (status == IM_OK) {
        /* The file and its sidecar, one writer's pair (formats.h): with a generator the record `surface --out`
         * writes, so that the readers take the file as the generated surface it is; else a .npy's units. */
        Py_BEGIN_ALLOW_THREADS status = im_surface_write_with_sidecar(PyBytes_AS_STRING(path_bytes), &field,
                                                                      generator_text ? &generator : NULL, NULL, NULL);
        Py_END_ALLOW_THREADS
    }
    Py_DECREF(array);
    Py_DECREF(path_bytes);
    return status == IM_OK ? Py_NewRef(Py_None) : py_raise_status(status);
}

PyMethodDef py_surface_methods[] = {
    {"generate", (PyCFunction)(void (*)(void))generate, METH_VARARGS | METH_KEYWORDS, "Spectral synthesis."},
    {"statistics", statistics, METH_VARARGS, "statistics(heights, delta, window, alpha) -> dict"},
    {"prepare", prepare, METH_VARARGS, "prepare(heights, detrend, fill, align) -> (heights, filled)"},
    {"psd", psd, METH_VARARGS, "psd(heights, delta, bins) -> (q, C, counts)"},
    {"histogram", histogram, METH_VARARGS, "histogram(heights, delta, quantity, bins) -> (centre, density)"},
    {"read_surface", read_surface, METH_VARARGS,
     "read_surface(path, channel, fill, resample_square, npy_order, unit, height_unit, length_unit) -> "
     "(heights, delta, unit, assumed)"},
    {"generator_record", (PyCFunction)(void (*)(void))generator_record, METH_VARARGS | METH_KEYWORDS,
     "generator_record(generate's arguments) -> the sidecar's generator record (JSON text)"},
    {"write_surface", write_surface, METH_VARARGS, "write_surface(path, heights, delta, unit, generator)"},
    {"length_unit", length_unit, METH_VARARGS, "length_unit(parameter, text) -> the unit's canonical spelling"},
    {NULL, NULL, 0, NULL}};
