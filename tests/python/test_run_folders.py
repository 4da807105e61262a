"""Run and sweep folders read from Python: tables as dicts of arrays, JSON files as dicts."""
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import drapelab
from conftest import SOURCE_DIR, TINY_OVERRIDES, TINY_SCENE, TINY_SET_ARGUMENTS, run_cli


def test_a_run_folder_reads_as_arrays(tmp_path):
    run = drapelab.run(TINY_SCENE, tmp_path / "run", overrides=TINY_OVERRIDES)
    assert {"metrics", "compare", "contacts"} <= set(run.tables)
    assert run.solvers == list(run.summary["solvers"])
    everything = run.metrics()
    ours = run.metrics("ours")
    assert len(everything["frame"]) == len(run.solvers) * 16  # frames 0..15 of each solver
    assert ours["frame"].dtype == np.int64 and np.array_equal(ours["frame"], np.arange(16))
    assert ours["kinetic_energy"].dtype == np.float64
    assert set(ours["solver"]) == {"ours"}
    contacts = run.table("contacts", solver="ours")
    assert set(contacts["collider"]) == {"ball", "floor"}
    with pytest.raises(KeyError, match="no rows of a solver named 'nobody'"):
        run.metrics("nobody")
    with pytest.raises(FileNotFoundError, match="nothing.csv"):
        run.table("nothing")


def test_read_csv_types_each_column():
    table = drapelab.read_csv(SOURCE_DIR / "tests" / "python" / "data" / "mixed.csv")
    assert table["count"].dtype == np.int64 and list(table["count"]) == [1, 2, 3]
    assert table["value"].dtype == np.float64
    assert np.isnan(table["value"][1]) and table["value"][2] == 2.5e-3
    assert list(table["name"]) == ["a", "b, with a comma", ""]


def test_a_different_run_into_a_folder_needs_force(tmp_path):
    drapelab.run(TINY_SCENE, tmp_path / "run", overrides=TINY_OVERRIDES)
    other = dict(TINY_OVERRIDES, duration=0.2)
    with pytest.raises(drapelab.RunError, match="holds a different run.*--force"):
        drapelab.run(TINY_SCENE, tmp_path / "run", overrides=other)
    replaced = drapelab.run(TINY_SCENE, tmp_path / "run", overrides=other, force=True)
    assert replaced.summary["run"]["duration"] == 0.2


def test_a_folder_that_is_not_a_run_is_named(tmp_path):
    with pytest.raises(FileNotFoundError, match="summary.json"):
        drapelab.read_run(tmp_path)
    with pytest.raises(FileNotFoundError, match="sweep.csv"):
        drapelab.read_sweep(tmp_path)


def test_a_sweep_reads_and_the_example_plots_it(tmp_path):
    run_cli("sweep", TINY_SCENE, "--vary", "cloth.springs.bend.ks=1,10", *TINY_SET_ARGUMENTS,
            "--set", "solvers=[{name: ours, type: spring_damper}]", "--out", tmp_path / "sweep")
    sweep = drapelab.read_sweep(tmp_path / "sweep")
    table = sweep.table
    assert list(table["cloth.springs.bend.ks"]) == [1, 10]
    assert list(table["status"]) == ["ok", "ok"]
    assert sweep.record["varied"][0]["key"] == "cloth.springs.bend.ks"
    assert [pathlib.Path(r.path).name for r in sweep.runs] == [
        pathlib.Path(f).name for f in table["run_folder"]]

    plot = tmp_path / "plot.png"
    example = SOURCE_DIR / "tools" / "python" / "examples" / "plot_sweep.py"
    subprocess.run([sys.executable, str(example), str(tmp_path / "sweep"), "--metric", "max_stretch",
                    "--out", str(plot)], check=True, env={**__import__("os").environ, "MPLBACKEND": "Agg"})
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
