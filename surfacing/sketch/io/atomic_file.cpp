#include "surfacing/sketch/io/atomic_file.h"

#include <fstream>
#include <random>
#include <system_error>

#include "surfacing/error.h"

namespace sketchsurf {

namespace {

std::filesystem::path temporary_name(const std::filesystem::path& file) {
  std::random_device rd;
  const auto tag = std::to_string(rd()) + std::to_string(rd());
  auto tmp = file;
  tmp += ".tmp-" + tag;
  return tmp;
}

}  // namespace

void write_atomically(const std::filesystem::path& file,
                      const std::function<void(std::ostream&)>& write) {
  const auto tmp = temporary_name(file);
  auto remove_tmp = [&] {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
  };
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw Error::processing(file.string() + ": cannot create file for writing");
      write(out);
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

}  // namespace sketchsurf
