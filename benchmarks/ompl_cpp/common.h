// What grid_ompl.cpp and family_ompl.cpp share: the run's clock and OMPL termination
// condition (as benchmarks/ompl_adapters.py's Termination: it counts its polls, one per
// planner iteration, and notes each improvement of an optimizing planner's best cost
// with its time), the cost threshold of -optimize, and the stats and progress lines.
#pragma once

#include <ompl/base/OptimizationObjective.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProjectionEvaluator.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>
#include <ompl/control/planners/sst/SST.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace ompl_cpp {

// PRM or PRM* by our planner name (or grid_ompl's mode).
inline bool isRoadmap(const std::string &planner) {
    return planner == "prm" || planner == "prmstar";
}

struct Run {
    std::chrono::steady_clock::time_point began = std::chrono::steady_clock::now();
    double limit = 30.0;
    bool optimize = false;                // keep improving until the limit
    std::function<double()> bestCost;     // set for an optimizing planner
    std::vector<std::pair<double, double>> improvements;  // (seconds, cost)
    unsigned long polls = 0;

    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    }

    bool poll() {
        ++polls;
        const double now = seconds();
        if (bestCost) {
            const double cost = bestCost();
            if (std::isfinite(cost) && (improvements.empty() || cost < improvements.back().second))
                improvements.emplace_back(now, cost);
        }
        return now >= limit;
    }

    ompl::base::PlannerTerminationCondition condition() {
        return ompl::base::PlannerTerminationCondition([this] { return poll(); });
    }

    // The limit alone, polls not counted: for PRM, whose solution-checking thread polls
    // the condition beside its roadmap's (roadmapVertices() then counts the iterations).
    ompl::base::PlannerTerminationCondition timeCondition() const {
        return ompl::base::PlannerTerminationCondition([this] { return seconds() >= limit; });
    }

    // The condition to solve the planner with: a roadmap's is the limit alone.
    ompl::base::PlannerTerminationCondition conditionFor(const std::string &planner) {
        return isRoadmap(planner) ? timeCondition() : condition();
    }

    // A roadmap's iterations, as ours count them: the vertices it added (start and goal
    // were given).
    void roadmapVertices(unsigned vertices) { polls = std::max(2u, vertices) - 2; }

    // -optimize: a threshold of 0 is never met, so the planner runs to the limit;
    // otherwise any solution meets an infinite one and the planner stops there.
    void setThreshold(ompl::base::OptimizationObjective &objective) const {
        objective.setCostThreshold(ompl::base::Cost(
            optimize ? 0.0 : std::numeric_limits<double>::infinity()));
    }

    // "ompl_cpp stats: status=... planning_seconds=S tree_nodes=N iterations=I cost=C
    // first_solution_seconds=F EXTRA" and, with -optimize, "ompl_cpp progress: S:C ...".
    void report(bool solved, double planning, unsigned treeNodes, const std::string &extra) const {
        std::string cost = "none", first = "none";
        char text[64];
        if (solved && !improvements.empty()) {
            std::snprintf(text, sizeof text, "%.9g", improvements.back().second);
            cost = text;
            std::snprintf(text, sizeof text, "%.6f", improvements.front().first);
            first = text;
        } else if (solved) {
            std::snprintf(text, sizeof text, "%.6f", planning);
            first = text;
        }
        std::fprintf(stderr, "ompl_cpp stats: status=%s planning_seconds=%.6f tree_nodes=%u "
                     "iterations=%lu cost=%s first_solution_seconds=%s%s\n",
                     solved ? "solved" : "unsolved", planning, treeNodes, polls, cost.c_str(),
                     first.c_str(), extra.c_str());
        if (optimize && solved && !improvements.empty()) {
            std::fprintf(stderr, "ompl_cpp progress:");
            for (const auto &step : improvements)
                std::fprintf(stderr, " %.6f:%.9g", step.first, step.second);
            std::fprintf(stderr, "\n");
        }
    }
};

// RRT* or Informed RRT* (OMPL's defaults), its best cost read by the run.
inline ompl::base::PlannerPtr starPlanner(const ompl::base::SpaceInformationPtr &info,
                                          bool informed, Run &run) {
    std::shared_ptr<ompl::geometric::RRTstar> planner =
        informed ? std::make_shared<ompl::geometric::InformedRRTstar>(info)
                 : std::make_shared<ompl::geometric::RRTstar>(info);
    run.bestCost = [planner] { return planner->bestCost().value(); };
    return planner;
}

// SST with its best solution's cost readable (a protected member in OMPL 1.5).
class CostedSST : public ompl::control::SST {
public:
    using ompl::control::SST::SST;
    double best() const { return prevSolutionCost_.value(); }
};

// SST (OMPL's goal bias, 0.05) with the given radii, its best cost read by the run.
inline ompl::base::PlannerPtr sstPlanner(const ompl::control::SpaceInformationPtr &info,
                                         double selection, double pruning, Run &run) {
    auto planner = std::make_shared<CostedSST>(info);
    planner->setSelectionRadius(selection);
    planner->setPruningRadius(pruning);
    run.bestCost = [planner] { return planner->best(); };
    return planner;
}

// PRM (k = 10) or PRM* (k = e (1 + 1/d) log n), OMPL's; with the objective's threshold
// infinite (the caller's setThreshold, no -optimize) solve() ends at the first roadmap
// path from start to goal, as ours; its solution check runs in a thread of its own,
// polling every millisecond.
inline std::shared_ptr<ompl::geometric::PRM> prmPlanner(const ompl::base::SpaceInformationPtr &info,
                                                        bool star) {
    return std::make_shared<ompl::geometric::PRM>(info, star);
}

// KPIECE1's grid as ours: the projection writes each coordinate already scaled to cells
// ((value - low) * scale, our AxesProjection), so every cell is 1 wide.
class ScaledProjection : public ompl::base::ProjectionEvaluator {
public:
    using Project = std::function<void(const ompl::base::State *, double *)>;
    ScaledProjection(const ompl::base::StateSpacePtr &space, unsigned dimension, Project project)
        : ompl::base::ProjectionEvaluator(space), dimension_(dimension),
          project_(std::move(project)) {}
    unsigned int getDimension() const override { return dimension_; }
    void defaultCellSizes() override { cellSizes_.assign(dimension_, 1.0); }
    void project(const ompl::base::State *state,
                 Eigen::Ref<Eigen::VectorXd> projection) const override {
        double out[8];
        project_(state, out);
        for (unsigned i = 0; i < dimension_; ++i) projection[i] = out[i];
    }
private:
    unsigned dimension_;
    Project project_;
};

// Control KPIECE1 with OMPL's defaults (goal bias 0.05, border fraction 0.8, cell score
// factors 0.9 and 0.45, 30 close samples: ours too) over the given projection.
inline ompl::base::PlannerPtr kpiecePlanner(const ompl::control::SpaceInformationPtr &info,
                                            const ompl::base::ProjectionEvaluatorPtr &projection) {
    auto planner = std::make_shared<ompl::control::KPIECE1>(info);
    planner->setProjectionEvaluator(projection);
    return planner;
}

// OMPL's generator seeded as benchmarks/ompl_adapters.py's ompl_seed (32 bits, not 0), its
// log silenced.
inline void seedOmpl(const char *seed) {
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(std::stoull(seed) % 0xFFFFFFFFull + 1));
}

// "optimize" as the last argument, or nothing.
inline bool optimizeFlag(int argc, char **argv, int plain) {
    return argc == plain + 1 && std::string(argv[plain]) == "optimize";
}

}  // namespace ompl_cpp
