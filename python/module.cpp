// The Python module sketchsurf._sketchsurf (pybind11): sketches read and written, the whole
// surfacing as one call on NumPy arrays. The package sketchsurf (python/sketchsurf/) re-exports it.

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstdint>
#include <exception>
#include <mutex>
#include <string>
#include <vector>

#include "surfacing/error.h"
#include "surfacing/pipeline.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"

namespace py = pybind11;

namespace sketchsurf {
namespace {

using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// A stroke's points as an (n, 3) float64 array (a copy).
py::array_t<double> points_array(const Stroke& stroke) {
  py::array_t<double> out({static_cast<py::ssize_t>(stroke.points.size()), py::ssize_t{3}});
  auto a = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < stroke.points.size(); ++i)
    for (py::ssize_t k = 0; k < 3; ++k) a(static_cast<py::ssize_t>(i), k) = stroke.points[i][k];
  return out;
}

/// A stroke whose points are the rows of an (n, 3) array.
Stroke stroke_from(const Points& points) {
  if (points.ndim() != 2 || points.shape(1) != 3)
    throw py::value_error("a stroke is an (n, 3) array of points, got an array of " + std::to_string(points.ndim()) +
                          " dimension(s)" + (points.ndim() == 2 ? " with " + std::to_string(points.shape(1)) + " columns" : ""));
  Stroke stroke;
  auto a = points.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i) stroke.points.emplace_back(a(i, 0), a(i, 1), a(i, 2));
  return stroke;
}

/// A Sketch from what surface() accepts: a Sketch, or a sequence of (n, 3) arrays.
Sketch sketch_from(const py::object& strokes) {
  if (py::isinstance<Sketch>(strokes)) return strokes.cast<Sketch>();
  Sketch sketch;
  for (const py::handle item : strokes) sketch.strokes.push_back(stroke_from(item.cast<Points>()));
  return sketch;
}

py::dict report_dict(const SurfaceResult& r) {
  const SurfaceReport& rep = r.report;
  py::dict d;
  d["regions"] = r.segmentation.models.size();
  d["vertices"] = r.mesh.n_vertices();
  d["faces"] = r.mesh.n_faces();
  d["strokes"] = rep.strokes;
  d["points"] = rep.points;
  d["diagonal"] = rep.diagonal;
  d["user_proxy"] = rep.user_proxy;
  d["stroke_distance"] = py::dict(py::arg("median") = rep.stroke_distance.median, py::arg("p95") = rep.stroke_distance.p95,
                                  py::arg("max") = rep.stroke_distance.max);
  d["warnings"] = rep.checks.warnings;
  std::vector<std::int64_t> ignored;
  for (const Decoration& dec : rep.decorations) ignored.push_back(dec.id);
  d["ignored_strokes"] = ignored;
  d["tubes"] = rep.tubes;
  d["loft_sections"] = rep.proxy.loft_sections;
  if (rep.symmetry) {
    const Plane& plane = rep.symmetry->plane;
    d["symmetry"] = py::dict(py::arg("normal") = std::vector<double>{plane.normal.x(), plane.normal.y(), plane.normal.z()},
                             py::arg("offset") = plane.offset, py::arg("distance") = rep.symmetry->distance,
                             py::arg("half_ends") = rep.symmetry->half_ends);
  } else {
    d["symmetry"] = py::none();
  }
  d["timings"] = py::dict(py::arg("prepare_s") = rep.prepare_s, py::arg("proxy_s") = rep.proxy_s,
                          py::arg("segment_s") = rep.segment_s, py::arg("extraction_s") = rep.extraction_s,
                          py::arg("checks_s") = rep.checks_s, py::arg("total_s") = rep.total_s);
  return d;
}

/// surface(): the GIL is released while the Surfacer runs; the progress callback takes it back for
/// each call (the stages report from worker threads too) and may cancel by returning False. An
/// exception raised by the callback cancels the run and is raised again here.
py::tuple surface_arrays(const py::object& strokes, const std::map<std::string, double>& values,
                  const std::optional<py::function>& progress) {
  Sketch sketch = sketch_from(strokes);
  Params params;
  params.apply(sketch.params);
  params.apply(values);
  std::mutex error_mutex;
  std::exception_ptr callback_error;
  ProgressCallback callback;
  if (progress)
    callback = [&](std::string_view stage, double fraction) {
      py::gil_scoped_acquire gil;
      try {
        const py::object answer = (*progress)(std::string(stage), fraction);
        return answer.is_none() || answer.cast<bool>();
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!callback_error) callback_error = std::current_exception();
        return false;
      }
    };
  SurfaceResult result;
  try {
    py::gil_scoped_release no_gil;
    result = Surfacer(params, callback).run(sketch);
  } catch (const Error&) {
    if (callback_error) std::rethrow_exception(callback_error);
    throw;
  }

  const auto nv = static_cast<py::ssize_t>(result.mesh.n_vertices());
  const auto nf = static_cast<py::ssize_t>(result.mesh.n_faces());
  py::array_t<double> v({nv, py::ssize_t{3}});
  py::array_t<std::int32_t> f({nf, py::ssize_t{3}});
  py::array_t<std::int32_t> labels(nv);
  py::array_t<bool> sharp(nv);
  auto va = v.mutable_unchecked<2>();
  for (const auto vh : result.mesh.vertices()) {
    const auto& p = result.mesh.point(vh);
    for (py::ssize_t k = 0; k < 3; ++k) va(vh.idx(), k) = p[static_cast<int>(k)];
  }
  auto fa = f.mutable_unchecked<2>();
  for (const auto fh : result.mesh.faces()) {
    py::ssize_t k = 0;
    for (const auto vh : result.mesh.fv_range(fh)) fa(fh.idx(), k++) = vh.idx();
  }
  auto la = labels.mutable_unchecked<1>();
  auto sa = sharp.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < nv; ++i) {
    la(i) = result.labels[static_cast<std::size_t>(i)];
    sa(i) = result.sharp[static_cast<std::size_t>(i)] != 0;
  }
  return py::make_tuple(v, f, labels, sharp, report_dict(result));
}

/// write_mesh(): V (n, 3), F (m, 3) and optional per-vertex labels and sharp flags to .ply, .obj,
/// .glb or .gltf, as the CLI writes them.
void write_mesh_arrays(const std::filesystem::path& path, const Points& v,
                       const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>& f,
                       const std::optional<std::vector<int>>& labels, const std::optional<std::vector<bool>>& sharp) {
  if (v.ndim() != 2 || v.shape(1) != 3) throw py::value_error("V must be an (n, 3) array");
  if (f.ndim() != 2 || f.shape(1) != 3) throw py::value_error("F must be an (m, 3) array of vertex indices");
  TriMesh mesh;
  auto va = v.unchecked<2>();
  std::vector<TriMesh::VertexHandle> handles;
  for (py::ssize_t i = 0; i < va.shape(0); ++i) handles.push_back(mesh.add_vertex(TriMesh::Point(va(i, 0), va(i, 1), va(i, 2))));
  auto fa = f.unchecked<2>();
  for (py::ssize_t i = 0; i < fa.shape(0); ++i) {
    for (py::ssize_t k = 0; k < 3; ++k)
      if (fa(i, k) < 0 || fa(i, k) >= va.shape(0))
        throw py::value_error("F[" + std::to_string(i) + "] names vertex " + std::to_string(fa(i, k)) + ", V has " +
                              std::to_string(va.shape(0)));
    mesh.add_face(handles[static_cast<std::size_t>(fa(i, 0))], handles[static_cast<std::size_t>(fa(i, 1))],
                  handles[static_cast<std::size_t>(fa(i, 2))]);
  }
  MeshAttributes attributes;
  if (labels) attributes.labels = *labels;
  if (sharp) attributes.sharp.assign(sharp->begin(), sharp->end());
  for (const std::size_t size : {attributes.labels.size(), attributes.sharp.size()})
    if (size != 0 && size != handles.size())
      throw py::value_error("labels and sharp need one value per vertex (" + std::to_string(handles.size()) + "), got " +
                            std::to_string(size));
  write_mesh(mesh, path, attributes);
}

}  // namespace
}  // namespace sketchsurf

PYBIND11_MODULE(_sketchsurf, m) {
  using namespace sketchsurf;
  m.doc() = "Piecewise-smooth surfaces from unstructured 3D sketches (Yu et al. 2022)";

  // sketchsurf::Error becomes SketchsurfError (a RuntimeError) whose `kind` is "usage", "input",
  // "processing" or "cancelled", as the CLI's exit codes tell them apart.
  static py::exception<Error> error(m, "SketchsurfError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      static const char* kinds[] = {"usage", "input", "processing", "cancelled"};
      const py::object exc = py::reinterpret_borrow<py::object>(error.ptr())(e.what());
      exc.attr("kind") = kinds[static_cast<int>(e.kind())];
      PyErr_SetObject(error.ptr(), exc.ptr());
    }
  });

  py::class_<Sketch>(m, "Sketch", "Strokes with annotations, as read from .tilt, .curves, .obj or .json")
      .def(py::init([](const std::vector<Points>& strokes) {
             Sketch s;
             for (const Points& p : strokes) s.strokes.push_back(stroke_from(p));
             return s;
           }),
           py::arg("strokes") = std::vector<Points>{}, "A sketch from a list of (n, 3) point arrays")
      .def_property(
          "strokes",
          [](const Sketch& s) {
            py::list out;
            for (const Stroke& stroke : s.strokes) out.append(points_array(stroke));
            return out;
          },
          [](Sketch& s, const std::vector<Points>& strokes) {
            s.strokes.clear();
            for (const Points& p : strokes) s.strokes.push_back(stroke_from(p));
          },
          "The strokes' points: a list of (n, 3) float64 arrays (copies)")
      .def_property_readonly("boundary", [](const Sketch& s) {
            std::vector<bool> out;
            for (const Stroke& stroke : s.strokes) out.push_back(stroke.boundary);
            return out;
          }, "Per stroke: marks the edge of an open surface")
      .def_readwrite("params", &Sketch::params, "Surfacing parameters stored with the sketch")
      .def_readwrite("units", &Sketch::units)
      .def_property_readonly("point_count", &Sketch::point_count)
      .def("__len__", [](const Sketch& s) { return s.strokes.size(); });

  m.def("read_sketch", [](const std::filesystem::path& path) { return read_sketch(path); }, py::arg("path"),
        "Reads a sketch (.tilt, .curves, .obj, .json); raises SketchsurfError naming the file and what is wrong");
  m.def("write_sketch", [](const Sketch& sketch, const std::filesystem::path& path) { write_sketch(sketch, path); },
        py::arg("sketch"), py::arg("path"), "Writes a sketch (.json, .tilt, .curves, .obj) by its extension");
  m.def("parameter_names", &Params::names, "The dotted parameter names surface() accepts, e.g. 'segment.restarts'");
  m.def("surface", &surface_arrays, py::arg("strokes"), py::arg("params") = std::map<std::string, double>{},
        py::arg("progress") = py::none(),
        "surface(strokes | Sketch, params={}, progress=None) -> (V, F, labels, sharp, report)\n\n"
        "The whole method. strokes: a Sketch or a list of (n, 3) arrays; params: {'segment.restarts': 2, ...}\n"
        "(applied over the sketch's own); progress(stage, fraction) may return False to cancel. V (n, 3)\n"
        "float64, F (m, 3) int32, labels (n,) int32 region per vertex, sharp (n,) bool, report a dict.\n"
        "The GIL is released while it runs.");
  m.def("write_mesh", &write_mesh_arrays, py::arg("path"), py::arg("V"), py::arg("F"), py::arg("labels") = py::none(),
        py::arg("sharp") = py::none(), "Writes a mesh (.ply, .obj, .glb, .gltf) with optional per-vertex labels and sharp flags");
}
