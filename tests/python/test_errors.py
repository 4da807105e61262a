"""Bad input from Python: drapelab.SceneError carries the loader's file:line messages."""
import pytest

import drapelab

GOOD_SCENE = """\
name: bad_example
duration: 0.1
cloth:
  shape: grid
  size: [0.2, 0.2]
  resolution: [5, 5]
  springs:
    stretch: {ks: -3, kd: 0.01}
solvers:
  - name: ours
    type: spring_damper
"""


def test_a_bad_value_names_file_line_and_key(tmp_path):
    scene = tmp_path / "bad.yaml"
    scene.write_text(GOOD_SCENE)
    with pytest.raises(drapelab.SceneError) as raised:
        drapelab.load(str(scene))
    message = str(raised.value)
    assert f"{scene}:8:" in message  # line 8 holds the negative ks
    assert "cloth.springs.stretch.ks" in message
    assert raised.value.errors and all(str(scene) in e for e in raised.value.errors)
    assert isinstance(raised.value, ValueError)


def test_a_bad_override_names_the_override(tiny_scene):
    path, _ = tiny_scene
    with pytest.raises(drapelab.SceneError, match="cloth.no_such_key"):
        drapelab.load(path, overrides={"cloth.no_such_key": 1})
    with pytest.raises(drapelab.SceneError, match="duration"):
        drapelab.load(path, overrides={"duration": "soon"})


def test_a_bad_dict_is_named_as_the_scene_dict():
    with pytest.raises(drapelab.SceneError, match="<scene dict>"):
        drapelab.load({"name": "x", "duration": -1})


def test_a_missing_file_is_named(tmp_path):
    missing = tmp_path / "nowhere.yaml"
    with pytest.raises(drapelab.SceneError, match="nowhere.yaml"):
        drapelab.load(missing)


def test_arguments_of_the_wrong_type_are_type_errors(tiny_scene):
    path, _ = tiny_scene
    with pytest.raises(TypeError, match="a scene file path or a dict"):
        drapelab.load(42)
    with pytest.raises(TypeError, match="overrides"):
        drapelab.load(path, overrides="duration=1")
    with pytest.raises(TypeError, match="key path"):
        drapelab.load(path, overrides={3: 1})


def test_nothing_is_written_for_a_refused_run(tmp_path):
    scene = tmp_path / "bad.yaml"
    scene.write_text(GOOD_SCENE)
    with pytest.raises(drapelab.SceneError):
        drapelab.run(scene, tmp_path / "out")
    assert not (tmp_path / "out").exists()
