"""drapelab.load and Simulation: loading, stepping, and reading state and metrics as arrays."""
import numpy as np
import pytest

import drapelab


def test_load_builds_every_solver_at_frame_zero(tiny_scene):
    path, overrides = tiny_scene
    sim = drapelab.load(str(path), overrides=overrides)
    assert sim.name == "sphere_drape"
    assert len(sim.solvers) >= 2 and sim.solvers[0] == "ours"
    assert sim.duration == 0.25 and sim.frame_rate == 60 and sim.frame_count == 15
    assert sim.particle_count == 81
    assert sim.triangles.shape == (128, 3) and sim.triangles.max() == 80
    for solver in sim.solvers:
        assert sim.frame(solver) == 0 and sim.time(solver) == 0.0
        assert sim.status(solver) == "ok" and sim.message(solver) == ""
        metrics = sim.metrics(solver)
        assert list(metrics) == drapelab.METRICS
        assert all(values.shape == (1,) for values in metrics.values())


def test_step_moves_every_solver_in_lock_step(tiny_scene):
    path, overrides = tiny_scene
    sim = drapelab.load(path, overrides=overrides)  # a pathlib.Path works as well as a str
    start = {solver: sim.positions(solver) for solver in sim.solvers}
    sim.step(frames=6)
    for solver in sim.solvers:
        assert sim.frame(solver) == 6 and sim.time(solver) == pytest.approx(0.1)
        positions, velocities = sim.positions(solver), sim.velocities(solver)
        assert positions.shape == (81, 3) and positions.dtype == np.float64
        assert velocities.shape == (81, 3)
        # 0.1 s of free fall from rest: every particle has dropped about g t^2 / 2 = 4.9 cm.
        drop = start[solver][:, 1] - positions[:, 1]
        assert np.all(np.abs(drop - 0.049) < 0.005), solver
        assert np.all(np.abs(velocities[:, 1] + 0.981) < 0.05), solver
        metrics = sim.metrics(solver)
        assert np.array_equal(metrics["frame"], np.arange(7))
        assert np.allclose(metrics["time"], np.arange(7) / 60)
        assert metrics["centroid_y"][6] < metrics["centroid_y"][0]


def test_one_solver_steps_alone_and_by_index(tiny_scene):
    path, overrides = tiny_scene
    sim = drapelab.load(path, overrides=overrides)
    sim.step(3, solver="ours")
    sim.step(2, solver=1)
    assert sim.frame("ours") == 3 and sim.frame(sim.solvers[1]) == 2
    assert all(sim.frame(s) == 0 for s in sim.solvers[2:])
    sim.step_to_end()
    assert all(sim.frame(s) == sim.frame_count for s in sim.solvers)
    # Past the scene's end, step goes on.
    sim.step(1, solver="ours")
    assert sim.frame("ours") == sim.frame_count + 1
    assert len(sim.metrics("ours")["frame"]) == sim.frame_count + 2


def test_a_copy_of_the_positions_is_not_the_solver_state(tiny_scene):
    path, overrides = tiny_scene
    sim = drapelab.load(path, overrides=overrides)
    positions = sim.positions("ours")
    positions[:] = 0.0
    assert not np.allclose(sim.positions("ours"), 0.0)


def test_contact_metrics_hold_values_on_a_scene_with_colliders(tiny_scene):
    path, overrides = tiny_scene
    overrides["duration"] = 0.5
    sim = drapelab.load(path, overrides=overrides)
    sim.step_to_end(solver="ours")
    metrics = sim.metrics("ours")
    assert not np.isnan(metrics["min_clearance"]).any()
    assert metrics["contact_count"][-1] > 0  # the cloth lies on the sphere by 0.5 s
    assert np.isnan(metrics["drape_coefficient"]).all()  # no drape support in this scene


def test_dynamic_bodies_are_read_per_solver():
    sim = drapelab.load(drapelab_scene("parachute.yaml"), overrides={"duration": 0.1})
    sim.step(3)
    for solver in sim.solvers:
        bodies = sim.bodies(solver)
        assert len(bodies) == 1
        (body,) = bodies.values()
        assert body["position"].shape == (3,) and body["orientation"].shape == (4,)
        assert np.linalg.norm(body["orientation"]) == pytest.approx(1.0)
        assert body["velocity"][1] < 0.0  # the payload falls


def test_a_dict_scene_reads_as_the_file_would():
    scene = {
        "name": "dict_sheet",
        "duration": 0.1,
        "frame_rate": 50,
        "cloth": {"shape": "grid", "size": [0.2, 0.2], "resolution": [5, 5], "plane": "xz",
                  "center": [0, 1, 0], "mass": 0.01,
                  "springs": {"stretch": {"ks": 100, "kd": 0.01}, "shear": {"ks": 10, "kd": 0.001},
                              "bend": {"ks": 1, "kd": 0.0001}}},
        "solvers": [{"name": "ours", "type": "spring_damper", "integrator": "rk4", "dt": 0.001}],
    }
    sim = drapelab.load(scene, overrides=["solvers.0.integrator=midpoint"])
    assert sim.solvers == ["ours"] and sim.particle_count == 25
    sim.step_to_end()
    # Free fall: the centroid drops g t^2 / 2 in 0.1 s.
    metrics = sim.metrics("ours")
    assert metrics["centroid_y"][0] - metrics["centroid_y"][-1] == pytest.approx(0.04905, rel=1e-3)


def test_stepping_arguments_are_checked(tiny_scene):
    path, overrides = tiny_scene
    sim = drapelab.load(path, overrides=overrides)
    with pytest.raises(KeyError, match="no solver named 'nobody'; the scene's solvers are ours"):
        sim.step(1, solver="nobody")
    with pytest.raises(IndexError):
        sim.positions(7)
    with pytest.raises(ValueError, match="frames must be >= 0"):
        sim.step(-1)
    assert "sphere_drape" in repr(sim) and "frame 0 (ok)" in repr(sim)


def drapelab_scene(name):
    from conftest import SOURCE_DIR
    return str(SOURCE_DIR / "scenes" / name)
