// sketchsurf batch SKETCH...|DIR... -o OUT_DIR [--jobs N] [--format ply|obj|glb|gltf] [--seed N]
// [--threads N] [--keep-all-strokes | --tubes] [--closed] [--force] [--param NAME=VALUE]...:
// `surface` on every sketch, each in a process of its own, so that a failure, a crash or an
// out-of-memory kill in one never stops the others; a summary table at the end, exit 0 only when
// every sketch was surfaced.

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "surfacing/error.h"
#include "surfacing/parallel.h"
#include "surfacing/pipeline.h"
#include "surfacing/sketch/io/atomic_file.h"
#include "tools/sketchsurf/commands.h"
#include "tools/sketchsurf/run_files.h"

extern char** environ;

namespace sketchsurf::cli {

namespace {

namespace fs = std::filesystem;

struct BatchOptions {
  std::vector<std::string> inputs;
  std::string output;
  unsigned jobs = 1;
  std::string format = "ply";
  std::optional<std::uint64_t> seed;
  std::optional<unsigned> threads;
  bool keep_all_strokes = false;
  bool tubes = false;
  bool closed = false;
  bool force = false;
  std::vector<std::string> params;
};

/// One sketch to surface: where it is, and its outputs' path under OUT_DIR without extension
/// (the path below the folder it was found in, or its stem when given by name).
struct Job {
  fs::path sketch;
  fs::path name;
};

/// How one sketch went.
struct Outcome {
  bool ran = false;        ///< false: not started (the batch was cancelled first)
  int exit_code = -1;      ///< the surface run's exit code; -1 when it died of a signal
  int signal = 0;          ///< the signal that ended it, if any
  double seconds = 0.0;    ///< wall-clock time of the run
  std::string error;       ///< what went wrong, from its log
  nlohmann::json report;   ///< its report.json when it succeeded
  bool ok() const { return ran && exit_code == 0; }
};

bool is_sketch_path(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const auto known = readable_sketch_extensions();
  return std::find(known.begin(), known.end(), ext) != known.end();
}

bool same_path(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return fs::equivalent(a, b, ec) && !ec;
}

/// The sketches of a folder, recursively (a `.tilt` folder is one sketch), sorted by path,
/// leaving out `skip` (the output folder, when it lies inside).
std::vector<Job> sketches_in(const fs::path& folder, const fs::path& skip) {
  std::vector<Job> found;
  std::error_code ec;
  fs::recursive_directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec);
  for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    const fs::path& path = it->path();
    const bool directory = it->is_directory(ec);
    if (directory && same_path(path, skip)) {
      it.disable_recursion_pending();
    } else if (is_sketch_path(path) && (directory || it->is_regular_file(ec))) {
      found.push_back({path, fs::path(path.lexically_relative(folder)).replace_extension()});
      if (directory) it.disable_recursion_pending();
    }
  }
  if (ec) throw Error::input(folder, "cannot list the folder: " + ec.message());
  std::sort(found.begin(), found.end(), [](const Job& a, const Job& b) { return a.name < b.name; });
  return found;
}

/// Every sketch named by the inputs, each with its own output name.
/// @throws Error (Usage) for an input that does not exist, a folder without sketches, or two
///         sketches that would write the same output.
std::vector<Job> collect_jobs(const std::vector<std::string>& inputs, const fs::path& out_dir) {
  std::vector<Job> jobs;
  for (const std::string& input : inputs) {
    const fs::path path(input);
    std::error_code ec;
    if (fs::is_directory(path, ec) && !is_sketch_path(path)) {
      std::vector<Job> found = sketches_in(path, out_dir);
      if (found.empty())
        throw Error::usage(input + ": no sketch (.tilt, .curves, .obj, .json) in this folder");
      jobs.insert(jobs.end(), found.begin(), found.end());
    } else if (fs::exists(path, ec)) {
      jobs.push_back({path, path.stem()});
    } else {
      throw Error::usage(input + ": no such file or folder");
    }
  }
  std::map<fs::path, fs::path> names;
  for (const Job& job : jobs) {
    const auto [at, added] = names.emplace(job.name, job.sketch);
    if (!added)
      throw Error::usage(at->second.string() + " and " + job.sketch.string() + " would both be written to " +
                         (out_dir / job.name).string() +
                         ".*; give their folders instead (outputs keep the folders' structure)");
  }
  return jobs;
}

/// Starts `exe args...` in a process group of its own (so that Ctrl-C reaches the batch, which
/// passes it on once), stdout discarded, stderr to `log`.
pid_t spawn(const fs::path& exe, const std::vector<std::string>& args, const fs::path& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  std::vector<std::string> words{exe.string()};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, exe.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw Error::processing("cannot start " + exe.string() + ": " + std::strerror(rc));
  return pid;
}

/// The message of the last "error:" line of a run's log (its cause), or "".
std::string error_from_log(const fs::path& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line)) {
    const auto at = line.find("error: ");
    if (at != std::string::npos) last = line.substr(at + 7);
  }
  return last;
}

/// The summary table: one row per sketch.
void print_table(std::ostream& out, const std::vector<Job>& jobs, const std::vector<Outcome>& outcomes) {
  std::vector<std::vector<std::string>> rows{{"sketch", "result", "vertices", "regions", "stroke median", "warnings", "time"}};
  auto fixed = [](double v, int digits, const char* unit) {
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(digits);
    s << v << unit;
    return s.str();
  };
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const Outcome& o = outcomes[i];
    std::vector<std::string> row{jobs[i].name.string()};
    if (!o.ran) {
      row.push_back("not run");
    } else if (!o.ok()) {
      row.push_back(o.signal ? "killed (signal " + std::to_string(o.signal) + ")"
                             : "failed (exit " + std::to_string(o.exit_code) + ")");
    } else {
      const nlohmann::json& r = o.report;
      row.push_back("ok");
      row.push_back(std::to_string(r.value("/mesh/vertices"_json_pointer, 0)));
      row.push_back(std::to_string(r.value("regions", 0)));
      row.push_back(fixed(100.0 * r.value("/stroke_distance/median"_json_pointer, 0.0), 3, "%"));
      row.push_back(std::to_string(r.value("/checks/warnings"_json_pointer, nlohmann::json::array()).size()));
    }
    if (o.ran) {
      row.resize(6);
      row.push_back(fixed(o.seconds, 1, " s"));
    }
    rows.push_back(std::move(row));
  }
  std::vector<std::size_t> width(rows[0].size(), 0);
  for (const auto& row : rows)
    for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  for (const auto& row : rows) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c) {
      const std::string pad(width[c] - row[c].size(), ' ');
      line += c < 2 ? row[c] + pad : pad + row[c];  // names left, numbers right
      if (c + 1 < row.size()) line += "  ";
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out << line << "\n";
  }
  for (std::size_t i = 0; i < jobs.size(); ++i)
    if (outcomes[i].ran && !outcomes[i].ok())
      out << jobs[i].name.string() << ": " << printable(outcomes[i].error) << "\n";
}

nlohmann::json summary_json(const std::vector<Job>& jobs, const std::vector<Outcome>& outcomes, const std::string& format) {
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const Outcome& o = outcomes[i];
    nlohmann::json row{{"sketch", jobs[i].sketch.string()},
                       {"output", jobs[i].name.string() + "." + format},
                       {"status", !o.ran ? "not run" : o.ok() ? "ok" : "failed"},
                       {"exit_code", o.exit_code},
                       {"seconds", o.seconds}};
    if (o.signal) row["signal"] = o.signal;
    if (!o.error.empty()) row["error"] = o.error;
    if (o.ok())
      row["result"] = {{"vertices", o.report.value("/mesh/vertices"_json_pointer, 0)},
                       {"regions", o.report.value("regions", 0)},
                       {"stroke_distance", o.report.value("stroke_distance", nlohmann::json::object())},
                       {"warnings", o.report.value("/checks/warnings"_json_pointer, nlohmann::json::array())}};
    rows.push_back(std::move(row));
  }
  return rows;
}

void run_batch(const BatchOptions& opt, const GlobalOptions& global) {
  const fs::path out_dir(opt.output);
  const std::map<std::string, double> given = parse_params(opt.params);
  try {  // a wrong name is told once, before any run starts
    Params().apply(given);
  } catch (const Error& e) {
    throw Error::usage(std::string("--param: ") + e.what());
  }
  std::error_code ec;
  if (fs::exists(out_dir, ec) && !fs::is_directory(out_dir, ec))
    throw Error::usage("-o " + opt.output + ": not a folder; batch writes one output per sketch into a folder");
  const std::vector<Job> jobs = collect_jobs(opt.inputs, out_dir);
  fs::create_directories(out_dir, ec);
  if (ec) throw Error::usage("-o " + opt.output + ": cannot create the folder: " + ec.message());
  RunFiles files;  // Ctrl-C and SIGTERM: stop starting runs, pass it on to the running ones
  const fs::path summary = out_dir / "summary.json";
  for (const Job& job : jobs) files.input(job.sketch.string());
  files.output("-o", summary.string());
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error::processing("cannot find the sketchsurf executable (/proc/self/exe): " + ec.message());

  // Each run gets its share of the cores unless told otherwise: --jobs runs side by side.
  const unsigned threads = opt.threads ? *opt.threads : std::max(1u, resolve_threads(0) / opt.jobs);
  using Clock = std::chrono::steady_clock;
  struct Running {
    std::size_t job;
    Clock::time_point start;
  };
  std::map<pid_t, Running> running;
  std::vector<Outcome> outcomes(jobs.size());
  std::size_t next = 0, done = 0;
  bool passed_on = false;
  while (next < jobs.size() || !running.empty()) {
    while (!cancel_requested() && running.size() < opt.jobs && next < jobs.size()) {
      const Job& job = jobs[next];
      const fs::path base = out_dir / job.name;
      fs::create_directories(base.parent_path(), ec);
      std::vector<std::string> args{"surface", job.sketch.string(), "-o", base.string() + "." + opt.format,
                                    "--report", base.string() + ".json", "--threads", std::to_string(threads)};
      if (opt.seed) args.insert(args.end(), {"--seed", std::to_string(*opt.seed)});
      if (opt.keep_all_strokes) args.push_back("--keep-all-strokes");
      if (opt.tubes) args.push_back("--tubes");
      if (opt.closed) args.push_back("--closed");
      if (opt.force) args.push_back("--force");
      for (const std::string& p : opt.params) args.insert(args.end(), {"--param", p});
      running[spawn(exe, args, base.string() + ".log")] = {next, Clock::now()};
      outcomes[next].ran = true;
      ++next;
    }
    if (cancel_requested()) {
      next = jobs.size();
      if (!passed_on)
        for (const auto& [pid, run] : running) kill(pid, SIGINT);
      passed_on = true;
    }
    if (running.empty()) break;
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;  // a signal: cancel_requested() may have changed
      throw Error::processing(std::string("waiting for a surface run: ") + std::strerror(errno));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const Job& job = jobs[it->second.job];
    Outcome& o = outcomes[it->second.job];
    o.seconds = std::chrono::duration<double>(Clock::now() - it->second.start).count();
    running.erase(it);
    const fs::path base = out_dir / job.name;
    if (WIFEXITED(status)) {
      o.exit_code = WEXITSTATUS(status);
    } else if (WIFSIGNALED(status)) {
      o.signal = WTERMSIG(status);
      o.error = std::string("killed by signal ") + std::to_string(o.signal) + " (" + strsignal(o.signal) + ")";
    }
    if (o.exit_code == 0) {
      std::ifstream in(base.string() + ".json");
      o.report = nlohmann::json::parse(in, nullptr, false);
      if (o.report.is_discarded()) o.report = nlohmann::json::object();
    } else if (!o.signal) {
      o.error = error_from_log(base.string() + ".log");
      if (o.error.empty()) o.error = "exit code " + std::to_string(o.exit_code);
    }
    ++done;
    if (!global.quiet)
      std::cerr << "batch: [" << done << "/" << jobs.size() << "] " << job.name.string() << ": "
                << (o.ok() ? "ok" : "failed: " + printable(o.error)) << "\n";
  }

  print_table(std::cout, jobs, outcomes);
  std::cout.flush();
  // Written also when cancelled: it says what was done.
  const nlohmann::json j = summary_json(jobs, outcomes, opt.format);
  write_atomically(summary, [&](std::ostream& out) { out << j.dump(2) << "\n"; });
  std::size_t ok = 0;
  std::string failed;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (outcomes[i].ok()) ++ok;
    else if (outcomes[i].ran) failed += (failed.empty() ? "" : ", ") + jobs[i].name.string();
  }
  if (cancel_requested())
    throw Error(ErrorKind::Cancelled, "batch cancelled after " + std::to_string(done) + " of " +
                                          std::to_string(jobs.size()) + " sketches");
  if (ok < jobs.size())
    throw Error::processing(std::to_string(jobs.size() - ok) + " of " + std::to_string(jobs.size()) +
                            " sketches failed (" + failed + "); their logs are " + opt.output + "/NAME.log");
  if (!global.quiet)
    std::cerr << "batch: " << ok << " of " << jobs.size() << " sketches surfaced into " << opt.output << "\n";
}

}  // namespace

void add_batch_command(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<BatchOptions>();
  auto* cmd = app.add_subcommand(
      "batch", "Surface every sketch of folders or files, in parallel; a summary table at the end");
  cmd->add_option("SKETCHES", opt->inputs,
                  "Sketches (.tilt, .curves, .obj, .json) and folders of them (searched recursively)")
      ->required();
  cmd->add_option("-o,--output", opt->output,
                  "Output folder: per sketch NAME.FORMAT, NAME.json (report) and NAME.log; summary.json")
      ->required();
  cmd->add_option("-j,--jobs", opt->jobs, "Sketches surfaced at the same time (default 1)")
      ->check(whole_number(1, kMaxThreads));
  cmd->add_option("--format", opt->format, "Surface format (default ply)")
      ->check(CLI::IsMember({"ply", "obj", "glb", "gltf"}));
  cmd->add_option("--seed", opt->seed, "Random seed of the segmentation")->check(whole_number(0, UINT64_MAX));
  cmd->add_option("--threads", opt->threads, "Worker threads per sketch (default: the cores shared among --jobs)")
      ->check(whole_number(1, kMaxThreads));
  auto* keep_all = cmd->add_flag("--keep-all-strokes", opt->keep_all_strokes,
                                 "Surface every stroke, also those that seem to depict no surface");
  cmd->add_flag("--tubes", opt->tubes, "Draw the strokes that seem to depict no surface as thin tubes")
      ->excludes(keep_all);
  cmd->add_flag("--closed", opt->closed, "Keep every surface closed: do not open it at rims found in the strokes");
  cmd->add_flag("--force", opt->force, "Write surfaces also where the strokes do not seem to depict one");
  cmd->add_option("--param", opt->params,
                  "NAME=VALUE: set a pipeline parameter of every run by its dotted name, as `surface "
                  "--param` does (over each sketch file's own). Repeatable")
      ->allow_extra_args(false);
  cmd->callback([opt, &global] { run_batch(*opt, global); });
}

}  // namespace sketchsurf::cli
