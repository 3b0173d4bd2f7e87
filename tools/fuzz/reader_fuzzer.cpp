// libFuzzer target for one file reader, chosen at build time: SKETCHSURF_FUZZ_EXTENSION is the
// extension the input is saved under (".tilt", ".curves", ".obj", ".json", ".ply") and
// SKETCHSURF_FUZZ_KIND what reads it:
//   0  read_sketch on the input as a file;
//   1  read_mesh (the reader of --proxy meshes) on the input as a file;
//   2  read_sketch on a directory-form .tilt: the input is a 4-byte little-endian length n, then
//      n bytes of data.sketch, then metadata.json. A .tilt file is a zip whose CRCs a mutation
//      breaks, so this form is what reaches the stroke and metadata parsers.
//
// Each input is written to a private temporary folder and read through the public entry point, so
// the input limits, the extension dispatch and the reader all run as they do for a user.
// Beyond crashes, leaks and sanitizer reports, it checks the error contract: a refused input throws
// sketchsurf::Error whose message names the file, holds no NUL byte and stays short (a broken
// line is quoted cut, never whole). Any other exception escapes and is reported as a crash.

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "surfacing/error.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"

namespace {

namespace fs = std::filesystem;

/// Longest error message accepted: a message quotes at most a short excerpt of the input.
constexpr std::size_t kMaxMessage = 2048;

/// Where every input is written: a file (or a directory-form .tilt) in a private folder.
fs::path& input_file() {
  static fs::path file;
  return file;
}

void remove_folder() {
  std::error_code ec;
  fs::remove_all(input_file().parent_path(), ec);
}

/// Reports a broken contract; abort() makes libFuzzer save the input as a crash.
void fail(const char* what, const std::string& message) {
  std::fprintf(stderr, "reader_fuzzer: %s: %.300s\n", what, message.c_str());
  std::abort();
}

/// Checks what a user is told when an input is refused.
void check_message(const std::string& message) {
  if (message.find(input_file().string()) == std::string::npos) fail("error does not name the file", message);
  if (message.find('\0') != std::string::npos) fail("error holds a NUL byte", message);
  if (message.size() > kMaxMessage) fail("error message too long", message);
}

/// Writes `size` bytes from `data` to `file`.
void write_bytes(const fs::path& file, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) fail("cannot write the input file", file.string());
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::string folder = (fs::temp_directory_path() / "sketchsurf-fuzz-XXXXXX").string();
  if (!mkdtemp(folder.data())) {
    std::perror("reader_fuzzer: mkdtemp");
    std::abort();
  }
  input_file() = fs::path(folder) / ("input" SKETCHSURF_FUZZ_EXTENSION);
  if (SKETCHSURF_FUZZ_KIND == 2) fs::create_directory(input_file());
  std::atexit(remove_folder);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
#if SKETCHSURF_FUZZ_KIND == 2
  std::size_t split = 0;
  if (size >= 4) {
    split = std::min<std::size_t>(size - 4, std::uint32_t{data[0]} | std::uint32_t{data[1]} << 8 |
                                                std::uint32_t{data[2]} << 16 |
                                                std::uint32_t{data[3]} << 24);
    data += 4;
    size -= 4;
  }
  write_bytes(input_file() / "data.sketch", data, split);
  write_bytes(input_file() / "metadata.json", data + split, size - split);
#else
  write_bytes(input_file(), data, size);
#endif
  try {
#if SKETCHSURF_FUZZ_KIND == 1
    sketchsurf::MeshAttributes attributes;
    sketchsurf::read_mesh(input_file(), &attributes);
#else
    sketchsurf::Warnings warnings;
    sketchsurf::read_sketch(input_file(), &warnings);
    for (const std::string& warning : warnings)
      if (warning.find('\0') != std::string::npos || warning.size() > kMaxMessage)
        fail("bad warning", warning);
#endif
  } catch (const sketchsurf::Error& error) {
    check_message(error.what());
  }
  return 0;
}
