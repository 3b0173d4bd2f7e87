#include "surfacing/sketch/io/obj_polylines.h"

#include <algorithm>
#include <set>

#include "surfacing/error.h"
#include "surfacing/sketch/io/atomic_file.h"
#include "surfacing/sketch/io/input_limits.h"
#include "surfacing/sketch/io/text_io.h"

namespace sketchsurf {

namespace {

using Chain = std::vector<std::size_t>;  // vertex indices, 0-based

/// Resolves an OBJ index token ("7", "-2", "7/3") to a 0-based vertex index among the `count`
/// vertices read so far; nullopt when it is malformed or out of range.
std::optional<std::size_t> resolve_index(std::string_view token, std::size_t count,
                                         std::string& why) {
  token = token.substr(0, token.find('/'));
  const auto i = io_detail::parse_int(token);
  if (!i || *i == 0) {
    why = io_detail::excerpt(token) + " is not a vertex index";
    return std::nullopt;
  }
  // 1-based; negative indices count back from the last vertex read (-1 = the last one).
  const std::int64_t zero_based = *i > 0 ? *i - 1 : static_cast<std::int64_t>(count) + *i;
  if (zero_based < 0 || zero_based >= static_cast<std::int64_t>(count)) {
    why = "vertex index " + std::to_string(*i) + " is out of range (" + std::to_string(count) +
          " vertices so far)";
    return std::nullopt;
  }
  return static_cast<std::size_t>(zero_based);
}

/// Chains of a graph made of 2-vertex segments, split at vertices of degree != 2. Open chains run
/// from their smaller end vertex and are listed by that vertex, then by segment order; closed
/// loops (every vertex of degree 2) start and end at their smallest vertex and go first towards
/// its smaller neighbour. Deterministic for a given file.
std::vector<Chain> segment_chains(std::size_t vertex_count,
                                  const std::vector<std::array<std::size_t, 2>>& segments) {
  // Incidence lists in CSR form: the segments at each vertex, in file order.
  std::vector<std::size_t> start(vertex_count + 1, 0);
  for (const auto& s : segments) {
    ++start[s[0] + 1];
    ++start[s[1] + 1];
  }
  for (std::size_t v = 0; v < vertex_count; ++v) start[v + 1] += start[v];
  std::vector<std::size_t> incident(start.back());
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t e = 0; e < segments.size(); ++e) {
      incident[fill[segments[e][0]]++] = e;
      incident[fill[segments[e][1]]++] = e;
    }
  }
  auto degree = [&](std::size_t v) { return start[v + 1] - start[v]; };
  auto other = [&](std::size_t e, std::size_t v) {
    return segments[e][0] == v ? segments[e][1] : segments[e][0];
  };
  std::vector<char> used(segments.size(), 0);
  // Walks from `from` along segment `e` until a vertex of degree != 2 (or back to `stop`).
  auto walk = [&](std::size_t from, std::size_t e, std::size_t stop) {
    Chain chain{from};
    std::size_t v = from;
    for (;;) {
      used[e] = 1;
      v = other(e, v);
      chain.push_back(v);
      if (degree(v) != 2 || v == stop) break;
      const std::size_t a = incident[start[v]], b = incident[start[v] + 1];
      e = a == e ? b : a;
      if (used[e]) break;
    }
    return chain;
  };

  std::vector<Chain> chains;
  for (std::size_t v = 0; v < vertex_count; ++v) {
    if (degree(v) == 2 || degree(v) == 0) continue;
    for (std::size_t k = start[v]; k < start[v + 1]; ++k)
      if (!used[incident[k]]) chains.push_back(walk(v, incident[k], vertex_count));
  }
  // What is left are closed loops through vertices of degree 2 only.
  for (std::size_t v = 0; v < vertex_count; ++v) {
    if (degree(v) != 2 || used[incident[start[v]]]) continue;
    const std::size_t a = incident[start[v]], b = incident[start[v] + 1];
    const std::size_t first = other(a, v) <= other(b, v) ? a : b;
    chains.push_back(walk(v, first, v));
  }
  return chains;
}

}  // namespace

Sketch read_obj_polylines(const std::filesystem::path& file, Warnings* warnings) {
  const std::string text = io_detail::read_file(file);
  io_detail::check_not_empty(text, file);
  io_detail::LineReader lines(text, file);
  std::vector<std::string_view> tokens;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Chain> records;  // the `l` records
  bool all_segments = true;
  std::size_t faces = 0, self_loops = 0;
  std::set<std::string> unknown;
  std::string_view line;
  std::string why;
  PointBudget vertex_budget(file), point_budget(file);
  while (lines.next(line)) {
    io_detail::split_tokens(line, tokens);
    if (tokens.empty() || tokens[0].front() == '#') continue;
    const std::string_view kind = tokens[0];
    if (kind == "v") {
      if (tokens.size() < 4)
        throw Error::input_at_line(file, lines.line_number(), "a vertex needs 3 coordinates");
      Eigen::Vector3d p;
      for (int c = 0; c < 3; ++c) {
        const auto d = io_detail::parse_double(tokens[c + 1]);
        if (!d)
          throw Error::input_at_line(file, lines.line_number(),
                                     io_detail::excerpt(tokens[c + 1]) +
                                         " is not a number");
        p[c] = *d;
      }
      vertex_budget.take(1);
      vertices.push_back(p);
    } else if (kind == "l") {
      if (tokens.size() < 3)
        throw Error::input_at_line(file, lines.line_number(), "a line needs at least 2 vertices");
      // An `l` record may name one vertex many times: its points are counted, not its bytes.
      point_budget.take(tokens.size() - 1);
      Chain chain;
      chain.reserve(tokens.size() - 1);
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        const auto i = resolve_index(tokens[k], vertices.size(), why);
        if (!i) throw Error::input_at_line(file, lines.line_number(), why);
        chain.push_back(*i);
      }
      if (chain.size() == 2 && chain[0] == chain[1]) {
        ++self_loops;  // a segment from a vertex to itself carries no stroke
        continue;
      }
      all_segments = all_segments && chain.size() == 2;
      records.push_back(std::move(chain));
    } else if (kind == "f") {
      ++faces;
    } else if (kind == "vn" || kind == "vt" || kind == "vp" || kind == "o" || kind == "g" ||
               kind == "s" || kind == "usemtl" || kind == "mtllib") {
      // no bearing on strokes
    } else {
      if (unknown.size() < 10) unknown.insert(io_detail::excerpt(kind));
    }
  }
  if (warnings) {
    if (faces)
      warnings->push_back("ignored " + std::to_string(faces) +
                          " face(s): a sketch is read from 'l' records only");
    if (self_loops)
      warnings->push_back("ignored " + std::to_string(self_loops) +
                          " 'l' segment(s) from a vertex to itself");
    if (!unknown.empty()) {
      std::string list;
      for (const auto& k : unknown) list += (list.empty() ? "" : ", ") + k;
      warnings->push_back("ignored records of unknown kind " + list);
    }
  }

  std::vector<Chain> chains;
  if (all_segments && !records.empty()) {
    std::vector<std::array<std::size_t, 2>> segments;
    segments.reserve(records.size());
    for (const auto& r : records) segments.push_back({r[0], r[1]});
    chains = segment_chains(vertices.size(), segments);
  } else {
    chains = std::move(records);
  }

  Sketch sketch;
  sketch.provenance = "OBJ polylines: " + file.filename().string();
  sketch.strokes.reserve(chains.size());
  for (const auto& chain : chains) {
    Stroke stroke;
    stroke.id = static_cast<std::int64_t>(sketch.strokes.size());
    stroke.points.reserve(chain.size());
    for (std::size_t i : chain) stroke.points.push_back(vertices[i]);
    sketch.strokes.push_back(std::move(stroke));
  }
  return sketch;
}

void write_obj_polylines(const Sketch& sketch, const std::filesystem::path& file) {
  write_atomically(file, [&](std::ostream& out) {
    std::string text = "# sketchsurf sketch: " + std::to_string(sketch.strokes.size()) +
                       " strokes as OBJ polylines ('l' records)\n";
    std::size_t next = 1;  // OBJ indices are 1-based
    for (std::size_t s = 0; s < sketch.strokes.size(); ++s) {
      const Stroke& stroke = sketch.strokes[s];
      // An OBJ line needs two vertices; a 0- or 1-point stroke has no polyline to write.
      if (stroke.points.size() < 2) continue;
      for (std::size_t i = 0; i < stroke.points.size(); ++i) {
        const Eigen::Vector3d& p = stroke.points[i];
        if (!p.allFinite())
          throw Error::processing("stroke " + std::to_string(s) + " point " + std::to_string(i) +
                                  " is not finite (NaN or Inf): clean the sketch first");
        text += "v ";
        for (int c = 0; c < 3; ++c) {
          if (c) text += ' ';
          io_detail::append_number(text, p[c]);
        }
        text += '\n';
      }
      text += "l";
      for (std::size_t i = 0; i < stroke.points.size(); ++i) {
        text += ' ';
        text += std::to_string(next + i);
      }
      text += '\n';
      next += stroke.points.size();
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
      text.clear();
    }
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

}  // namespace sketchsurf
