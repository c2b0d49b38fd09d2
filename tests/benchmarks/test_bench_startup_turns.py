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
