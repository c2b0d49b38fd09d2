"""The alternating start-up benchmark on one problem, our planner against itself."""

from benchmarks import bench_startup
from benchmarks.bench_startup import Pairs

SIMPLE = bench_startup.ROOT / "benchmarks" / "problems" / "course" / "simple-0.sw"


def test_ratios_are_of_medians_and_of_pairs():
    pairs = Pairs(ours=(1.0, 2.0, 9.0), theirs=(2.0, 4.0, 3.0))
    assert pairs.ratio_of_medians == 2.0 / 3.0
    assert pairs.median_pair_ratio == 0.5  # of 0.5, 0.5 and 3


def test_a_run_prints_a_line_per_problem_and_the_pooled_one(capsys):
    status = bench_startup.main(["--pairs", "2", "--problems", str(SIMPLE),
                                 "--ours", "./run.sh -seed 1", "--theirs", "./run.sh -seed 2"])
    lines = capsys.readouterr().out.splitlines()
    assert status == 0
    assert lines[-2].split()[0] == "simple-0" and lines[-1].split()[0] == "all"
    assert all(float(word) > 0 for word in lines[-1].split()[1:])


def test_a_failing_command_is_one_line_and_status_1(capsys):
    status = bench_startup.main(["--pairs", "1", "--problems", str(SIMPLE),
                                 "--ours", "./run.sh -bogus"])
    err = capsys.readouterr().err
    assert status == 1 and err.count("\n") == 1 and "exit status 2" in err


def test_the_page_holds_the_command_that_made_it_and_the_tables(tmp_path, capsys):
    page = tmp_path / "startup.md"
    argv = ["--pairs", "1", "--problems", str(SIMPLE), "--ours", "./run.sh -seed 1",
            "--theirs", "./run.sh -seed 2", "--page", str(page)]
    assert bench_startup.main(argv) == 0
    text = page.read_text()
    printed = capsys.readouterr().out
    assert "--theirs './run.sh -seed 2'" in text.splitlines()[2]
    assert printed.strip() in text and text.count("\nsimple-0 ") == 1
