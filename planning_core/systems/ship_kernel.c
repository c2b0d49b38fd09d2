/* The grid ship's sampled extension in C: planning_core.systems._ship_kernel.

   ShipKernel(cells, width, height, count, theta_range, max_thrust) binds a grid's
   row-major blocked cells (bytes, one per cell, nonzero: blocked) and a ship's control
   bounds. extend(state, target, rng) answers as its reference, the control RRT's
   ControlSamplingSteering.extend over the grid ships' space information
   (rrt_cli/planners/steering.py): count controls drawn as Spaceship.sample_control
   draws them (rng.random() for theta, then for the thrust), each propagated as
   Spaceship.propagate_while over the grid (SPEC 2's dynamics; None as soon as a slice
   leaves the free cells) and kept when its end prints strictly inside the map
   (GridControlSpaceInformation.propagate_valid), the end nearest the target by
   position (closeness; the first of equals); it returns (end, control), or None when
   no control was valid. propagate_while(state, control) is the one step, for the
   tests. The same draws and the same float operations in the same order (no fused
   multiply-adds: the build pins -ffp-contract=off; Python's math.atan2 special cases
   written out, math.cos's ValueError for an infinite theta raised too), so the same
   bits come out. Built with the compiled modules (tools/build_compiled.py) and used
   only with them. */

#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>

#define SLICES 20 /* spaceship.SLICES */
static const double DT = 1.0 / SLICES; /* spaceship.DT */
static const double PI = 3.14159265358979323846; /* CPython's Py_MATH_PI */

typedef struct {
    PyObject_HEAD
    unsigned char *cells; /* width * height, row-major from the bottom row */
    Py_ssize_t width, height;
    Py_ssize_t count;     /* controls per extension */
    double theta_range, max_thrust;
} ShipKernel;

static PyObject *random_name; /* "random": rng.random() */

/* Python's math.atan2: C99's special values, written out as CPython does. */
static double py_atan2(double y, double x)
{
    if (isnan(x) || isnan(y))
        return NAN;
    if (isinf(y)) {
        if (isinf(x))
            return copysign(copysign(1.0, x) == 1.0 ? 0.25 * PI : 0.75 * PI, y);
        return copysign(0.5 * PI, y);
    }
    if (isinf(x) || y == 0.0)
        return copysign(copysign(1.0, x) == 1.0 ? 0.0 : PI, y);
    return atan2(y, x);
}

#define LANES 16 /* controls propagated together */

/* Spaceship.propagate_while over the grid for n <= LANES controls from one start,
   their slice loops interleaved: the controls' chains of dependent operations (a
   square root and two divisions a slice) overlap in the processor, and each
   control's operations are the reference's, in its order. ok[i]: control i stayed
   in the free cells (end[i] is then where it ended). */
static void slices_together(const ShipKernel *k, const double *start, const double *theta,
                            const double *thrust, Py_ssize_t n, double (*end)[4], int *ok)
{
    double x[LANES], y[LANES], dx[LANES], dy[LANES], step[LANES], push_x[LANES],
        push_y[LANES];
    double right = (double)k->width, top = (double)k->height;
    Py_ssize_t live = n;
    for (Py_ssize_t i = 0; i < n; i++) {
        x[i] = start[0];
        y[i] = start[1];
        dx[i] = start[2];
        dy[i] = start[3];
        step[i] = DT * thrust[i];
        push_x[i] = step[i] * cos(theta[i]);
        push_y[i] = step[i] * sin(theta[i]);
        ok[i] = 1;
    }
    for (int slice = 0; slice < SLICES && live > 0; slice++) {
        for (Py_ssize_t i = 0; i < n; i++) {
            if (!ok[i])
                continue;
            double vx = dx[i], vy = dy[i];
            double speed = sqrt(vx * vx + vy * vy);
            if (speed > 0.0) {
                dx[i] = vx + (vx * push_x[i] - vy * push_y[i]) / speed;
                dy[i] = vy + (vy * push_x[i] + vx * push_y[i]) / speed;
            } else {
                double a = py_atan2(vy, vx) + theta[i];
                dx[i] = vx + step[i] * cos(a);
                dy[i] = vy + step[i] * sin(a);
            }
            double px = x[i] + DT * dx[i], py = y[i] + DT * dy[i];
            x[i] = px;
            y[i] = py;
            if (!(0.0 <= px && px < right && 0.0 <= py && py < top)
                || k->cells[(Py_ssize_t)py * k->width + (Py_ssize_t)px]) {
                ok[i] = 0;
                live--;
            }
        }
    }
    for (Py_ssize_t i = 0; i < n; i++) {
        end[i][0] = x[i];
        end[i][1] = y[i];
        end[i][2] = dx[i];
        end[i][3] = dy[i];
    }
}

/* The first count floats of sequence into out (it holds count to most values); -1
   with an exception when they are not. */
static int read_floats(PyObject *sequence, double *out, Py_ssize_t count, Py_ssize_t most,
                       const char *what)
{
    PyObject *fast = PySequence_Fast(sequence, what);
    if (fast == NULL)
        return -1;
    Py_ssize_t size = PySequence_Fast_GET_SIZE(fast);
    if (size < count || size > most) {
        PyErr_Format(PyExc_ValueError, "ShipKernel: %s of %zd values expected", what, count);
        Py_DECREF(fast);
        return -1;
    }
    PyObject **items = PySequence_Fast_ITEMS(fast);
    for (Py_ssize_t i = 0; i < count; i++) {
        out[i] = PyFloat_AsDouble(items[i]);
        if (out[i] == -1.0 && PyErr_Occurred()) {
            Py_DECREF(fast);
            return -1;
        }
    }
    Py_DECREF(fast);
    return 0;
}

/* 0 when k is initialised and called with arity arguments; else -1 with an exception
   (usage says how to call it). */
static int callable(const ShipKernel *k, Py_ssize_t nargs, Py_ssize_t arity, const char *usage)
{
    if (k->cells == NULL) {
        PyErr_SetString(PyExc_RuntimeError, "ShipKernel: not initialised");
        return -1;
    }
    if (nargs != arity) {
        PyErr_SetString(PyExc_TypeError, usage);
        return -1;
    }
    return 0;
}

static PyObject *kernel_propagate_while(ShipKernel *k, PyObject *const *args, Py_ssize_t nargs)
{
    double start[4], control[2], end[1][4];
    int ok;
    if (callable(k, nargs, 2, "ShipKernel.propagate_while(state, control)") < 0
        || read_floats(args[0], start, 4, 4, "a state") < 0
        || read_floats(args[1], control, 2, 2, "a control") < 0)
        return NULL;
    if (isinf(control[0])) { /* math.cos(inf) */
        PyErr_SetString(PyExc_ValueError, "math domain error");
        return NULL;
    }
    slices_together(k, start, &control[0], &control[1], 1, end, &ok);
    if (!ok)
        Py_RETURN_NONE;
    return Py_BuildValue("(dddd)", end[0][0], end[0][1], end[0][2], end[0][3]);
}

/* rng.random() as a double (samplers.uniform's draw); -1 with an exception when it
   fails. */
static int draw(PyObject *rng, double *out)
{
    PyObject *value = PyObject_CallMethodNoArgs(rng, random_name);
    if (value == NULL)
        return -1;
    *out = PyFloat_AsDouble(value);
    Py_DECREF(value);
    return (*out == -1.0 && PyErr_Occurred()) ? -1 : 0;
}

static PyObject *kernel_extend(ShipKernel *k, PyObject *const *args, Py_ssize_t nargs)
{
    double start[4], target[2], best[4], best_control[2], best_d2 = INFINITY;
    int found = 0;
    if (callable(k, nargs, 3, "ShipKernel.extend(state, target, rng)") < 0
        || read_floats(args[0], start, 4, 4, "a state") < 0
        || read_floats(args[1], target, 2, PY_SSIZE_T_MAX, "a target") < 0)
        return NULL;
    for (Py_ssize_t first = 0; first < k->count; first += LANES) {
        Py_ssize_t n = k->count - first < LANES ? k->count - first : LANES;
        double theta[LANES], thrust[LANES], end[LANES][4];
        int ok[LANES];
        for (Py_ssize_t i = 0; i < n; i++) { /* sample_control's draws, in its order */
            double u, v;
            if (draw(args[2], &u) < 0 || draw(args[2], &v) < 0)
                return NULL;
            theta[i] = u * k->theta_range;
            thrust[i] = v * k->max_thrust;
            if (isinf(theta[i])) { /* math.cos(inf), raised after the same draws */
                PyErr_SetString(PyExc_ValueError, "math domain error");
                return NULL;
            }
        }
        slices_together(k, start, theta, thrust, n, end, ok);
        for (Py_ssize_t i = 0; i < n; i++) {
            if (!ok[i] || !(end[i][0] > 0.0 && end[i][1] > 0.0))
                continue;
            double dx = end[i][0] - target[0], dy = end[i][1] - target[1];
            double d2 = dx * dx + dy * dy;
            if (d2 < best_d2) {
                memcpy(best, end[i], sizeof best);
                best_control[0] = theta[i];
                best_control[1] = thrust[i];
                best_d2 = d2;
                found = 1;
            }
        }
    }
    if (!found)
        Py_RETURN_NONE;
    return Py_BuildValue("((dddd)(dd))", best[0], best[1], best[2], best[3],
                         best_control[0], best_control[1]);
}

static int kernel_init(ShipKernel *k, PyObject *args, PyObject *kwargs)
{
    Py_buffer cells;
    Py_ssize_t width, height, count;
    double theta_range, max_thrust;
    static char *names[] = {"cells", "width", "height", "count", "theta_range", "max_thrust",
                            NULL};
    if (k->cells != NULL) {
        PyErr_SetString(PyExc_RuntimeError, "ShipKernel: already initialised");
        return -1;
    }
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "y*nnndd", names, &cells, &width, &height,
                                     &count, &theta_range, &max_thrust))
        return -1;
    if (width < 1 || height < 1 || cells.len != width * height) {
        PyBuffer_Release(&cells);
        PyErr_SetString(PyExc_ValueError, "ShipKernel: width * height cells expected");
        return -1;
    }
    if (count < 1) {
        PyBuffer_Release(&cells);
        PyErr_SetString(PyExc_ValueError, "ShipKernel: at least one control per extension");
        return -1;
    }
    k->cells = PyMem_Malloc((size_t)cells.len);
    if (k->cells == NULL) {
        PyBuffer_Release(&cells);
        PyErr_NoMemory();
        return -1;
    }
    memcpy(k->cells, cells.buf, (size_t)cells.len);
    PyBuffer_Release(&cells);
    k->width = width;
    k->height = height;
    k->count = count;
    k->theta_range = theta_range;
    k->max_thrust = max_thrust;
    return 0;
}

static void kernel_dealloc(ShipKernel *k)
{
    PyMem_Free(k->cells);
    Py_TYPE(k)->tp_free((PyObject *)k);
}

static PyMethodDef kernel_methods[] = {
    {"extend", (PyCFunction)(void (*)(void))kernel_extend, METH_FASTCALL,
     "extend(state, target, rng): as the control RRT's sampled extension over the grid."},
    {"propagate_while", (PyCFunction)(void (*)(void))kernel_propagate_while, METH_FASTCALL,
     "propagate_while(state, control): as Spaceship.propagate_while(state, control, grid)."},
    {NULL, NULL, 0, NULL},
};

static PyTypeObject ShipKernelType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "planning_core.systems._ship_kernel.ShipKernel",
    .tp_doc = "A grid's blocked cells and a ship's control bounds, for its extension in C.",
    .tp_basicsize = sizeof(ShipKernel),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)kernel_init,
    .tp_dealloc = (destructor)kernel_dealloc,
    .tp_methods = kernel_methods,
};

static struct PyModuleDef kernel_module = {
    PyModuleDef_HEAD_INIT, "_ship_kernel",
    "The grid ship's sampled extension in C (reference: ControlSamplingSteering.extend).",
    -1, NULL,
};

PyMODINIT_FUNC PyInit__ship_kernel(void)
{
    if (PyType_Ready(&ShipKernelType) < 0)
        return NULL;
    if (random_name == NULL && (random_name = PyUnicode_InternFromString("random")) == NULL)
        return NULL;
    PyObject *module = PyModule_Create(&kernel_module);
    if (module == NULL)
        return NULL;
    if (PyModule_AddIntConstant(module, "SLICES", SLICES) < 0
        || PyModule_AddType(module, &ShipKernelType) < 0) {
        Py_DECREF(module);
        return NULL;
    }
    return module;
}
