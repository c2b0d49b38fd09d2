// OMPL with C++ callbacks on our grid problems: the practical limit for these planners
// (issue 19). The same set-up as benchmarks/ompl_adapters.py, written in C++:
//   point: R^2, motions checked every 0.05 map units, goal radius 0.1; geometric RRT
//          (goal bias 0.05), RRT-Connect, PRM, PRM*, RRT* or Informed RRT* (OMPL's
//          defaults, minimizing path length: OMPL's own objective, as the Python peer;
//          PRM and PRM* end at their first path, as ours);
//   ship, left: R^4, one step of 20 slices per control (SPEC 2's slice; a slice that
//          collides makes the step invalid); control RRT (goal bias 0.05), KPIECE1
//          (a control held 1 to 10 steps, as ours; the grid over our projection: the
//          position in cells of 0.5 map units on maps under 20 a side, else 1, and the
//          velocity in cells of 0.2) or SST (our SST's radii, 0.25 map units; cost: the
//          length of the polyline through the positions, our cost for the ships,
//          docs/optimal-planning.md).
// Input on stdin (benchmarks/ompl_cpp_programs.py's grid_input writes it from a .sw problem):
//   W H / W*H characters 0 or 1, row-major from the bottom row / sx sy gx gy
// Usage: grid_ompl MODE TIME_LIMIT SEED [optimize]
//   MODE: point (RRT) | rrtconnect | prm | prmstar | rrtstar | informed | ship (RRT) | left (RRT)
//         | kpiece | kpiece-left | sst | sst-left
//   optimize: RRT*, Informed RRT* and SST keep improving until the limit.
// Prints the answer on stdout in SPEC 2's format (no tree) and common.h's stats line (and,
// with optimize, its progress line) on stderr. Exit 0 solved, 2 bad usage, 3 unsolved.
#include "common.h"

#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
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

struct Grid {
    int width = 0, height = 0;
    std::vector<char> blocked;
    double sx, sy, gx, gy;
    bool free(double x, double y) const {  // strictly inside (printable) and not blocked
        return x > 0.0 && y > 0.0 && x < width && y < height &&
               !blocked[static_cast<int>(y) * width + static_cast<int>(x)];
    }
};

static const double GOAL_RADIUS = 0.1 * (1.0 - 1e-9);
static const double SHIP_SST_RADIUS = 0.25;  // our SST's selection and pruning radii

static const double *values(const ob::State *s) {
    return s->as<ob::RealVectorStateSpace::StateType>()->values;
}

// RRT* or Informed RRT* minimizing OMPL's path length (our cost in the plane).
static ob::PlannerPtr pointOptimizer(og::SimpleSetup &setup, bool informed, Run &run) {
    auto info = setup.getSpaceInformation();
    auto objective = std::make_shared<ob::PathLengthOptimizationObjective>(info);
    run.setThreshold(*objective);
    setup.setOptimizationObjective(objective);
    return ompl_cpp::starPlanner(info, informed, run);
}

static ob::PlannerPtr pointPlanner(og::SimpleSetup &setup, const std::string &mode, Run &run) {
    if (mode == "rrtstar" || mode == "informed")
        return pointOptimizer(setup, mode == "informed", run);
    auto info = setup.getSpaceInformation();
    if (ompl_cpp::isRoadmap(mode)) {
        auto objective = std::make_shared<ob::PathLengthOptimizationObjective>(info);
        run.setThreshold(*objective);
        setup.setOptimizationObjective(objective);
        return ompl_cpp::prmPlanner(info, mode == "prmstar");
    }
    if (mode == "rrtconnect") return std::make_shared<og::RRTConnect>(info);
    auto rrt = std::make_shared<og::RRT>(info);
    rrt->setGoalBias(0.05);
    return rrt;
}

static bool solvePoint(const Grid &g, const std::string &mode, Run &run) {
    auto space = std::make_shared<ob::RealVectorStateSpace>(2);
    ob::RealVectorBounds bounds(2);
    bounds.setLow(0, 0.0); bounds.setHigh(0, g.width);
    bounds.setLow(1, 0.0); bounds.setHigh(1, g.height);
    space->setBounds(bounds);
    og::SimpleSetup setup(space);
    setup.setStateValidityChecker([&g](const ob::State *s) {
        return g.free(values(s)[0], values(s)[1]);
    });
    auto info = setup.getSpaceInformation();
    info->setStateValidityCheckingResolution(0.05 / space->getMaximumExtent());
    ob::ScopedState<> start(space), goal(space);
    start[0] = g.sx; start[1] = g.sy; goal[0] = g.gx; goal[1] = g.gy;
    setup.setStartAndGoalStates(start, goal, GOAL_RADIUS);
    setup.setPlanner(pointPlanner(setup, mode, run));
    setup.solve(run.conditionFor(mode));
    const bool solved = setup.haveExactSolutionPath();
    const double seconds = run.seconds();
    ob::PlannerData data(info);
    setup.getPlannerData(data);
    if (ompl_cpp::isRoadmap(mode)) run.roadmapVertices(data.numVertices());
    if (solved) {
        const og::PathGeometric &path = setup.getSolutionPath();
        std::printf("%zu\n", path.getStateCount());
        for (std::size_t k = 0; k < path.getStateCount(); ++k)
            std::printf("%.17g %.17g\n", values(path.getState(k))[0], values(path.getState(k))[1]);
        std::printf("0\n");
    }
    run.report(solved, seconds, data.numVertices(), "");
    return solved;
}

class PositionGoal : public ob::GoalSampleableRegion {
public:
    PositionGoal(const ob::SpaceInformationPtr &si, double gx, double gy)
        : ob::GoalSampleableRegion(si), gx_(gx), gy_(gy) { setThreshold(GOAL_RADIUS); }
    double distanceGoal(const ob::State *s) const override {
        return std::hypot(values(s)[0] - gx_, values(s)[1] - gy_);
    }
    void sampleGoal(ob::State *s) const override {
        double *v = s->as<ob::RealVectorStateSpace::StateType>()->values;
        v[0] = gx_; v[1] = gy_; v[2] = 0.0; v[3] = 0.0;
    }
    unsigned int maxSampleCount() const override { return 1; }
private:
    double gx_, gy_;
};

// The ships' cost: each step's straight distance between positions.
class PositionLength : public ob::OptimizationObjective {
public:
    explicit PositionLength(const ob::SpaceInformationPtr &si) : ob::OptimizationObjective(si) {}
    ob::Cost stateCost(const ob::State *) const override { return identityCost(); }
    ob::Cost motionCost(const ob::State *a, const ob::State *b) const override {
        return ob::Cost(std::hypot(values(b)[0] - values(a)[0], values(b)[1] - values(a)[1]));
    }
};

static void propagateShip(const Grid &g, const ob::State *from, const oc::Control *c,
                          ob::State *to) {
    const double *s = values(from);
    const double *u = c->as<oc::RealVectorControlSpace::ControlType>()->values;
    double *r = to->as<ob::RealVectorStateSpace::StateType>()->values;
    double x = s[0], y = s[1], dx = s[2], dy = s[3];
    const double dt = 1.0 / 20, step = dt * u[1];
    for (int k = 0; k < 20; ++k) {  // SPEC 2's slice
        const double a = std::atan2(dy, dx) + u[0];
        dx += step * std::cos(a);
        dy += step * std::sin(a);
        x += dt * dx;
        y += dt * dy;
        if (!(x >= 0.0 && y >= 0.0 && x < g.width && y < g.height) ||
            g.blocked[static_cast<int>(y) * g.width + static_cast<int>(x)]) {
            r[0] = -1.0; r[1] = -1.0; r[2] = 0.0; r[3] = 0.0;  // invalid end
            return;
        }
    }
    r[0] = x; r[1] = y; r[2] = dx; r[3] = dy;
}

// KPIECE1's grid over (x, y, dx, dy), as our ships' (GridControlOptions' cell sizes).
static ob::ProjectionEvaluatorPtr shipProjection(const Grid &g, const ob::StateSpacePtr &space) {
    const double cell = std::max(g.width, g.height) < 20 ? 0.5 : 1.0, velocity = 0.2;
    return std::make_shared<ompl_cpp::ScaledProjection>(
        space, 4, [cell, velocity](const ob::State *s, double *out) {
            out[0] = values(s)[0] / cell; out[1] = values(s)[1] / cell;
            out[2] = values(s)[2] / velocity; out[3] = values(s)[3] / velocity;
        });
}

static ob::PlannerPtr shipPlanner(const Grid &g, oc::SimpleSetup &setup, const std::string &kind,
                                  Run &run) {
    auto info = setup.getSpaceInformation();
    if (kind == "rrt") {
        auto rrt = std::make_shared<oc::RRT>(info);
        rrt->setGoalBias(0.05);
        return rrt;
    }
    if (kind == "kpiece") {
        info->setMinMaxControlDuration(1, 10);  // ours: a control held 1 to 10 steps
        return ompl_cpp::kpiecePlanner(info, shipProjection(g, info->getStateSpace()));
    }
    auto objective = std::make_shared<PositionLength>(info);
    run.setThreshold(*objective);
    setup.getProblemDefinition()->setOptimizationObjective(objective);
    return ompl_cpp::sstPlanner(info, SHIP_SST_RADIUS, SHIP_SST_RADIUS, run);
}

static void printShipPath(const oc::PathControl &path) {
    std::printf("%zu\n", path.getControlCount());
    for (std::size_t k = 0; k < path.getControlCount(); ++k) {
        const double *s = values(path.getState(k));
        const double *u = path.getControl(k)->as<oc::RealVectorControlSpace::ControlType>()->values;
        std::printf("%.17g %.17g %.17g %.17g %.17g %.17g\n", s[0], s[1], s[2], s[3], u[0], u[1]);
    }
    std::printf("0\n");
}

// kind: rrt, kpiece or sst.
static bool solveShip(const Grid &g, double thetaRange, const std::string &kind, Run &run) {
    auto space = std::make_shared<ob::RealVectorStateSpace>(4);
    ob::RealVectorBounds bounds(4);
    bounds.setLow(0, 0.0); bounds.setHigh(0, g.width);
    bounds.setLow(1, 0.0); bounds.setHigh(1, g.height);
    for (int i = 2; i < 4; ++i) { bounds.setLow(i, -1.0); bounds.setHigh(i, 1.0); }
    space->setBounds(bounds);
    auto controls = std::make_shared<oc::RealVectorControlSpace>(space, 2);
    ob::RealVectorBounds cb(2);
    cb.setLow(0, 0.0); cb.setHigh(0, thetaRange);
    cb.setLow(1, 0.0); cb.setHigh(1, 0.5);
    controls->setBounds(cb);
    oc::SimpleSetup setup(controls);
    setup.setStateValidityChecker([&g](const ob::State *s) {
        return g.free(values(s)[0], values(s)[1]);
    });
    setup.setStatePropagator([&g](const ob::State *from, const oc::Control *c, double,
                                  ob::State *to) { propagateShip(g, from, c, to); });
    auto info = setup.getSpaceInformation();
    info->setPropagationStepSize(1.0);
    info->setMinMaxControlDuration(1, 1);
    ob::ScopedState<> start(space);
    start[0] = g.sx; start[1] = g.sy; start[2] = 0.0; start[3] = 0.0;
    setup.setStartState(start);
    setup.setGoal(std::make_shared<PositionGoal>(info, g.gx, g.gy));
    setup.setPlanner(shipPlanner(g, setup, kind, run));
    setup.solve(run.condition());
    const bool solved = setup.haveExactSolutionPath();
    const double seconds = run.seconds();
    ob::PlannerData data(info);
    setup.getPlannerData(data);
    if (solved) {
        oc::PathControl &path = setup.getSolutionPath();
        path.interpolate();  // one control a step (SPEC 2): KPIECE1 holds one for several
        printShipPath(path);
    }
    run.report(solved, seconds, data.numVertices(), "");
    return solved;
}

int main(int argc, char **argv) {
    const bool optimize = ompl_cpp::optimizeFlag(argc, argv, 4);
    if (argc != 4 && !optimize) {
        std::fprintf(stderr, "usage: grid_ompl point|rrtconnect|prm|prmstar|rrtstar|informed|ship|"
                             "left|kpiece|kpiece-left|sst|sst-left TIME SEED [optimize]\n");
        return 2;
    }
    const std::string mode = argv[1];
    Grid g;
    std::string cells;
    if (!(std::cin >> g.width >> g.height >> cells >> g.sx >> g.sy >> g.gx >> g.gy) ||
        cells.size() != static_cast<size_t>(g.width) * g.height) {
        std::fprintf(stderr, "grid_ompl: bad input\n");
        return 2;
    }
    for (char c : cells) g.blocked.push_back(c == '1');
    ompl_cpp::seedOmpl(argv[3]);
    Run run;
    run.limit = std::stod(argv[2]);
    run.optimize = optimize;
    bool solved;
    static const std::vector<std::string> pointModes = {"point", "rrtconnect", "prm", "prmstar",
                                                        "rrtstar", "informed"};
    const bool left = mode.size() > 5 && mode.compare(mode.size() - 5, 5, "-left") == 0;
    const std::string kind = left ? mode.substr(0, mode.size() - 5) : mode;
    if (std::find(pointModes.begin(), pointModes.end(), mode) != pointModes.end())
        solved = solvePoint(g, mode, run);
    else if (mode == "ship" || mode == "left")
        solved = solveShip(g, mode == "left" ? M_PI : 2.0 * M_PI, "rrt", run);
    else if (kind == "kpiece" || kind == "sst")
        solved = solveShip(g, left ? M_PI : 2.0 * M_PI, kind, run);
    else { std::fprintf(stderr, "grid_ompl: unknown mode %s\n", mode.c_str()); return 2; }
    return solved ? 0 : 3;
}
