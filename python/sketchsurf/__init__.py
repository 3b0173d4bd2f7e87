"""sketchsurf: piecewise-smooth surfaces from unstructured 3D sketches (Yu et al. 2022).

    import sketchsurf
    sketch = sketchsurf.read_sketch("chair.curves")
    V, F, labels, sharp, report = sketchsurf.surface(sketch, {"segment.restarts": 4})
    sketchsurf.write_mesh("chair.ply", V, F, labels, sharp)

surface() also takes a list of (n, 3) NumPy arrays, one per stroke, and a progress callback
progress(stage, fraction) that may return False to cancel; it releases the GIL while it runs, so
threads surface sketches side by side. sketchsurf.batch surfaces a folder on a Dask cluster.
"""

from ._sketchsurf import (  # noqa: F401
    Sketch,
    SketchsurfError,
    parameter_names,
    read_sketch,
    surface,
    write_mesh,
    write_sketch,
)

__all__ = ["Sketch", "SketchsurfError", "parameter_names", "read_sketch", "surface", "write_mesh",
           "write_sketch"]
