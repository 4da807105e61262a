"""Stepping releases the GIL (other Python threads run meanwhile), and Ctrl-C stops a long call."""
import os
import signal
import threading
import time

import numpy as np
import pytest

import drapelab
from conftest import TINY_SCENE

# ours alone at 25 x 25 for 4 s: about a second or more of stepping on one core.
LONG = {"duration": 4, "cloth.resolution": [25, 25], "solvers": [{"name": "ours", "type": "spring_damper"}]}


def test_other_threads_run_while_a_solver_steps():
    sim = drapelab.load(TINY_SCENE, overrides=LONG)
    started = threading.Event()

    def step():
        started.set()
        sim.step_to_end()

    stepper = threading.Thread(target=step)
    stepper.start()
    started.wait()
    counted = 0
    while stepper.is_alive():  # with the GIL held by step_to_end this loop could not turn
        counted += 1
    stepper.join()
    assert sim.frame("ours") == sim.frame_count
    # Tens of millions here when the GIL is released; a few hundred at most if it were held.
    assert counted > 100_000, counted


def test_ctrl_c_stops_stepping_after_the_current_step():
    sim = drapelab.load(TINY_SCENE, overrides=LONG)
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    began = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        sim.step_to_end()
    assert time.monotonic() - began < 2.0
    stopped_at = sim.frame("ours")
    assert 0 < stopped_at < sim.frame_count
    assert sim.status("ours") == "ok"
    # The simulation stays usable: every measured frame is whole, and stepping goes on from there.
    assert len(sim.metrics("ours")["frame"]) == stopped_at + 1
    sim.step(2)
    assert sim.frame("ours") == stopped_at + 2


def test_reads_from_another_thread_see_whole_frames():
    sim = drapelab.load(TINY_SCENE, overrides=LONG)
    stepper = threading.Thread(target=sim.step_to_end)
    stepper.start()
    reads = 0
    while stepper.is_alive():
        metrics = sim.metrics("ours")
        frames = metrics["frame"]
        # Every frame measured so far, none half-written, and the positions of a whole frame.
        assert np.array_equal(frames, np.arange(len(frames)))
        assert all(len(values) == len(frames) for values in metrics.values())
        assert sim.positions("ours").shape == (625, 3)
        reads += 1
    stepper.join()
    assert reads > 10  # the reads went on while the solver stepped
    assert len(sim.metrics("ours")["frame"]) == sim.frame_count + 1
