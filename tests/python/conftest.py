"""Shared set-up of the Python module's tests: where the sources and the drapelab program are, and a
tiny version of a scene with colliders that every suite can run in seconds."""
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("DRAPELAB_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
DRAPELAB_EXE = os.environ.get("DRAPELAB_EXE", str(SOURCE_DIR / "build/tools/drapelab/drapelab"))

# sphere_drape at 9 x 9 particles for 0.25 s: contact with a sphere and a plane (so the clearance,
# penetration and contact columns hold values), three solvers (ours and Bullet's two cloths).
TINY_SCENE = SOURCE_DIR / "scenes" / "sphere_drape.yaml"
TINY_OVERRIDES = {"duration": 0.25, "cloth.resolution": [9, 9]}
TINY_SET_ARGUMENTS = ["--set", "duration=0.25", "--set", "cloth.resolution=[9, 9]"]


@pytest.fixture
def tiny_scene():
    return TINY_SCENE, dict(TINY_OVERRIDES)


def run_cli(*arguments, check=True):
    """Runs the drapelab program; returns the finished process (stdout and stderr as text)."""
    return subprocess.run([DRAPELAB_EXE, *map(str, arguments)], capture_output=True, text=True,
                          check=check)
