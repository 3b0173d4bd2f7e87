"""Surface every sketch of a folder on a Dask cluster (dask.distributed): a LocalCluster on this
machine, or the scheduler of a cluster whose workers see the same files (a shared filesystem).

    python3 -m sketchsurf.batch SKETCH_DIR -o OUT_DIR [--scheduler tcp://host:8786] [--workers N]
        [--param segment.restarts=4 ...]

Each sketch is one task: read, surfaced, written as OUT_DIR/NAME.ply (NAME keeps the path below
SKETCH_DIR); a sketch that fails is reported in its row and never stops the others. The rows (one
dict per sketch: sketch, output, status "ok" or "failed", error, regions, vertices,
stroke_distance, warnings, seconds) come back in the order of the sketch paths and are written to
OUT_DIR/summary.json; the exit code is 0 only when every sketch succeeded.
"""

import argparse
import json
import os
import pathlib
import sys
import time

SKETCH_EXTENSIONS = (".tilt", ".curves", ".obj", ".json")


def find_sketches(folder):
    """Every sketch below `folder` (a .tilt folder is one sketch), sorted by path."""
    folder = pathlib.Path(folder)
    found = []
    for root, dirs, files in os.walk(folder):
        for d in list(dirs):
            if d.lower().endswith(".tilt"):
                found.append(pathlib.Path(root) / d)
                dirs.remove(d)
        found += [pathlib.Path(root) / f for f in files if f.lower().endswith(SKETCH_EXTENSIONS)]
    return sorted(found)


def surface_file(sketch_path, output_path, params=None):
    """Surfaces one sketch file into `output_path`; returns its summary row (never raises)."""
    import sketchsurf

    start = time.monotonic()
    row = {"sketch": str(sketch_path), "output": str(output_path)}
    try:
        sketch = sketchsurf.read_sketch(str(sketch_path))
        V, F, labels, sharp, report = sketchsurf.surface(sketch, params or {})
        pathlib.Path(output_path).parent.mkdir(parents=True, exist_ok=True)
        sketchsurf.write_mesh(str(output_path), V, F, labels, sharp)
        row.update(status="ok", regions=report["regions"], vertices=report["vertices"],
                   stroke_distance=report["stroke_distance"], warnings=report["warnings"])
    except Exception as e:  # a failed sketch is a row, not a failed batch
        row.update(status="failed", error=str(e), kind=getattr(e, "kind", type(e).__name__))
    row["seconds"] = time.monotonic() - start
    return row


def surface_folder(folder, out_dir, client, params=None, output_format="ply"):
    """Surfaces every sketch of `folder` on the Dask `client`'s workers; returns the rows and
    writes them to OUT_DIR/summary.json."""
    folder, out_dir = pathlib.Path(folder), pathlib.Path(out_dir)
    sketches = find_sketches(folder)
    outputs = [out_dir / p.relative_to(folder).with_suffix("." + output_format) for p in sketches]
    futures = client.map(surface_file, [str(p) for p in sketches], [str(o) for o in outputs],
                         [params] * len(sketches), pure=False)
    rows = client.gather(futures)
    out_dir.mkdir(parents=True, exist_ok=True)
    temporary = out_dir / ("summary.json.tmp-%d" % os.getpid())
    temporary.write_text(json.dumps(rows, indent=2) + "\n")
    temporary.replace(out_dir / "summary.json")
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m sketchsurf.batch", description=__doc__.split("\n\n")[0])
    parser.add_argument("folder")
    parser.add_argument("-o", "--output", required=True)
    parser.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster)")
    parser.add_argument("--workers", type=int, default=None, help="LocalCluster worker processes")
    parser.add_argument("--format", default="ply", choices=["ply", "obj", "glb", "gltf"])
    parser.add_argument("--param", action="append", default=[], metavar="NAME=VALUE")
    args = parser.parse_args(argv)
    params = {}
    for item in args.param:
        name, _, value = item.partition("=")
        params[name] = float(value)

    from dask.distributed import Client, LocalCluster

    if args.scheduler:
        client = Client(args.scheduler)
    else:
        client = Client(LocalCluster(n_workers=args.workers, threads_per_worker=1))
    with client:
        rows = surface_folder(args.folder, args.output, client, params, args.format)
    width = max([len(r["sketch"]) for r in rows] + [6])
    for r in rows:
        detail = ("%d regions, %d vertices" % (r["regions"], r["vertices"]) if r["status"] == "ok"
                  else r["error"])
        print("%-*s  %-6s  %6.1f s  %s" % (width, r["sketch"], r["status"], r["seconds"], detail))
    failed = sum(r["status"] != "ok" for r in rows)
    print("%d of %d sketches surfaced" % (len(rows) - failed, len(rows)), file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
