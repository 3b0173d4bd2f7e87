#include "surfacing/sketch/io/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <system_error>

#include "surfacing/error.h"

namespace sketchsurf {

namespace {

constexpr std::string_view kTemporaryInfix = ".tmp-";

/// FILE.tmp-PID-TAG followed by `suffix`.
std::filesystem::path temporary_name(const std::filesystem::path& file, const std::string& suffix) {
  std::random_device rd;
  auto tmp = file;
  tmp += std::string(kTemporaryInfix) + std::to_string(getpid()) + "-" + std::to_string(rd()) + suffix;
  return tmp;
}

/// Removes the FILE.tmp-PID-... files that processes no longer running left next to `file`.
/// Files of a running process (or of one this user cannot signal) are kept.
void remove_stale_temporaries(const std::filesystem::path& file) {
  const std::string prefix = file.filename().string() + std::string(kTemporaryInfix);
  std::error_code ec;
  const auto dir = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!name.starts_with(prefix)) continue;
    const char* first = name.data() + prefix.size();
    const char* last = name.data() + name.size();
    pid_t pid = 0;
    const auto [ptr, err] = std::from_chars(first, last, pid);
    if (err != std::errc() || ptr == last || *ptr != '-' || pid <= 0 || pid == getpid()) continue;
    if (kill(pid, 0) == -1 && errno == ESRCH) {
      std::error_code ignored;
      std::filesystem::remove(it->path(), ignored);
    }
  }
}

/// `message` with every occurrence of `from` replaced by `to`.
std::string replaced(std::string message, const std::string& from, const std::string& to) {
  for (std::size_t at = message.find(from); at != std::string::npos; at = message.find(from, at + to.size()))
    message.replace(at, from.size(), to);
  return message;
}

}  // namespace

void write_atomically(const std::filesystem::path& file,
                      const std::function<void(std::ostream&)>& write) {
  remove_stale_temporaries(file);
  const auto tmp = temporary_name(file, "");
  auto remove_tmp = [&] {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
  };
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out)
        throw Error::processing(file.string() + ": cannot create file for writing (" +
                                std::strerror(errno) +
                                "); write it into an existing directory where you may write");
      try {
        write(out);
      } catch (const Error& e) {
        const std::string named = file.string() + ": ";
        if (std::string_view(e.what()).starts_with(named)) throw;
        throw Error(e.kind(), named + e.what());
      }
      out.flush();
      if (!out) throw Error::processing(file.string() + ": write failed (disk full?)");
      out.close();
      if (out.fail()) throw Error::processing(file.string() + ": closing the file failed");
    }
    std::error_code ec;
    std::filesystem::rename(tmp, file, ec);
    if (ec) throw Error::processing(file.string() + ": cannot replace file: " + ec.message());
  } catch (...) {
    remove_tmp();
    throw;
  }
}

StagedFiles::~StagedFiles() {
  for (const auto& [tmp, final_name] : staged_) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
  }
}

void StagedFiles::write(const std::filesystem::path& file,
                        const std::function<void(const std::filesystem::path&)>& write) {
  remove_stale_temporaries(file);
  const auto tmp = temporary_name(file, file.extension().string());
  staged_.emplace_back(tmp, file);
  try {
    write(tmp);
  } catch (const Error& e) {
    throw Error(e.kind(), replaced(e.what(), tmp.string(), file.string()));
  }
}

void StagedFiles::commit() {
  while (!staged_.empty()) {
    const auto [tmp, file] = staged_.front();
    std::error_code ec;
    std::filesystem::rename(tmp, file, ec);
    if (ec) throw Error::processing(file.string() + ": cannot replace file: " + ec.message());
    staged_.erase(staged_.begin());
  }
}

}  // namespace sketchsurf
