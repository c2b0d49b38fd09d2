// OMPL with C++ callbacks on the family (SPEC 5), the practical limit for these planners
// (issue 19). The set-up of benchmarks/ompl_family.py, in C++:
//   state space: a compound of SO2 and bounded RealVector subspaces, one per metric group
//     (a group holding an angle and more than one variable: one subspace per variable),
//     variables in no group in a subspace of weight 0; OMPL's distance is then our metric
//     up to those per-variable sums (nearest neighbours only);
//   validity: bounds; the arm's two links (closed segments) or the body placed at
//     (x, y, theta) inside the closed world box and off every closed obstacle, by exact
//     tests (separating axes; closest point for a disc) behind a bounding-box check;
//     the pendulum: bounds only;
//   goal: our metric restricted to the goal's variables, threshold a hair inside the
//     tolerance;
//   geometric (arm2, rigid2): motions of our metric's length d checked at the
//     n = max(1, ceil(d / check)) samples after the start (SPEC 5.2); RRT (goal bias
//     0.05), RRTConnect, PRM, PRM*, RRT* or Informed RRT* (OMPL's defaults) minimizing
//     path length in our metric (OMPL's objective where OMPL's distance is our metric and
//     the planner is RRT* or a PRM, else one calling our metric, as the Python peer; PRM
//     and PRM* end at their first path, as ours);
//   kinodynamic (pendulum, car2, unicycle, car1): our slice (SPEC 5.2's euler or rk4,
//     the same float operations in the same order as planning_core/integrators.py) as
//     the propagator, OMPL's step DT, KMIN..KMAX steps a control; control RRT (goal bias
//     0.05), KPIECE1 (OMPL's defaults, the grid over our KPIECE1's projection, from the
//     input) or SST (our SST's radii, from the input) minimizing the duration: a weight-0
//     subspace counts the slices from the start, a motion costs its slices times DT.
// Input on stdin: the flat problem benchmarks/ompl_cpp_programs.py writes (family_input).
// Usage: family_ompl rrt|rrtconnect|prm|prmstar|rrtstar|informed|kpiece|sst TIME_LIMIT SEED
//        [optimize]
//   optimize: RRT*, Informed RRT* and SST keep improving until the limit.
// Prints the path on stdout in SPEC 5.4's format (no tree), so the validator can check
// it, and common.h's stats line (with " motion_checks=M" for a geometric problem) and,
// with optimize, its progress line on stderr. Exit 0 solved, 2 bad usage, 3 unsolved.
#include "common.h"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <ompl/control/SimpleSetup.h>
#include <ompl/control/planners/rrt/RRT.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <algorithm>
#include <iostream>

namespace ob = ompl::base;
namespace oc = ompl::control;
namespace og = ompl::geometric;
using ompl_cpp::Run;

static const double TAU = 2.0 * M_PI, SNAP = 1e-12;

struct Point { double x, y; };

struct Obstacle {
    char kind;                 // 'R' rect, 'C' circle, 'P' convex polygon
    double x0, y0, x1, y1;     // bounding box
    double cx = 0, cy = 0, r = 0;
    std::vector<Point> points; // rect corners or polygon vertices
};

struct Problem {
    std::string system;
    std::vector<bool> angle;
    std::vector<double> low, high;
    std::vector<std::pair<double, std::vector<int>>> groups;
    double check = 0.01;                    // geometric
    bool kinodynamic = false;
    std::string scheme;                     // kinodynamic: euler | rk4
    double dt = 0, param = 0;               // param: the pendulum's g, car1's L
    int kmin = 1, kmax = 1;
    std::vector<double> controlLow, controlHigh;
    double selection = 0, pruning = 0;      // our SST's radii
    std::vector<std::pair<int, std::pair<double, double>>> cells;  // KPIECE1: (index, (low, scale))
    double bx = 0, by = 0, l1 = 1, l2 = 1;  // arm2
    std::vector<Point> body;                // rigid2, the cars
    bool hasBox = false;
    double X0 = 0, Y0 = 0, X1 = 0, Y1 = 0;
    std::vector<Obstacle> obstacles;
    std::vector<double> start;
    double tolerance = 0;
    std::vector<std::pair<int, double>> goal;
};

// ---- geometry: closed shapes, touching is a collision ----

// Some edge line of `a` (either winding) has all of `b` strictly beyond it.
static bool edgeSeparates(const std::vector<Point> &a, const std::vector<Point> &b) {
    const size_t n = a.size();
    double area = 0;
    for (size_t i = 0; i < n; ++i) {
        const Point &p = a[i], &q = a[(i + 1) % n];
        area += p.x * q.y - q.x * p.y;
    }
    const double sign = area >= 0 ? 1.0 : -1.0;
    for (size_t i = 0; i < n; ++i) {
        const Point &p = a[i], &q = a[(i + 1) % n];
        const double ex = q.x - p.x, ey = q.y - p.y;
        bool allOut = true;
        for (const Point &v : b) {
            if (sign * (ex * (v.y - p.y) - ey * (v.x - p.x)) >= 0) { allOut = false; break; }
        }
        if (allOut) return true;
    }
    return false;
}

// The segment's line has all of `pts` strictly on one side.
static bool lineSeparates(const Point &a, const Point &b, const std::vector<Point> &pts) {
    const double ex = b.x - a.x, ey = b.y - a.y;
    bool pos = false, neg = false;
    for (const Point &v : pts) {
        const double c = ex * (v.y - a.y) - ey * (v.x - a.x);
        if (c >= 0) pos = true;
        if (c <= 0) neg = true;
    }
    return !(pos && neg);
}

static double segmentDistance2(const Point &a, const Point &b, double px, double py) {
    const double ex = b.x - a.x, ey = b.y - a.y, len2 = ex * ex + ey * ey;
    double t = len2 > 0 ? ((px - a.x) * ex + (py - a.y) * ey) / len2 : 0.0;
    t = std::min(1.0, std::max(0.0, t));
    const double dx = a.x + t * ex - px, dy = a.y + t * ey - py;
    return dx * dx + dy * dy;
}

static bool polygonMeetsDisc(const std::vector<Point> &pts, const Obstacle &o) {
    const size_t n = pts.size();
    bool inside = true;
    double area = 0;
    for (size_t i = 0; i < n; ++i) area += pts[i].x * pts[(i + 1) % n].y - pts[(i + 1) % n].x * pts[i].y;
    const double sign = area >= 0 ? 1.0 : -1.0;
    for (size_t i = 0; i < n; ++i) {
        const Point &a = pts[i], &b = pts[(i + 1) % n];
        if (sign * ((b.x - a.x) * (o.cy - a.y) - (b.y - a.y) * (o.cx - a.x)) < 0) inside = false;
        if (segmentDistance2(a, b, o.cx, o.cy) <= o.r * o.r) return true;
    }
    return inside;
}

static bool boxesMeet(double x0, double y0, double x1, double y1, const Obstacle &o) {
    return o.x0 <= x1 && x0 <= o.x1 && o.y0 <= y1 && y0 <= o.y1;
}

// A polygon (a placed body, or a segment as a 2-gon) is inside the box and off every obstacle.
static bool shapeFree(const Problem &p, const std::vector<Point> &pts, bool segment) {
    double x0 = pts[0].x, x1 = x0, y0 = pts[0].y, y1 = y0;
    for (const Point &v : pts) {
        x0 = std::min(x0, v.x); x1 = std::max(x1, v.x);
        y0 = std::min(y0, v.y); y1 = std::max(y1, v.y);
    }
    if (!(x0 <= x1 && y0 <= y1)) return false;  // NaN
    if (p.hasBox && !(p.X0 <= x0 && x1 <= p.X1 && p.Y0 <= y0 && y1 <= p.Y1)) return false;
    for (const Obstacle &o : p.obstacles) {
        if (!boxesMeet(x0, y0, x1, y1, o)) continue;
        if (o.kind == 'C') {
            if (segment ? segmentDistance2(pts[0], pts[1], o.cx, o.cy) <= o.r * o.r
                        : polygonMeetsDisc(pts, o)) return false;
        } else if (segment) {
            if (!edgeSeparates(o.points, pts) && !lineSeparates(pts[0], pts[1], o.points))
                return false;
        } else if (!edgeSeparates(o.points, pts) && !edgeSeparates(pts, o.points)) {
            return false;
        }
    }
    return true;
}

// ---- the problem's state: validity, metric, interpolation, dynamics ----

struct Family {
    Problem p;
    std::vector<std::pair<int, int>> slot;  // per variable: subspace, index in it
    int counter = -1;                       // kinodynamic: the slice count's subspace
    bool exactMetric = true;                // OMPL's distance is our metric

    bool valid(const double *q) const {
        for (size_t i = 0; i < p.angle.size(); ++i) {
            if (!std::isfinite(q[i])) return false;
            if (!p.angle[i] && !(p.low[i] <= q[i] && q[i] <= p.high[i])) return false;
        }
        if (p.system == "pendulum") return true;
        if (p.system == "arm2") {
            const double c1 = std::cos(q[0]), s1 = std::sin(q[0]);
            const double c2 = std::cos(q[0] + q[1]), s2 = std::sin(q[0] + q[1]);
            const Point base{p.bx, p.by}, elbow{p.bx + p.l1 * c1, p.by + p.l1 * s1};
            const Point tip{elbow.x + p.l2 * c2, elbow.y + p.l2 * s2};
            return shapeFree(p, {base, elbow}, true) && shapeFree(p, {elbow, tip}, true);
        }
        double c = std::cos(q[2]), s = std::sin(q[2]);
        if (std::fabs(c) < SNAP) c = 0.0;
        if (std::fabs(s) < SNAP) s = 0.0;
        std::vector<Point> placed;
        placed.reserve(p.body.size());
        for (const Point &v : p.body)
            placed.push_back({q[0] + c * v.x - s * v.y, q[1] + s * v.x + c * v.y});
        return shapeFree(p, placed, false);
    }

    double difference(int i, double a, double b) const {
        return p.angle[i] ? std::remainder(b - a, TAU) : b - a;
    }

    double distance(const double *a, const double *b) const {
        double total = 0;
        for (const auto &group : p.groups) {
            double sum = 0;
            for (int i : group.second) { const double d = difference(i, a[i], b[i]); sum += d * d; }
            total += group.first * std::sqrt(sum);
        }
        return total;
    }

    // SPEC 5.2's rates, each written as the system's expression (planning_core/systems).
    void rates(const double *s, const double *u, double *r) const {
        if (p.system == "pendulum") { r[0] = s[1]; r[1] = -p.param * std::cos(s[0]) + u[0]; }
        else if (p.system == "car1") {
            r[0] = u[0] * std::cos(s[2]); r[1] = u[0] * std::sin(s[2]);
            r[2] = (u[0] / p.param) * std::tan(u[1]);
        } else {  // car2, unicycle
            r[0] = s[3] * std::cos(s[2]); r[1] = s[3] * std::sin(s[2]);
            r[2] = p.system == "car2" ? u[0] : s[4];
            r[3] = p.system == "car2" ? u[1] : u[0];
            if (p.system == "unicycle") r[4] = u[1];
        }
    }

    // One slice of DT (planning_core/integrators.py's euler_slice or rk4_slice).
    void slice(const double *s, const double *u, double *out) const {
        const size_t n = slot.size();
        double k1[8], k2[8], k3[8], k4[8], mid[8];
        rates(s, u, k1);
        if (p.scheme == "euler") {
            for (size_t i = 0; i < n; ++i) out[i] = s[i] + p.dt * k1[i];
        } else {
            const double half = p.dt / 2.0, sixth = p.dt / 6.0;
            for (size_t i = 0; i < n; ++i) mid[i] = s[i] + half * k1[i];
            rates(mid, u, k2);
            for (size_t i = 0; i < n; ++i) mid[i] = s[i] + half * k2[i];
            rates(mid, u, k3);
            for (size_t i = 0; i < n; ++i) mid[i] = s[i] + p.dt * k3[i];
            rates(mid, u, k4);
            for (size_t i = 0; i < n; ++i)
                out[i] = s[i] + sixth * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        for (size_t i = 0; i < n; ++i) if (p.angle[i]) out[i] = std::remainder(out[i], TAU);
    }

    void get(const ob::State *s, double *q) const {
        const auto *c = s->as<ob::CompoundState>();
        for (size_t i = 0; i < slot.size(); ++i) {
            const ob::State *sub = c->components[slot[i].first];
            q[i] = p.angle[i] ? sub->as<ob::SO2StateSpace::StateType>()->value
                              : sub->as<ob::RealVectorStateSpace::StateType>()->values[slot[i].second];
        }
    }

    void put(ob::State *s, const double *q) const {
        auto *c = s->as<ob::CompoundState>();
        for (size_t i = 0; i < slot.size(); ++i) {
            ob::State *sub = c->components[slot[i].first];
            if (p.angle[i]) sub->as<ob::SO2StateSpace::StateType>()->value = q[i];
            else sub->as<ob::RealVectorStateSpace::StateType>()->values[slot[i].second] = q[i];
        }
    }

    // Kinodynamic: the slices from the start to this state.
    double &slices(ob::State *s) const {
        return s->as<ob::CompoundState>()->components[counter]
            ->as<ob::RealVectorStateSpace::StateType>()->values[0];
    }
    double slices(const ob::State *s) const { return slices(const_cast<ob::State *>(s)); }
};

// SPEC 5.2's motion check: the n samples after the start, n = max(1, ceil(d / check)).
class SampledMotions : public ob::MotionValidator {
public:
    SampledMotions(const ob::SpaceInformationPtr &si, const Family &f) : ob::MotionValidator(si), f_(f) {}
    bool checkMotion(const ob::State *s1, const ob::State *s2) const override {
        const size_t n = f_.slot.size();
        double a[8], b[8], q[8];
        f_.get(s1, a); f_.get(s2, b);
        const int steps = std::max(1, static_cast<int>(std::ceil(f_.distance(a, b) / f_.p.check)));
        for (int k = 1; k <= steps; ++k) {
            const double t = static_cast<double>(k) / steps;
            for (size_t i = 0; i < n; ++i) {
                const double d = f_.difference(i, a[i], b[i]);
                const double v = t < 0.5 ? a[i] + t * d : b[i] - (1.0 - t) * d;
                q[i] = f_.p.angle[i] ? std::remainder(v, TAU) : v;
            }
            if (!f_.valid(q)) { ++invalid_; return false; }
        }
        ++valid_;
        return true;
    }
    bool checkMotion(const ob::State *s1, const ob::State *s2,
                     std::pair<ob::State *, double> &) const override {
        return checkMotion(s1, s2);
    }
private:
    const Family &f_;
};

class FamilyGoal : public ob::GoalSampleableRegion {
public:
    FamilyGoal(const ob::SpaceInformationPtr &si, const Family &f) : ob::GoalSampleableRegion(si), f_(f) {
        setThreshold(f.p.tolerance * (1.0 - 1e-9));
        for (const auto &group : f.p.groups) {  // the metric restricted to the goal's variables
            std::vector<int> kept;
            for (int i : group.second)
                for (const auto &g : f.p.goal) if (g.first == i) kept.push_back(i);
            if (!kept.empty()) groups_.push_back({group.first, kept});
        }
        target_.assign(f.slot.size(), 0.0);
        for (const auto &g : f.p.goal) target_[g.first] = g.second;
    }
    double distanceGoal(const ob::State *s) const override {
        double q[8], total = 0;
        f_.get(s, q);
        for (const auto &group : groups_) {
            double sum = 0;
            for (int i : group.second) { const double d = f_.difference(i, q[i], target_[i]); sum += d * d; }
            total += group.first * std::sqrt(sum);
        }
        return total;
    }
    void sampleGoal(ob::State *s) const override {
        double q[8];
        sampler_->sampleUniform(s);
        f_.get(s, q);
        for (const auto &g : f_.p.goal) q[g.first] = g.second;
        f_.put(s, q);
    }
    unsigned int maxSampleCount() const override {
        return f_.p.goal.size() == f_.slot.size() ? 1 : 1000000;
    }
    void setSampler(const ob::StateSamplerPtr &sampler) { sampler_ = sampler; }
private:
    const Family &f_;
    std::vector<std::pair<double, std::vector<int>>> groups_;
    std::vector<double> target_;
    ob::StateSamplerPtr sampler_;
};

// Path length in our metric (where OMPL's distance is not it, or for Informed RRT*: OMPL's
// direct informed sampler refuses our compound space, as in the Python peer).
class MetricLength : public ob::OptimizationObjective {
public:
    MetricLength(const ob::SpaceInformationPtr &si, const Family &f)
        : ob::OptimizationObjective(si), f_(f) {}
    ob::Cost stateCost(const ob::State *) const override { return identityCost(); }
    ob::Cost motionCost(const ob::State *a, const ob::State *b) const override {
        double qa[8], qb[8];
        f_.get(a, qa); f_.get(b, qb);
        return ob::Cost(f_.distance(qa, qb));
    }
private:
    const Family &f_;
};

// A kinodynamic motion's duration: its slices times DT.
class Duration : public ob::OptimizationObjective {
public:
    Duration(const ob::SpaceInformationPtr &si, const Family &f)
        : ob::OptimizationObjective(si), f_(f) {}
    ob::Cost stateCost(const ob::State *) const override { return identityCost(); }
    ob::Cost motionCost(const ob::State *a, const ob::State *b) const override {
        return ob::Cost((f_.slices(b) - f_.slices(a)) * f_.p.dt);
    }
private:
    const Family &f_;
};

// ---- input ----

static bool readNumbers(std::istream &in, std::vector<double> &values, size_t count) {
    values.resize(count);
    for (double &v : values) if (!(in >> v)) return false;
    return true;
}

static bool readVariables(std::istream &in, Problem &p) {
    std::string word;
    int n, count;
    if (!(in >> word >> p.system >> word >> n) || n < 1 || n > 8) return false;
    p.angle.resize(n); p.low.resize(n); p.high.resize(n);
    for (int i = 0; i < n; ++i) {
        int a;
        if (!(in >> a >> p.low[i] >> p.high[i])) return false;
        p.angle[i] = a != 0;
    }
    if (!(in >> word >> count)) return false;
    for (int g = 0; g < count; ++g) {
        double w; int k;
        if (!(in >> w >> k)) return false;
        std::vector<int> idx(k);
        for (int &i : idx) if (!(in >> i) || i < 0 || i >= n) return false;
        p.groups.push_back({w, idx});
    }
    return true;
}

// "check STEP" (geometric) or "dynamics SCHEME DT KMIN KMAX PARAM / controls M LO HI ... /
// sst SELECTION PRUNING / kpiece N INDEX LOW SCALE ..." (kinodynamic); then "arm ..."
// (arm2) or "body N X Y ...".
static bool readSystem(std::istream &in, Problem &p) {
    std::string word;
    int count;
    p.kinodynamic = p.system != "arm2" && p.system != "rigid2";
    if (!p.kinodynamic) {
        if (!(in >> word >> p.check)) return false;
    } else {
        if (!(in >> word >> p.scheme >> p.dt >> p.kmin >> p.kmax >> p.param >> word >> count)
            || count < 1 || count > 8 || p.kmin < 1 || p.kmax < p.kmin) return false;
        p.controlLow.resize(count); p.controlHigh.resize(count);
        for (int i = 0; i < count; ++i)
            if (!(in >> p.controlLow[i] >> p.controlHigh[i])) return false;
        if (!(in >> word >> p.selection >> p.pruning >> word >> count) || count < 1 || count > 8)
            return false;
        p.cells.resize(count);
        for (auto &axis : p.cells)
            if (!(in >> axis.first >> axis.second.first >> axis.second.second)) return false;
    }
    if (p.system == "arm2") return static_cast<bool>(in >> word >> p.bx >> p.by >> p.l1 >> p.l2);
    if (!(in >> word >> count) || (count < 3 && !(p.system == "pendulum" && count == 0)))
        return false;
    p.body.resize(count);
    for (Point &v : p.body) if (!(in >> v.x >> v.y)) return false;
    return true;
}

static bool readObstacle(std::istream &in, Obstacle &o) {
    if (!(in >> o.kind)) return false;
    if (o.kind == 'R') {
        if (!(in >> o.x0 >> o.y0 >> o.x1 >> o.y1)) return false;
        o.points = {{o.x0, o.y0}, {o.x1, o.y0}, {o.x1, o.y1}, {o.x0, o.y1}};
    } else if (o.kind == 'C') {
        if (!(in >> o.cx >> o.cy >> o.r)) return false;
        o.x0 = o.cx - o.r; o.x1 = o.cx + o.r; o.y0 = o.cy - o.r; o.y1 = o.cy + o.r;
    } else if (o.kind == 'P') {
        int m;
        if (!(in >> m) || m < 3) return false;
        o.points.resize(m);
        for (Point &v : o.points) if (!(in >> v.x >> v.y)) return false;
        o.x0 = o.x1 = o.points[0].x; o.y0 = o.y1 = o.points[0].y;
        for (const Point &v : o.points) {
            o.x0 = std::min(o.x0, v.x); o.x1 = std::max(o.x1, v.x);
            o.y0 = std::min(o.y0, v.y); o.y1 = std::max(o.y1, v.y);
        }
    } else return false;
    return true;
}

static bool readProblem(std::istream &in, Problem &p) {
    std::string word;
    int has, count;
    if (!readVariables(in, p) || !readSystem(in, p) || !(in >> word >> has)) return false;
    p.hasBox = has != 0;
    if (p.hasBox && !(in >> p.X0 >> p.Y0 >> p.X1 >> p.Y1)) return false;
    if (!(in >> word >> count)) return false;
    p.obstacles.resize(count);
    for (Obstacle &o : p.obstacles) if (!readObstacle(in, o)) return false;
    if (!(in >> word) || !readNumbers(in, p.start, p.angle.size())) return false;
    if (!(in >> word >> p.tolerance >> count)) return false;
    const int n = static_cast<int>(p.angle.size());
    for (int k = 0; k < count; ++k) {
        int i; double v;
        if (!(in >> i >> v) || i < 0 || i >= n) return false;
        p.goal.push_back({i, v});
    }
    return true;
}

// ---- set-up ----

static void addSubspace(ob::CompoundStateSpace &space, Family &f, const std::vector<int> &idx,
                        double weight) {
    const int k = space.getSubspaceCount();
    if (f.p.angle[idx[0]]) {
        space.addSubspace(std::make_shared<ob::SO2StateSpace>(), weight);
        f.slot[idx[0]] = {k, 0};
        return;
    }
    auto sub = std::make_shared<ob::RealVectorStateSpace>(idx.size());
    ob::RealVectorBounds bounds(idx.size());
    for (size_t j = 0; j < idx.size(); ++j) {
        bounds.setLow(j, f.p.low[idx[j]]);
        bounds.setHigh(j, f.p.high[idx[j]]);
        f.slot[idx[j]] = {k, static_cast<int>(j)};
    }
    sub->setBounds(bounds);
    space.addSubspace(sub, weight);
}

static std::shared_ptr<ob::CompoundStateSpace> layout(Family &f) {
    auto space = std::make_shared<ob::CompoundStateSpace>();
    const size_t n = f.p.angle.size();
    f.slot.assign(n, {-1, 0});
    std::vector<std::pair<double, std::vector<int>>> parts = f.p.groups;
    std::vector<int> loose;
    for (size_t i = 0; i < n; ++i) {
        bool grouped = false;
        for (const auto &g : f.p.groups)
            grouped = grouped || std::find(g.second.begin(), g.second.end(), i) != g.second.end();
        if (!grouped) loose.push_back(i);
    }
    if (!loose.empty()) parts.push_back({0.0, loose});
    for (const auto &part : parts) {
        bool anyAngle = false;
        for (int i : part.second) anyAngle = anyAngle || f.p.angle[i];
        if (anyAngle && part.second.size() > 1) {
            f.exactMetric = false;
            for (int i : part.second) addSubspace(*space, f, {i}, part.first);
        } else {
            addSubspace(*space, f, part.second, part.first);
        }
    }
    if (f.p.kinodynamic) {  // the slice count, weighing nothing
        auto counter = std::make_shared<ob::RealVectorStateSpace>(1);
        counter->setBounds(0.0, 1e12);
        f.counter = space->getSubspaceCount();
        space->addSubspace(counter, 0.0);
    }
    return space;
}

static void setValidity(ob::SpaceInformation &info, const Family &f) {
    info.setStateValidityChecker([&f](const ob::State *s) {
        double q[8];
        f.get(s, q);
        return f.valid(q);
    });
}

static void setStartAndGoal(ob::ProblemDefinition &problem, const ob::SpaceInformationPtr &info,
                            const Family &f) {
    ob::ScopedState<> start(info->getStateSpace());
    f.put(start.get(), f.p.start.data());
    if (f.p.kinodynamic) f.slices(start.get()) = 0.0;
    problem.addStartState(start);
    auto goal = std::make_shared<FamilyGoal>(info, f);
    goal->setSampler(info->getStateSpace()->allocStateSampler());
    problem.setGoal(goal);
}

// RRT, RRTConnect, PRM, PRM*, RRT* or Informed RRT* on a geometric problem.
static ob::PlannerPtr geometricPlanner(og::SimpleSetup &setup, const Family &f,
                                       const std::string &planner, Run &run) {
    auto info = setup.getSpaceInformation();
    if (planner == "rrtconnect") return std::make_shared<og::RRTConnect>(info);
    if (planner == "rrt") {
        auto rrt = std::make_shared<og::RRT>(info);
        rrt->setGoalBias(0.05);
        return rrt;
    }
    const bool informed = planner == "informed";
    ob::OptimizationObjectivePtr objective;
    if (f.exactMetric && !informed)
        objective = std::make_shared<ob::PathLengthOptimizationObjective>(info);
    else
        objective = std::make_shared<MetricLength>(info, f);
    run.setThreshold(*objective);
    setup.setOptimizationObjective(objective);
    if (ompl_cpp::isRoadmap(planner)) return ompl_cpp::prmPlanner(info, planner == "prmstar");
    return ompl_cpp::starPlanner(info, informed, run);
}

// Control RRT, KPIECE1 or SST on a kinodynamic problem.
static ob::PlannerPtr kinodynamicPlanner(oc::SimpleSetup &setup, const Family &f,
                                         const std::string &planner, Run &run) {
    auto info = setup.getSpaceInformation();
    if (planner == "rrt") {
        auto rrt = std::make_shared<oc::RRT>(info);
        rrt->setGoalBias(0.05);
        return rrt;
    }
    if (planner == "kpiece") {
        auto projection = std::make_shared<ompl_cpp::ScaledProjection>(
            info->getStateSpace(), f.p.cells.size(), [&f](const ob::State *s, double *out) {
                double q[8];
                f.get(s, q);
                for (size_t k = 0; k < f.p.cells.size(); ++k) {
                    const auto &axis = f.p.cells[k];
                    out[k] = (q[axis.first] - axis.second.first) * axis.second.second;
                }
            });
        return ompl_cpp::kpiecePlanner(info, projection);
    }
    auto objective = std::make_shared<Duration>(info, f);
    run.setThreshold(*objective);
    setup.getProblemDefinition()->setOptimizationObjective(objective);
    return ompl_cpp::sstPlanner(info, f.p.selection, f.p.pruning, run);
}

// ---- planning and output ----

static void printState(const Family &f, const ob::State *s) {
    double q[8];
    f.get(s, q);
    for (size_t i = 0; i < f.slot.size(); ++i) std::printf(i ? " %.17g" : "%.17g", q[i]);
}

static bool solveGeometric(Family &f, const std::string &planner, Run &run) {
    auto info = std::make_shared<ob::SpaceInformation>(layout(f));
    setValidity(*info, f);
    info->setMotionValidator(std::make_shared<SampledMotions>(info, f));
    info->setup();
    og::SimpleSetup setup(info);
    setStartAndGoal(*setup.getProblemDefinition(), info, f);
    setup.setPlanner(geometricPlanner(setup, f, planner, run));
    setup.solve(run.conditionFor(planner));
    const bool solved = setup.haveExactSolutionPath();
    const double seconds = run.seconds();
    if (solved) {
        const og::PathGeometric &path = setup.getSolutionPath();
        std::printf("%zu\n", path.getStateCount());
        for (size_t k = 0; k < path.getStateCount(); ++k) {
            printState(f, path.getState(k));
            std::printf("\n");
        }
        std::printf("0\n");
    }
    ob::PlannerData data(info);
    setup.getPlannerData(data);
    if (ompl_cpp::isRoadmap(planner)) run.roadmapVertices(data.numVertices());
    const auto motions = info->getMotionValidator();
    run.report(solved, seconds, data.numVertices(), " motion_checks=" + std::to_string(
        motions->getValidMotionCount() + motions->getInvalidMotionCount()));
    return solved;
}

static void printControlPath(const Family &f, const oc::PathControl &path) {
    std::printf("%zu\n", path.getControlCount());
    for (size_t k = 0; k < path.getControlCount(); ++k) {
        printState(f, path.getState(k));
        const double *u = path.getControl(k)->as<oc::RealVectorControlSpace::ControlType>()->values;
        for (size_t j = 0; j < f.p.controlLow.size(); ++j) std::printf(" %.17g", u[j]);
        std::printf(" %ld\n", std::lround(path.getControlDuration(k) / f.p.dt));
    }
    std::printf("0\n");
}

static bool solveKinodynamic(Family &f, const std::string &planner, Run &run) {
    auto space = layout(f);
    const size_t m = f.p.controlLow.size();
    auto controls = std::make_shared<oc::RealVectorControlSpace>(space, m);
    ob::RealVectorBounds bounds(m);
    for (size_t j = 0; j < m; ++j) {
        bounds.setLow(j, f.p.controlLow[j]);
        bounds.setHigh(j, f.p.controlHigh[j]);
    }
    controls->setBounds(bounds);
    auto info = std::make_shared<oc::SpaceInformation>(space, controls);
    setValidity(*info, f);
    info->setStatePropagator([&f](const ob::State *from, const oc::Control *c, double,
                                  ob::State *to) {
        double q[8], next[8];  // one slice: the step is DT
        f.get(from, q);
        f.slice(q, c->as<oc::RealVectorControlSpace::ControlType>()->values, next);
        f.put(to, next);
        f.slices(to) = f.slices(from) + 1.0;
    });
    info->setPropagationStepSize(f.p.dt);
    info->setMinMaxControlDuration(f.p.kmin, f.p.kmax);
    info->setup();
    oc::SimpleSetup setup(info);
    setStartAndGoal(*setup.getProblemDefinition(), info, f);
    setup.setPlanner(kinodynamicPlanner(setup, f, planner, run));
    setup.solve(run.condition());
    const bool solved = setup.haveExactSolutionPath();
    const double seconds = run.seconds();
    if (solved) printControlPath(f, setup.getSolutionPath());
    ob::PlannerData data(info);
    setup.getPlannerData(data);
    run.report(solved, seconds, data.numVertices(), "");
    return solved;
}

int main(int argc, char **argv) {
    const bool optimize = ompl_cpp::optimizeFlag(argc, argv, 4);
    if (argc != 4 && !optimize) {
        std::fprintf(stderr, "usage: family_ompl rrt|rrtconnect|prm|prmstar|rrtstar|informed|"
                             "kpiece|sst TIME SEED [optimize]\n");
        return 2;
    }
    const std::string planner = argv[1];
    Family f;
    if (!readProblem(std::cin, f.p)) {
        std::fprintf(stderr, "family_ompl: bad input\n");
        return 2;
    }
    const bool geometric = planner == "rrtconnect" || ompl_cpp::isRoadmap(planner) ||
                           planner == "rrtstar" || planner == "informed";
    const bool control = planner == "sst" || planner == "kpiece";
    if (f.p.kinodynamic ? geometric : control) {
        std::fprintf(stderr, "family_ompl: %s does not plan for %s\n", planner.c_str(),
                     f.p.system.c_str());
        return 2;
    }
    if (!geometric && !control && planner != "rrt") {
        std::fprintf(stderr, "family_ompl: unknown planner %s\n", planner.c_str());
        return 2;
    }
    ompl_cpp::seedOmpl(argv[3]);
    Run run;
    run.limit = std::stod(argv[2]);
    run.optimize = optimize;
    const bool solved = f.p.kinodynamic ? solveKinodynamic(f, planner, run)
                                         : solveGeometric(f, planner, run);
    return solved ? 0 : 3;
}
