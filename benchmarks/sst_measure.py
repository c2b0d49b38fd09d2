"""SST measurements: python measure.py sweep|cost OUT.json  (run from the worktree root)."""
import json, random, sys, time
from multiprocessing import Pool

def setup_for(case):
    from cli_common import parse_any_problem
    from planning_core.setups import grid_setup, kinoplan_setup
    path, vehicle = case
    problem = parse_any_problem(open(path).read())
    return kinoplan_setup(problem) if vehicle is None else grid_setup(problem, vehicle)

def run(job):
    from rrt_startup.compiled import activate
    activate()
    import dataclasses
    from planning_core.problem_definition import Objective
    from planning_core.plan_text import format_plan
    from planning_core.costs import path_cost
    from rrt_cli.planners import sst
    from rrt_cli.planners.base import StopCondition
    from validator.checks import validate_plan
    case, seed, limit, optimize = job
    setup = setup_for(case)
    pdef = setup.pdef
    if optimize:
        pdef = dataclasses.replace(pdef, objective=Objective())
    r = sst.solve(setup.si, pdef, StopCondition(time_limit=limit), random.Random(seed))
    valid = None
    if r.solved:
        valid = validate_plan(setup, format_plan(r.trajectory, r.tree)).valid
    return dict(case=f"{case[0].rsplit('/',1)[-1]} {case[1] or ''}".strip(), seed=seed,
                solved=r.solved, valid=valid, seconds=r.stats.planning_seconds,
                first=r.stats.first_solution_seconds, improvements=r.stats.improvements,
                cost=path_cost(setup.si, r.path, r.path_controls) if r.solved else None)

if __name__ == "__main__":
    sys.path.insert(0, ".")
    mode, out = sys.argv[1], sys.argv[2]
    F = "benchmarks/problems/family/"
    C = "benchmarks/problems/course/"
    fam = ["pendulum-t3", "pendulum-t5", "pendulum-t10", "car2-corridors", "unicycle-circles",
           "car1-scene1", "car1-scene2", "car1-scene3"]
    if mode == "sweep":
        cases = [(F + n + ".kp", None) for n in fam] + [
            (C + n + ".sw", v) for n in ["simple-0", "space-0", "space-1", "space-2", "space-3"]
            for v in ("spaceship", "left")]
        jobs = [(c, s, 30.0, False) for c in cases for s in range(20)]
    else:
        cases = [(F + "pendulum-t5.kp", None), (F + "car1-scene2.kp", None),
                 (C + "space-1.sw", "spaceship")]
        jobs = [(c, s, 10.0, True) for c in cases for s in range(20)]
    t = time.time()
    with Pool(2) as pool:
        results = []
        for res in pool.imap_unordered(run, jobs):
            results.append(res)
            json.dump(results, open(out, "w"))
    print("done", time.time() - t)
