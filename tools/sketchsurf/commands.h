#pragma once
// The sketchsurf CLI: one add_*_command per subcommand, each in its own cmd_*.cpp.
// A command's callback throws sketchsurf::Error; main() maps it to the exit code.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "surfacing/mesh.h"
#include "surfacing/progress.h"
#include "surfacing/sketch/decorations.h"
#include "surfacing/sketch/io/sketch_io.h"

namespace sketchsurf::cli {

/// Options shared by every command.
struct GlobalOptions {
  bool verbose = false;  ///< print the parameters in effect and extra detail to stderr
  bool quiet = false;    ///< no progress or warnings on stderr
};

void add_info_command(CLI::App& app, const GlobalOptions& global);
void add_convert_command(CLI::App& app, const GlobalOptions& global);
/// `proxy` (cmd_proxy.cpp): the proxy surface, VIPSS or an attracted user mesh (paper §5).
void add_proxy_command(CLI::App& app, const GlobalOptions& global);
/// `segment` (cmd_segment.cpp): proxy labelled into smooth regions, paper §4.1-4.2.
void add_segment_command(CLI::App& app, const GlobalOptions& global);
/// `surface` (cmd_surface.cpp): the final piecewise-smooth surface, the whole method (paper §4-5).
void add_surface_command(CLI::App& app, const GlobalOptions& global);
/// `batch` (cmd_batch.cpp): `surface` on every sketch of folders or files, one process each.
void add_batch_command(CLI::App& app, const GlobalOptions& global);
/// `eval` (cmd_eval.cpp): a surface against its ground truth (accuracy, completeness, creases).
void add_eval_command(CLI::App& app, const GlobalOptions& global);
/// `synth` (cmd_synth.cpp): a synthetic sketch drawn on a mesh, clean or VR-like.
void add_synth_command(CLI::App& app, const GlobalOptions& global);
/// `review` (cmd_review.cpp): contact sheets and an index page; only with SKETCHSURF_ENGINE.
void add_review_command(CLI::App& app, const GlobalOptions& global);
/// `render` (cmd_render.cpp); only in builds with SKETCHSURF_ENGINE (SKETCHSURF_HAVE_ENGINE).
void add_render_command(CLI::App& app, const GlobalOptions& global);

/// Progress on stderr: a bar on a terminal, one plain line per stage and per 10% otherwise.
ProgressCallback stderr_progress(const GlobalOptions& global);
/// Reads a sketch, prints its reader warnings, refuses coordinates too large to surface
/// (check_extent), cleans it (NaN/Inf, duplicates, too-short strokes)
/// and prints what cleaning removed, unless quiet.
Sketch read_clean_sketch(const std::string& file, const GlobalOptions& global);
/// Reads a user's proxy mesh (--proxy, --from) and refuses one that cannot be a proxy of `sketch`
/// (proxy_mesh_problem(): not finite, beyond +-1e12, no area, far larger or smaller than the
/// strokes) with an Error (Input) naming the file, before any work: such a mesh would otherwise
/// spend minutes and gigabytes in remeshing, or fail later without a file named.
TriMesh read_proxy_mesh(const std::string& file, const Sketch& sketch);
/// Rethrows `e` from the work on `file` with the file named: an input or processing error says
/// which sketch it is about (batch runs print many); others as they are.
[[noreturn]] void rethrow_naming(const std::string& file, const Error& e);
/// Notes on stderr, unless quiet, the strokes of `file` left out as depicting no surface, with
/// what keeps them (`keep_hint`, e.g. "--keep-all-strokes keeps them"), or, with `tubes` > 0, the
/// tubes drawn round them instead.
void note_decorations(const GlobalOptions& global, const std::string& file,
                      const std::vector<Decoration>& decorations, std::size_t tubes,
                      const std::string& keep_hint);
/// Prints reader warnings to stderr as "FILE: warning: ...", unless quiet.
void print_warnings(const GlobalOptions& global, const std::string& file, const Warnings& warnings);
/// `text` with control bytes other than newline and tab written as \xNN: what a terminal is
/// given never holds a NUL byte or an escape sequence from a broken file.
std::string printable(std::string_view text);

}  // namespace sketchsurf::cli
