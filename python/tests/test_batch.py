"""The Dask runner on a LocalCluster: every sketch of a folder surfaced, a corrupt one reported."""

import json

import pytest

from conftest import write_quick

distributed = pytest.importorskip("dask.distributed")


def test_surfaces_a_folder_on_a_local_cluster(tmp_path):
    from sketchsurf.batch import surface_folder

    write_quick("cube", tmp_path / "in" / "cube.json")
    write_quick("cylinder", tmp_path / "in" / "parts" / "cylinder.json")
    (tmp_path / "in" / "broken.json").write_text('{"format": "sketchsurf-sketch", "version": 1, "strokes": [')
    (tmp_path / "in" / "notes.txt").write_text("not a sketch\n")

    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        rows = surface_folder(tmp_path / "in", tmp_path / "out", client)

    by_name = {r["output"].split("/out/")[1]: r for r in rows}
    assert sorted(by_name) == ["broken.ply", "cube.ply", "parts/cylinder.ply"]
    assert by_name["broken.ply"]["status"] == "failed"
    assert by_name["broken.ply"]["kind"] == "input" and "broken.json" in by_name["broken.ply"]["error"]
    assert by_name["cube.ply"]["status"] == "ok" and by_name["cube.ply"]["regions"] == 6
    assert by_name["parts/cylinder.ply"]["status"] == "ok" and by_name["parts/cylinder.ply"]["regions"] >= 3
    assert (tmp_path / "out" / "cube.ply").stat().st_size > 0
    assert (tmp_path / "out" / "parts" / "cylinder.ply").stat().st_size > 0
    assert json.loads((tmp_path / "out" / "summary.json").read_text()) == rows
