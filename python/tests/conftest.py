"""Shared fixtures: the source tree, the `ancf` executable, small scenes (seconds in all)."""

import os
import pathlib

import pytest

import ancf

SOURCE = pathlib.Path(os.environ.get("ANCF_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
SCENES = SOURCE / "studies" / "scenes"
PENDULUM = SCENES / "cable_pendulum.toml"
# The benchmark pendulum (REFERENCES §10) cut down to test size: 4 elements, 0.05 s.
SMALL = {"cable[0].elements": 4, "integrator.t_end": 0.05}


@pytest.fixture(scope="session")
def executable():
    path = os.environ.get("ANCF_EXECUTABLE")
    if not path or not os.path.exists(path):
        pytest.skip("ANCF_EXECUTABLE (the `ancf` command) not given; ctest sets it")
    return path


@pytest.fixture
def small_pendulum():
    return ancf.load(PENDULUM, SMALL)


@pytest.fixture
def small_pendulum_file(tmp_path, small_pendulum):
    """The small pendulum as a scene file of its own (for `ancf run`)."""
    path = tmp_path / "small_pendulum.toml"
    path.write_text(small_pendulum.toml())
    return path
