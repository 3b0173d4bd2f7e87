"""The module: sketches read and written, surface() on NumPy arrays, progress, cancel, the GIL."""

import threading
import time

import numpy as np
import pytest

import sketchsurf
from conftest import QUICK


def test_reads_and_writes_sketches(cube, tmp_path):
    assert len(cube) == 18
    strokes = cube.strokes
    assert all(s.dtype == np.float64 and s.ndim == 2 and s.shape[1] == 3 for s in strokes)
    assert sum(len(s) for s in strokes) == cube.point_count
    sketchsurf.write_sketch(cube, str(tmp_path / "copy.curves"))
    copy = sketchsurf.read_sketch(str(tmp_path / "copy.curves"))
    assert len(copy) == 18
    for a, b in zip(strokes, copy.strokes):
        np.testing.assert_allclose(a, b, atol=1e-6)


def test_sketch_from_arrays_and_bad_input(tmp_path):
    sketch = sketchsurf.Sketch([np.zeros((4, 3)), np.ones((2, 3))])
    assert len(sketch) == 2 and sketch.point_count == 6
    with pytest.raises(ValueError, match=r"\(n, 3\)"):
        sketchsurf.Sketch([np.zeros((4, 2))])
    broken = tmp_path / "broken.json"
    broken.write_text('{"format": "sketchsurf-sketch", "version": 1, "strokes": [')
    with pytest.raises(sketchsurf.SketchsurfError, match="broken.json") as e:
        sketchsurf.read_sketch(str(broken))
    assert e.value.kind == "input"
    with pytest.raises(sketchsurf.SketchsurfError, match="segment.no_such") as e:
        sketchsurf.surface(sketch, {"segment.no_such": 1})
    assert e.value.kind == "usage"


def test_surfaces_the_cube_from_arrays_with_progress_and_the_gil_released(cube):
    stages = []
    result = {}

    def run():
        result["out"] = sketchsurf.surface(cube.strokes, QUICK)

    # Without a callback the run never takes the GIL: this thread keeps running meanwhile.
    worker = threading.Thread(target=run)
    worker.start()
    ticks = 0
    while worker.is_alive():
        ticks += 1
        time.sleep(0.005)
    worker.join()
    assert ticks >= 20

    V, F, labels, sharp, report = result["out"]
    assert V.shape[1] == 3 and V.dtype == np.float64
    assert F.shape[1] == 3 and F.min() >= 0 and F.max() < len(V)
    assert labels.shape == (len(V),) and sharp.shape == (len(V),) and sharp.dtype == bool
    # The cube's six faces: six regions, their vertices on six planes through the face centres.
    assert report["regions"] == 6 and len(np.unique(labels)) == 6
    assert report["stroke_distance"]["median"] < 0.005
    assert 0 < sharp.sum() < len(V)
    for label in np.unique(labels):
        points = V[labels == label]
        spread = np.sort(points.std(axis=0))
        assert spread[0] < 0.05 * spread[1], spread  # flat

    # The same sketch as a Sketch, with a progress callback: the same surface.
    V2, F2, *_ = sketchsurf.surface(cube, QUICK, progress=lambda stage, f: stages.append((stage, f)))
    np.testing.assert_array_equal(V, V2)
    np.testing.assert_array_equal(F, F2)
    assert stages and all(0.0 <= f <= 1.0 for _, f in stages)
    names = {s for s, _ in stages}
    assert {"prepare", "proxy", "segmentation", "extract", "done"} <= names, names


def test_progress_cancels_and_its_exception_is_raised(cube):
    with pytest.raises(sketchsurf.SketchsurfError) as e:
        sketchsurf.surface(cube, QUICK, progress=lambda stage, fraction: False)
    assert e.value.kind == "cancelled"

    def fail(stage, fraction):
        raise KeyError("from the callback")

    with pytest.raises(KeyError, match="from the callback"):
        sketchsurf.surface(cube, QUICK, progress=fail)


def test_writes_meshes(tmp_path):
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    sketchsurf.write_mesh(str(tmp_path / "t.ply"), V, F, labels=[0, 0, 1, 1], sharp=[True, False, False, True])
    assert (tmp_path / "t.ply").stat().st_size > 0
    with pytest.raises(ValueError, match="names vertex 7"):
        sketchsurf.write_mesh(str(tmp_path / "bad.ply"), V, np.array([[0, 1, 7]]))


def test_half_a_sketch_is_completed_and_reported():
    """Half a box (x from 0 to 0.5), its long strokes stopping in the air at x = 0: the whole box."""
    def line(a, b, n=60):
        return np.linspace(a, b, n)

    strokes = []
    for x in (0.25, 0.5):
        corners = [(x, -0.2, -0.3), (x, -0.2, 0.3), (x, 0.2, 0.3), (x, 0.2, -0.3), (x, -0.2, -0.3)]
        strokes.append(np.vstack([line(a, b, 30)[:-1] for a, b in zip(corners, corners[1:])] + [np.array([corners[-1]])]))
    for y, z in [(0.2, 0), (-0.2, 0), (0, 0.3), (0, -0.3), (0.2, 0.3), (0.2, -0.3), (-0.2, 0.3), (-0.2, -0.3)]:
        strokes.append(line((0, y, z), (0.5, y, z)))
    V, F, labels, sharp, report = sketchsurf.surface(strokes, QUICK)
    assert report["symmetry"]["half_ends"] == 8
    assert abs(abs(report["symmetry"]["normal"][0]) - 1) < 1e-6
    assert V[:, 0].min() < -0.45 and V[:, 0].max() > 0.45
    *_, as_drawn = sketchsurf.surface(strokes, {**QUICK, "prepare.complete_half": 0})
    assert as_drawn["symmetry"] is None or as_drawn["symmetry"]["half_ends"] == 0



def test_a_proxy_lofted_through_sections_is_reported():
    """A dress: a four-lobed hem, a waist circle above it, two profiles. Where VIPSS's surface counts
    as framing no surface (here from 50% of it far from every stroke), the proxy is lofted."""
    a = np.linspace(0, 2 * np.pi, 400)
    hem = 1 + 0.3 * np.cos(4 * a)
    strokes = [np.column_stack([hem * np.cos(a), hem * np.sin(a), np.zeros_like(a)]),
               np.column_stack([0.5 * np.cos(a), 0.5 * np.sin(a), np.full_like(a, 2.0)])]
    for side in (-1, 1):
        t = np.linspace(0, 1, 100)
        strokes.append(np.column_stack([side * (1.3 - 0.8 * t), np.zeros_like(t), 2 * t]))
    # At the default resolution: at a coarse one the Laplacian lifts the held side's rim up to 1%
    # of the diagonal past the waist.
    V, F, labels, sharp, report = sketchsurf.surface(strokes, {"segment.restarts": 2, "proxy.outline_most": 0.5})
    assert report["loft_sections"] == 2
    assert V[:, 2].min() > -0.02 and V[:, 2].max() < 2.02
    assert np.hypot(V[:, 0], V[:, 1]).max() < 1.32
    *_, plain = sketchsurf.surface(strokes, QUICK)
    assert plain["loft_sections"] == 0
