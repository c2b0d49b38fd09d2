// OMPL with C++ callbacks on our grid problems: the practical limit for these planners
// (issue 19). The same set-up as benchmarks/ompl_adapters.py, written in C++:
//   point: R^2, geometric RRT (goal bias 0.05) or RRT-Connect, motions checked every
//          0.05 map units, goal radius 0.1;
//   ship, left: R^4, control RRT (goal bias 0.05), one step of 20 slices per control
//          (SPEC 2's slice; a slice that collides makes the step invalid).
// Input on stdin (bench_compiled.py writes it from a parsed .sw problem):
//   W H / W*H characters 0 or 1, row-major from the bottom row / sx sy gx gy
// Usage: grid_ompl point|rrtconnect|ship|left TIME_LIMIT SEED
// Prints one line on stderr: "ompl_cpp stats: status=solved|unsolved planning_seconds=S".
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/control/SimpleSetup.h>
#include <ompl/control/planners/rrt/RRT.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace ob = ompl::base;
namespace oc = ompl::control;
namespace og = ompl::geometric;

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

static bool solvePoint(const Grid &g, bool connect, double limit) {
    auto space = std::make_shared<ob::RealVectorStateSpace>(2);
    ob::RealVectorBounds bounds(2);
    bounds.setLow(0, 0.0); bounds.setHigh(0, g.width);
    bounds.setLow(1, 0.0); bounds.setHigh(1, g.height);
    space->setBounds(bounds);
    og::SimpleSetup setup(space);
    setup.setStateValidityChecker([&g](const ob::State *s) {
        const double *v = s->as<ob::RealVectorStateSpace::StateType>()->values;
        return g.free(v[0], v[1]);
    });
    auto info = setup.getSpaceInformation();
    info->setStateValidityCheckingResolution(0.05 / space->getMaximumExtent());
    ob::ScopedState<> start(space), goal(space);
    start[0] = g.sx; start[1] = g.sy; goal[0] = g.gx; goal[1] = g.gy;
    setup.setStartAndGoalStates(start, goal, GOAL_RADIUS);
    if (connect) {
        setup.setPlanner(std::make_shared<og::RRTConnect>(info));
    } else {
        auto rrt = std::make_shared<og::RRT>(info);
        rrt->setGoalBias(0.05);
        setup.setPlanner(rrt);
    }
    setup.solve(limit);
    return setup.haveExactSolutionPath();
}

class PositionGoal : public ob::GoalSampleableRegion {
public:
    PositionGoal(const ob::SpaceInformationPtr &si, double gx, double gy)
        : ob::GoalSampleableRegion(si), gx_(gx), gy_(gy) { setThreshold(GOAL_RADIUS); }
    double distanceGoal(const ob::State *s) const override {
        const double *v = s->as<ob::RealVectorStateSpace::StateType>()->values;
        return std::hypot(v[0] - gx_, v[1] - gy_);
    }
    void sampleGoal(ob::State *s) const override {
        double *v = s->as<ob::RealVectorStateSpace::StateType>()->values;
        v[0] = gx_; v[1] = gy_; v[2] = 0.0; v[3] = 0.0;
    }
    unsigned int maxSampleCount() const override { return 1; }
private:
    double gx_, gy_;
};

static bool solveShip(const Grid &g, double thetaRange, double limit) {
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
        const double *v = s->as<ob::RealVectorStateSpace::StateType>()->values;
        return g.free(v[0], v[1]);
    });
    setup.setStatePropagator([&g](const ob::State *from, const oc::Control *c, double,
                                  ob::State *to) {
        const double *s = from->as<ob::RealVectorStateSpace::StateType>()->values;
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
    });
    auto info = setup.getSpaceInformation();
    info->setPropagationStepSize(1.0);
    info->setMinMaxControlDuration(1, 1);
    ob::ScopedState<> start(space);
    start[0] = g.sx; start[1] = g.sy; start[2] = 0.0; start[3] = 0.0;
    setup.setStartState(start);
    setup.setGoal(std::make_shared<PositionGoal>(info, g.gx, g.gy));
    auto rrt = std::make_shared<oc::RRT>(info);
    rrt->setGoalBias(0.05);
    setup.setPlanner(rrt);
    setup.solve(limit);
    return setup.haveExactSolutionPath();
}

int main(int argc, char **argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: grid_ompl point|rrtconnect|ship|left TIME SEED\n");
        return 2;
    }
    const std::string mode = argv[1];
    const double limit = std::stod(argv[2]);
    Grid g;
    std::string cells;
    if (!(std::cin >> g.width >> g.height >> cells >> g.sx >> g.sy >> g.gx >> g.gy) ||
        cells.size() != static_cast<size_t>(g.width) * g.height) {
        std::fprintf(stderr, "grid_ompl: bad input\n");
        return 2;
    }
    for (char c : cells) g.blocked.push_back(c == '1');
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(std::stoul(argv[3]) % 0xFFFFFFFFul + 1));
    const auto began = std::chrono::steady_clock::now();
    bool solved;
    if (mode == "point" || mode == "rrtconnect") solved = solvePoint(g, mode == "rrtconnect", limit);
    else if (mode == "ship") solved = solveShip(g, 2.0 * M_PI, limit);
    else if (mode == "left") solved = solveShip(g, M_PI, limit);
    else { std::fprintf(stderr, "grid_ompl: unknown mode %s\n", mode.c_str()); return 2; }
    const double seconds = std::chrono::duration<double>(
        std::chrono::steady_clock::now() - began).count();
    std::fprintf(stderr, "ompl_cpp stats: status=%s planning_seconds=%.6f\n",
                 solved ? "solved" : "unsolved", seconds);
    return solved ? 0 : 3;
}
