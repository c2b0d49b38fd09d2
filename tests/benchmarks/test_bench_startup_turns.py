"""Several commands measured in the same rounds: each round runs each once, the
first command rotating (two commands alternate, as the pairs always did)."""

from pathlib import Path

from benchmarks import bench_startup


def test_rounds_rotate_the_first_command(monkeypatch):
    ran = []
    monkeypatch.setattr(bench_startup, "time_once",
                        lambda command, problem: ran.append(command[0]) or len(ran))
    times = bench_startup.take_turns([["a"], ["b"], ["c"]], Path("p.sw"), rounds=3)
    assert "".join(ran) == "abc" + "abc" + "bca" + "cab"  # warm-up, then three rounds
    assert times == [(4, 9, 11), (5, 7, 12), (6, 8, 10)]


def test_with_seeds_round_r_runs_every_command_with_seed_r(monkeypatch):
    ran = []
    monkeypatch.setattr(bench_startup, "time_once",
                        lambda command, problem: ran.append(" ".join(command)) or 1.0)
    bench_startup.take_turns([["a"], ["b"]], Path("p.sw"), rounds=2, seeds=True)
    assert ran == ["a -seed 1", "b -seed 1",                  # warm-up
                   "a -seed 1", "b -seed 1", "b -seed 2", "a -seed 2"]


def test_with_seeds_the_default_commands_name_no_seed(monkeypatch, capsys):
    commands = []
    monkeypatch.setattr(bench_startup, "take_turns",
                        lambda commands_, problem, rounds, seeds: commands.append(
                            (commands_, seeds)) or [(1.0,), (2.0,)])
    assert bench_startup.main(["--seeds", "--pairs", "1", "--problems", "p.sw"]) == 0
    (ours, theirs), seeds = commands[0]
    assert seeds and "-seed" not in ours + theirs
    assert ours == ["./run.sh"] and theirs[-2:] == ["-m", "benchmarks.ompl_planner"]
    assert "round r with -seed r" in capsys.readouterr().out
