"""The module steps and measures exactly as drapelab run does: the same numbers to the last digit."""
import csv
import math

import numpy as np

import drapelab
from conftest import TINY_OVERRIDES, TINY_SCENE, TINY_SET_ARGUMENTS, run_cli


def read_metrics_csv(path):
    """metrics.csv read with Python's own csv module, per solver: {column: [float, ...]}."""
    tables = {}
    with open(path, newline="") as file:
        for row in csv.DictReader(file):
            table = tables.setdefault(row.pop("solver"), {})
            for column, cell in row.items():
                table.setdefault(column, []).append(float(cell) if cell != "" else math.nan)
    return tables


def test_stepping_gives_metrics_csv_to_the_last_digit(tmp_path):
    run_cli("run", TINY_SCENE, "--out", tmp_path / "cli", *TINY_SET_ARGUMENTS, "--quiet")
    expected = read_metrics_csv(tmp_path / "cli" / "metrics.csv")

    sim = drapelab.load(TINY_SCENE, overrides=TINY_OVERRIDES)
    sim.step_to_end()
    assert sorted(expected) == sorted(sim.solvers)
    for solver in sim.solvers:
        got = sim.metrics(solver)
        assert list(got) == list(expected[solver])  # the same columns, in the same order
        for column, values in expected[solver].items():
            # Exact: metrics.csv writes the shortest text that reads back as the same double.
            assert np.array_equal(got[column], np.array(values), equal_nan=True), (solver, column)


def test_drapelab_run_from_python_writes_the_same_tables(tmp_path):
    run_cli("run", TINY_SCENE, "--out", tmp_path / "cli", *TINY_SET_ARGUMENTS, "--quiet")
    folder = drapelab.run(TINY_SCENE, tmp_path / "py", overrides=TINY_OVERRIDES)
    assert folder.path == str(tmp_path / "py")
    for table in ("metrics.csv", "compare.csv", "contacts.csv"):
        assert (tmp_path / "py" / table).read_bytes() == (tmp_path / "cli" / table).read_bytes(), table
    # And the same final metrics in summary.json.
    cli = drapelab.read_run(tmp_path / "cli").summary
    assert [s["final"] for s in folder.summary["solvers"].values()] == [
        s["final"] for s in cli["solvers"].values()]


def test_two_loads_step_alike():
    first = drapelab.load(TINY_SCENE, overrides=TINY_OVERRIDES)
    second = drapelab.load(TINY_SCENE, overrides=TINY_OVERRIDES)
    first.step(5)
    second.step(5)
    for solver in first.solvers:
        assert np.array_equal(first.positions(solver), second.positions(solver))
