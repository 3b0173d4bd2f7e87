import os
import pathlib

import pytest

import sketchsurf

TESTS_DIR = pathlib.Path(os.environ.get("SKETCHSURF_TESTS_DIR", pathlib.Path(__file__).parents[2] / "tests"))

# A coarse proxy and two restarts: a bundled sketch surfaces in about a second.
QUICK = {"proxy.edge": 0.03, "proxy.points": 150, "segment.restarts": 2}


@pytest.fixture
def cube():
    return sketchsurf.read_sketch(str(TESTS_DIR / "data" / "cube.json"))


def write_quick(name, path):
    """The bundled sketch `name` with the QUICK parameters stored in it, written to `path`."""
    sketch = sketchsurf.read_sketch(str(TESTS_DIR / "data" / (name + ".json")))
    sketch.params = QUICK
    path.parent.mkdir(parents=True, exist_ok=True)
    sketchsurf.write_sketch(sketch, str(path))
