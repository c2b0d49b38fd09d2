// OMPL with C++ callbacks on the geometric family (SPEC 5: arm2, rigid2), the practical
// limit for these planners (issue 19). The set-up of benchmarks/ompl_family.py, in C++:
//   state space: a compound of SO2 and bounded RealVector subspaces, one per metric group
//     (a group holding an angle and more than one variable: one subspace per variable),
//     variables in no group in a subspace of weight 0; OMPL's distance is then our metric
//     up to those per-variable sums (nearest neighbours only);
//   validity: bounds; the arm's two links (closed segments) or the body placed at
//     (x, y, theta) inside the closed world box and off every closed obstacle, by exact
//     tests (separating axes; closest point for a disc) behind a bounding-box check;
//   motions: our metric's length d, n = max(1, ceil(d / check)), the n samples after the
//     start tested (SPEC 5.2); goal: our metric restricted to the goal's variables,
//     threshold a hair inside the tolerance; RRT (goal bias 0.05) or RRTConnect.
// Input on stdin: the flat problem benchmarks/ompl_cpp_programs.py writes (family_input).
// Usage: family_ompl rrt|rrtconnect TIME_LIMIT SEED
// Prints the path on stdout in SPEC 5.4's geometric format (no tree), so the validator can
// check it, and one line on stderr: "ompl_cpp stats: status=solved|unsolved
// planning_seconds=S tree_nodes=N motion_checks=M" (S: OMPL's set-up and solve).
#include <ompl/base/MotionValidator.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace ob = ompl::base;
namespace og = ompl::geometric;

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
    double check = 0.01;
    double bx = 0, by = 0, l1 = 1, l2 = 1;  // arm2
    std::vector<Point> body;                // rigid2
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

// ---- the problem's state: validity, metric, interpolation ----

struct Family {
    Problem p;
    std::vector<std::pair<int, int>> slot;  // per variable: subspace, index in it

    bool valid(const double *q) const {
        for (size_t i = 0; i < p.angle.size(); ++i) {
            if (!std::isfinite(q[i])) return false;
            if (!p.angle[i] && !(p.low[i] <= q[i] && q[i] <= p.high[i])) return false;
        }
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

// ---- input, set-up, output ----

static bool readProblem(std::istream &in, Problem &p) {
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
    if (!(in >> word >> p.check)) return false;
    if (p.system == "arm2") { if (!(in >> word >> p.bx >> p.by >> p.l1 >> p.l2)) return false; }
    else if (p.system == "rigid2") {
        if (!(in >> word >> count) || count < 3) return false;
        p.body.resize(count);
        for (Point &v : p.body) if (!(in >> v.x >> v.y)) return false;
    } else return false;
    int has;
    if (!(in >> word >> has)) return false;
    p.hasBox = has != 0;
    if (p.hasBox && !(in >> p.X0 >> p.Y0 >> p.X1 >> p.Y1)) return false;
    if (!(in >> word >> count)) return false;
    for (int k = 0; k < count; ++k) {
        Obstacle o;
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
        p.obstacles.push_back(o);
    }
    p.start.resize(n);
    if (!(in >> word)) return false;
    for (double &v : p.start) if (!(in >> v)) return false;
    if (!(in >> word >> p.tolerance >> count)) return false;
    for (int k = 0; k < count; ++k) {
        int i; double v;
        if (!(in >> i >> v) || i < 0 || i >= n) return false;
        p.goal.push_back({i, v});
    }
    return true;
}

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
        if (anyAngle && part.second.size() > 1)
            for (int i : part.second) addSubspace(*space, f, {i}, part.first);
        else
            addSubspace(*space, f, part.second, part.first);
    }
    return space;
}

static void printPath(const Family &f, const og::PathGeometric &path) {
    std::printf("%zu\n", path.getStateCount());
    double q[8];
    for (size_t k = 0; k < path.getStateCount(); ++k) {
        f.get(path.getState(k), q);
        for (size_t i = 0; i < f.slot.size(); ++i) std::printf(i ? " %.17g" : "%.17g", q[i]);
        std::printf("\n");
    }
    std::printf("0\n");
}

// Plans; prints the path (when solved) after the time is taken, and the stats line.
static bool solve(Family &f, const std::string &planner, double limit,
                  std::chrono::steady_clock::time_point began) {
    auto space = layout(f);
    auto info = std::make_shared<ob::SpaceInformation>(space);
    info->setStateValidityChecker([&f](const ob::State *s) {
        double q[8];
        f.get(s, q);
        return f.valid(q);
    });
    info->setMotionValidator(std::make_shared<SampledMotions>(info, f));
    info->setup();
    og::SimpleSetup setup(info);
    ob::ScopedState<> start(space);
    f.put(start.get(), f.p.start.data());
    setup.setStartState(start);
    auto goal = std::make_shared<FamilyGoal>(info, f);
    goal->setSampler(space->allocStateSampler());
    setup.setGoal(goal);
    if (planner == "rrtconnect") {
        setup.setPlanner(std::make_shared<og::RRTConnect>(info));
    } else {
        auto rrt = std::make_shared<og::RRT>(info);
        rrt->setGoalBias(0.05);
        setup.setPlanner(rrt);
    }
    setup.solve(limit);
    const bool solved = setup.haveExactSolutionPath();
    const double seconds = std::chrono::duration<double>(
        std::chrono::steady_clock::now() - began).count();
    if (solved) printPath(f, setup.getSolutionPath());
    ob::PlannerData data(info);
    setup.getPlannerData(data);
    const auto motions = info->getMotionValidator();
    std::fprintf(stderr, "ompl_cpp stats: status=%s planning_seconds=%.6f tree_nodes=%u "
                 "motion_checks=%u\n", solved ? "solved" : "unsolved", seconds,
                 data.numVertices(), motions->getValidMotionCount() + motions->getInvalidMotionCount());
    return solved;
}

int main(int argc, char **argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: family_ompl rrt|rrtconnect TIME SEED\n");
        return 2;
    }
    const std::string planner = argv[1];
    if (planner != "rrt" && planner != "rrtconnect") {
        std::fprintf(stderr, "family_ompl: unknown planner %s\n", planner.c_str());
        return 2;
    }
    Family f;
    if (!readProblem(std::cin, f.p)) {
        std::fprintf(stderr, "family_ompl: bad input\n");
        return 2;
    }
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(std::stoul(argv[3]) % 0xFFFFFFFFul + 1));
    const auto began = std::chrono::steady_clock::now();
    return solve(f, planner, std::stod(argv[2]), began) ? 0 : 3;
}
