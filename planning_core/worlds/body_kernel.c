/* A placed body's full collision test and a point's clearance in C:
   planning_core.worlds._body_kernel.

   BodyKernel(body_xs, body_ys, has_box, box, kinds, boxes, xs, ys, discs) binds a
   body's points and a world's box and obstacles (segment_tests.Obstacles) as C
   arrays. meets(x, y, theta) answers as its reference, the shapes' test
   ContinuousWorld.first_obstacle(place(body, x, y, theta)) is not None: the body's
   points rotated by theta and moved to (x, y), then outside the closed box, or
   meeting a closed obstacle (bounding boxes first; a disc by its nearest edge, a
   rect by the body's edge lines, a polygon by both polygons' edge lines). clearance(x, y) is body_tests.clearance, Python's math.hypot
   called where that takes one. The same float operations in the same order (no
   fused multiply-adds: the build pins -ffp-contract=off), so the same poses meet
   and the same clearances come out; placed(x, y, theta) returns the placed points,
   for the tests that compare them bit for bit. Built with the compiled modules
   (tools/build_compiled.py) and used only with them. */

#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>

#define RECT 0 /* segment_tests' obstacle kinds */
#define DISC 1
#define POLYGON 2
#define SNAP 1e-12 /* body_tests.SNAP: |cos| or |sin| below this is 0 */

typedef struct {
    PyObject_HEAD
    Py_ssize_t n;          /* the body's points */
    double *bx, *by;       /* the body in its own frame (CCW) */
    double *px, *py;       /* the body placed (scratch) */
    double box[4];         /* xmin, ymin, xmax, ymax (closed; infinite without a box) */
    int has_box;
    Py_ssize_t m;          /* obstacles */
    int *kinds;
    double *boxes;         /* four per obstacle: its bounding box */
    double *discs;         /* three per obstacle: a disc's cx, cy, r */
    Py_ssize_t *first;     /* m + 1 offsets into ox, oy: obstacle i's points */
    double *ox, *oy;       /* rects' corners and polygons' points (CCW) */
    double *memory;        /* the one block the arrays above live in */
    int ready;             /* __init__ ran once and read every argument */
} BodyKernel;

/* Some edge line of the CCW polygon p has every point of q strictly outside it
   (segment_tests.edge_separates). */
static int edge_separates(const double *pxs, const double *pys, Py_ssize_t np,
                          const double *qxs, const double *qys, Py_ssize_t nq)
{
    double ax = pxs[np - 1], ay = pys[np - 1];
    for (Py_ssize_t i = 0; i < np; i++) {
        double bx = pxs[i], by = pys[i];
        double ex = bx - ax, ey = by - ay;
        int separated = 1;
        for (Py_ssize_t j = 0; j < nq; j++) {
            if (ex * (qys[j] - ay) - ey * (qxs[j] - ax) >= 0.0) {
                separated = 0;
                break;
            }
        }
        if (separated)
            return 1;
        ax = bx;
        ay = by;
    }
    return 0;
}

/* c within sqrt(r2) of the closed segment ab (segment_tests.near_segment). */
static int near_segment(double ax, double ay, double bx, double by,
                        double cx, double cy, double r2)
{
    double ex = bx - ax, ey = by - ay, wx = cx - ax, wy = cy - ay;
    double t = ex * wx + ey * wy;
    if (t <= 0.0)
        return wx * wx + wy * wy <= r2;
    double l2 = ex * ex + ey * ey;
    if (t >= l2) {
        double dx = cx - bx, dy = cy - by;
        return dx * dx + dy * dy <= r2;
    }
    double cr = ex * wy - ey * wx;
    return cr * cr <= r2 * l2;
}

/* The closed polygon and the closed disc meet (body_tests.poly_disc). */
static int poly_disc(const double *xs, const double *ys, Py_ssize_t n,
                     double cx, double cy, double r)
{
    double r2 = r * r;
    int inside = 1;
    double ax = xs[n - 1], ay = ys[n - 1];
    for (Py_ssize_t i = 0; i < n; i++) {
        double bx = xs[i], by = ys[i];
        double ex = bx - ax, ey = by - ay;
        double cr = ex * (cy - ay) - ey * (cx - ax);
        if (cr < 0.0) {
            inside = 0;
            if (cr * cr > r2 * (ex * ex + ey * ey))
                return 0;
            if (near_segment(ax, ay, bx, by, cx, cy, r2))
                return 1;
        }
        ax = bx;
        ay = by;
    }
    return inside;
}

/* The body's points placed at (x, y, theta) into px, py
   (body_tests.placed_coordinates). */
static void place(BodyKernel *k, double x, double y, double theta)
{
    double c, s;
    if (isinf(theta)) { /* math.cos raises there; the reference takes NaNs */
        c = s = NAN;
    } else {
        c = cos(theta);
        s = sin(theta);
    }
    if (fabs(c) < SNAP)
        c = 0.0;
    if (fabs(s) < SNAP)
        s = 0.0;
    for (Py_ssize_t i = 0; i < k->n; i++) {
        k->px[i] = x + c * k->bx[i] - s * k->by[i];
        k->py[i] = y + s * k->bx[i] + c * k->by[i];
    }
}

/* (min, max) of the values, compared as body_tests._extent does. */
static void extent(const double *values, Py_ssize_t n, double *lo, double *hi)
{
    *lo = *hi = values[0];
    for (Py_ssize_t i = 0; i < n; i++) {
        if (values[i] < *lo)
            *lo = values[i];
        if (values[i] > *hi)
            *hi = values[i];
    }
}

static int meets_obstacle(BodyKernel *k, Py_ssize_t i)
{
    const double *xs = k->ox + k->first[i], *ys = k->oy + k->first[i];
    Py_ssize_t count = k->first[i + 1] - k->first[i];
    switch (k->kinds[i]) {
    case DISC:
        return poly_disc(k->px, k->py, k->n, k->discs[3 * i], k->discs[3 * i + 1],
                         k->discs[3 * i + 2]);
    case RECT: /* the rect's axes: the bounding boxes already overlap */
        return !edge_separates(k->px, k->py, k->n, xs, ys, count);
    default:
        return !(edge_separates(k->px, k->py, k->n, xs, ys, count)
                 || edge_separates(xs, ys, count, k->px, k->py, k->n));
    }
}

/* Placed at (x, y, theta), the body leaves the box or meets an obstacle. */
static int meets(BodyKernel *k, double x, double y, double theta)
{
    double x0, x1, y0, y1;
    place(k, x, y, theta);
    extent(k->px, k->n, &x0, &x1);
    extent(k->py, k->n, &y0, &y1);
    const double *box = k->box;
    if (!(x0 <= x1 && y0 <= y1 && box[0] <= x0 && x1 <= box[2]
          && box[1] <= y0 && y1 <= box[3]))
        return 1;
    for (Py_ssize_t i = 0; i < k->m; i++) {
        const double *b = k->boxes + 4 * i;
        if (b[0] <= x1 && x0 <= b[2] && b[1] <= y1 && y0 <= b[3] && meets_obstacle(k, i))
            return 1;
    }
    return 0;
}

/* ---- clearance: a point's distance to the obstacles and the box's sides ---- */

static PyObject *hypot_function; /* Python's math.hypot: its floats, not libm's hypot */

/* math.hypot(a, b); NaN with an exception set when it fails (out of memory). */
static double py_hypot(double a, double b)
{
    PyObject *args[2] = {PyFloat_FromDouble(a), PyFloat_FromDouble(b)};
    double value = NAN;
    if (args[0] != NULL && args[1] != NULL) {
        PyObject *result = PyObject_Vectorcall(hypot_function, args, 2, NULL);
        if (result != NULL) {
            value = PyFloat_AsDouble(result);
            Py_DECREF(result);
        }
    }
    Py_XDECREF(args[0]);
    Py_XDECREF(args[1]);
    return value;
}

/* Python's two-argument min() and max(): the second only when strictly less/greater. */
static double min2(double a, double b) { return b < a ? b : a; }
static double max2(double a, double b) { return b > a ? b : a; }

/* segment_tests.nearer: min(best, hypot(px, py)), the hypot only where it may win. */
static double nearer(double best, double px, double py)
{
    if (max2(fabs(px), fabs(py)) < best) {
        double d = py_hypot(px, py);
        if (d < best)
            return d;
    }
    return best;
}

/* segment_tests.polygon_distance: the point to the closed CCW polygon (0 inside). */
static double polygon_distance(const double *xs, const double *ys, Py_ssize_t n,
                               double x, double y)
{
    if (!edge_separates(xs, ys, n, &x, &y, 1))
        return 0.0;
    double best = INFINITY, ax = xs[n - 1], ay = ys[n - 1];
    for (Py_ssize_t i = 0; i < n; i++) {
        double bx = xs[i], by = ys[i];
        double ex = bx - ax, ey = by - ay, wx = x - ax, wy = y - ay; /* segment_offset */
        double l2 = ex * ex + ey * ey;
        double t = l2 == 0.0 ? 0.0 : min2(1.0, max2(0.0, (ex * wx + ey * wy) / l2));
        best = nearer(best, wx - t * ex, wy - t * ey);
        ax = bx;
        ay = by;
    }
    return best;
}

/* body_tests.obstacle_distance: the point to obstacle i. */
static double obstacle_distance(BodyKernel *k, Py_ssize_t i, double x, double y)
{
    const double *b = k->boxes + 4 * i, *d = k->discs + 3 * i;
    switch (k->kinds[i]) {
    case DISC:
        return max2(0.0, py_hypot(x - d[0], y - d[1]) - d[2]);
    case RECT:
        return py_hypot(max2(max2(b[0] - x, 0.0), x - b[2]), max2(max2(b[1] - y, 0.0), y - b[3]));
    default:
        return polygon_distance(k->ox + k->first[i], k->oy + k->first[i],
                                k->first[i + 1] - k->first[i], x, y);
    }
}

/* body_tests.clearance: the point to the nearest obstacle or box side. */
static double clearance(BodyKernel *k, double x, double y)
{
    const double *box = k->box;
    double gap = INFINITY;
    if (k->has_box)
        gap = max2(0.0, min2(min2(min2(x - box[0], box[2] - x), y - box[1]), box[3] - y));
    for (Py_ssize_t i = 0; i < k->m; i++) {
        const double *b = k->boxes + 4 * i;
        if (max2(b[0] - x, x - b[2]) < gap && max2(b[1] - y, y - b[3]) < gap)
            gap = min2(gap, obstacle_distance(k, i, x, y));
    }
    return gap;
}

/* ---- Python glue: arguments in, the arrays filled once ---- */

static int read_doubles(PyObject *sequence, double *out, Py_ssize_t count)
{
    PyObject *fast = PySequence_Fast(sequence, "BodyKernel: a sequence of floats expected");
    if (fast == NULL)
        return -1;
    if (PySequence_Fast_GET_SIZE(fast) != count) {
        PyErr_SetString(PyExc_ValueError, "BodyKernel: a sequence of the wrong length");
        Py_DECREF(fast);
        return -1;
    }
    for (Py_ssize_t i = 0; i < count; i++) {
        out[i] = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(fast, i));
        if (out[i] == -1.0 && PyErr_Occurred()) {
            Py_DECREF(fast);
            return -1;
        }
    }
    Py_DECREF(fast);
    return 0;
}

static Py_ssize_t length(PyObject *sequence)
{
    Py_ssize_t n = PySequence_Size(sequence);
    if (n < 0)
        PyErr_SetString(PyExc_TypeError, "BodyKernel: a sequence expected");
    return n;
}

/* Obstacle i's kind, bounding box, disc and points into the arrays. */
static int read_obstacle(BodyKernel *k, Py_ssize_t i, PyObject *kinds, PyObject *boxes,
                         PyObject *xs, PyObject *ys, PyObject *discs)
{
    PyObject *items[5] = {PySequence_GetItem(kinds, i), PySequence_GetItem(boxes, i),
                          PySequence_GetItem(xs, i), PySequence_GetItem(ys, i),
                          PySequence_GetItem(discs, i)};
    int status = -1;
    if (items[0] && items[1] && items[2] && items[3] && items[4]) {
        long kind = PyLong_AsLong(items[0]);
        Py_ssize_t count = k->first[i + 1] - k->first[i];
        k->kinds[i] = (int)kind;
        if (!(kind == -1 && PyErr_Occurred())
            && read_doubles(items[1], k->boxes + 4 * i, 4) == 0
            && read_doubles(items[2], k->ox + k->first[i], count) == 0
            && read_doubles(items[3], k->oy + k->first[i], count) == 0
            && read_doubles(items[4], k->discs + 3 * i, 3) == 0)
            status = 0;
        if (status == 0 && kind != DISC && count < 1) {
            PyErr_SetString(PyExc_ValueError, "BodyKernel: a rect or polygon without points");
            status = -1;
        }
    }
    for (int j = 0; j < 5; j++)
        Py_XDECREF(items[j]);
    return status;
}

/* The offsets of the obstacles' points (k->first, allocated here): -1 on error. */
static Py_ssize_t point_offsets(BodyKernel *k, PyObject *xs)
{
    k->first = PyMem_New(Py_ssize_t, k->m + 1);
    if (k->first == NULL) {
        PyErr_NoMemory();
        return -1;
    }
    k->first[0] = 0;
    for (Py_ssize_t i = 0; i < k->m; i++) {
        PyObject *item = PySequence_GetItem(xs, i);
        Py_ssize_t count = item ? length(item) : -1;
        Py_XDECREF(item);
        if (count < 0)
            return -1;
        k->first[i + 1] = k->first[i] + count;
    }
    return k->first[k->m];
}

static int kernel_init(BodyKernel *k, PyObject *args, PyObject *kwargs)
{
    PyObject *body_xs, *body_ys, *box, *kinds, *boxes, *xs, *ys, *discs;
    int has_box;
    static char *names[] = {"body_xs", "body_ys", "has_box", "box", "kinds", "boxes", "xs",
                            "ys", "discs", NULL};
    if (k->first != NULL || k->kinds != NULL || k->memory != NULL) {
        PyErr_SetString(PyExc_RuntimeError, "BodyKernel: already initialised");
        return -1;
    }
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOpOOOOOO", names, &body_xs, &body_ys,
                                     &has_box, &box, &kinds, &boxes, &xs, &ys, &discs))
        return -1;
    k->has_box = has_box;
    k->n = length(body_xs);
    k->m = length(kinds);
    if (k->n < 0 || k->m < 0)
        return -1;
    if (k->n < 1) {
        PyErr_SetString(PyExc_ValueError, "BodyKernel: a body without points");
        return -1;
    }
    Py_ssize_t points = point_offsets(k, xs);
    if (points < 0)
        return -1;
    k->kinds = PyMem_New(int, k->m + 1);
    k->memory = PyMem_New(double, 4 * k->n + 7 * k->m + 2 * points + 1);
    if (k->kinds == NULL || k->memory == NULL) {
        PyErr_NoMemory();
        return -1;
    }
    k->bx = k->memory;
    k->by = k->bx + k->n;
    k->px = k->by + k->n;
    k->py = k->px + k->n;
    k->boxes = k->py + k->n;
    k->discs = k->boxes + 4 * k->m;
    k->ox = k->discs + 3 * k->m;
    k->oy = k->ox + points;
    if (read_doubles(body_xs, k->bx, k->n) < 0 || read_doubles(body_ys, k->by, k->n) < 0
        || read_doubles(box, k->box, 4) < 0)
        return -1;
    for (Py_ssize_t i = 0; i < k->m; i++) {
        if (read_obstacle(k, i, kinds, boxes, xs, ys, discs) < 0)
            return -1;
    }
    k->ready = 1;
    return 0;
}

static void kernel_dealloc(BodyKernel *k)
{
    PyMem_Free(k->first);
    PyMem_Free(k->kinds);
    PyMem_Free(k->memory);
    Py_TYPE(k)->tp_free((PyObject *)k);
}

/* The count floats of args into out; -1 with an exception when they are not. */
static int floats(BodyKernel *k, PyObject *const *args, Py_ssize_t nargs, double *out,
                  Py_ssize_t count)
{
    if (!k->ready) {
        PyErr_SetString(PyExc_RuntimeError, "BodyKernel: not initialised");
        return -1;
    }
    if (nargs != count) {
        PyErr_Format(PyExc_TypeError, "BodyKernel: %zd floats expected", count);
        return -1;
    }
    for (Py_ssize_t i = 0; i < count; i++) {
        out[i] = PyFloat_AsDouble(args[i]);
        if (out[i] == -1.0 && PyErr_Occurred())
            return -1;
    }
    return 0;
}

static PyObject *kernel_meets(BodyKernel *k, PyObject *const *args, Py_ssize_t nargs)
{
    double p[3];
    if (floats(k, args, nargs, p, 3) < 0)
        return NULL;
    return PyBool_FromLong(meets(k, p[0], p[1], p[2]));
}

static PyObject *kernel_clearance(BodyKernel *k, PyObject *const *args, Py_ssize_t nargs)
{
    double p[2];
    if (floats(k, args, nargs, p, 2) < 0)
        return NULL;
    double gap = clearance(k, p[0], p[1]);
    return PyErr_Occurred() ? NULL : PyFloat_FromDouble(gap);
}

static PyObject *kernel_placed(BodyKernel *k, PyObject *const *args, Py_ssize_t nargs)
{
    double p[3];
    if (floats(k, args, nargs, p, 3) < 0)
        return NULL;
    place(k, p[0], p[1], p[2]);
    PyObject *xs = PyList_New(k->n), *ys = PyList_New(k->n);
    for (Py_ssize_t i = 0; xs != NULL && ys != NULL && i < k->n; i++) {
        PyList_SET_ITEM(xs, i, PyFloat_FromDouble(k->px[i]));
        PyList_SET_ITEM(ys, i, PyFloat_FromDouble(k->py[i]));
    }
    PyObject *pair = (xs != NULL && ys != NULL) ? PyTuple_Pack(2, xs, ys) : NULL;
    Py_XDECREF(xs);
    Py_XDECREF(ys);
    return pair;
}

static PyMethodDef kernel_methods[] = {
    {"meets", (PyCFunction)(void (*)(void))kernel_meets, METH_FASTCALL,
     "meets(x, y, theta): placed there, the body leaves the box or meets an obstacle."},
    {"clearance", (PyCFunction)(void (*)(void))kernel_clearance, METH_FASTCALL,
     "clearance(x, y): the point's distance to the world, as body_tests.clearance."},
    {"placed", (PyCFunction)(void (*)(void))kernel_placed, METH_FASTCALL,
     "placed(x, y, theta): the placed points' (xs, ys), as body_tests.placed_coordinates."},
    {NULL, NULL, 0, NULL},
};

static PyTypeObject BodyKernelType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "planning_core.worlds._body_kernel.BodyKernel",
    .tp_doc = "A body's points and a world's box and obstacles, as C arrays.",
    .tp_basicsize = sizeof(BodyKernel),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)kernel_init,
    .tp_dealloc = (destructor)kernel_dealloc,
    .tp_methods = kernel_methods,
};

static struct PyModuleDef kernel_module = {
    PyModuleDef_HEAD_INIT, "_body_kernel",
    "The body test's C kernel (reference: the shapes' ContinuousWorld.first_obstacle).",
    -1, NULL,
};

PyMODINIT_FUNC PyInit__body_kernel(void)
{
    if (PyType_Ready(&BodyKernelType) < 0)
        return NULL;
    if (hypot_function == NULL) {
        PyObject *math = PyImport_ImportModule("math");
        if (math == NULL)
            return NULL;
        hypot_function = PyObject_GetAttrString(math, "hypot");
        Py_DECREF(math);
        if (hypot_function == NULL)
            return NULL;
    }
    PyObject *module = PyModule_Create(&kernel_module);
    if (module == NULL)
        return NULL;
    if (PyModule_AddIntConstant(module, "RECT", RECT) < 0
        || PyModule_AddIntConstant(module, "DISC", DISC) < 0
        || PyModule_AddIntConstant(module, "POLYGON", POLYGON) < 0
        || PyModule_AddType(module, &BodyKernelType) < 0) {
        Py_DECREF(module);
        return NULL;
    }
    return module;
}
