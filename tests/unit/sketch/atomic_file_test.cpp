#include "surfacing/sketch/io/atomic_file.h"

#include <gtest/gtest.h>

#include "tests/unit/sketch/io_test_support.h"

namespace sketchsurf {
namespace {

using testing::TempDir;

TEST(AtomicFile, ReplacesTheFileAndLeavesNoTemporary) {
  TempDir dir;
  testing::write_text(dir / "f.txt", "old");
  write_atomically(dir / "f.txt", [](std::ostream& out) { out << "new content"; });
  EXPECT_EQ(testing::read_text(dir / "f.txt"), "new content");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"f.txt"});
}

TEST(AtomicFile, AnErrorMidwayLeavesTheOldFileUntouchedAndNoTemporary) {
  TempDir dir;
  testing::write_text(dir / "f.txt", "old");
  const std::string big(1 << 20, 'x');  // more than a stream buffer: bytes did reach the disk
  try {
    write_atomically(dir / "f.txt", [&](std::ostream& out) {
      out << big;
      throw Error::processing("stroke 3 is not finite");
    });
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Processing);
    EXPECT_STREQ(e.what(), "stroke 3 is not finite");  // passes through unchanged
  }
  EXPECT_EQ(testing::read_text(dir / "f.txt"), "old");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"f.txt"});
}

TEST(AtomicFile, AnyExceptionMidwayLeavesNoNewFile) {
  TempDir dir;
  EXPECT_THROW(write_atomically(dir / "g.txt",
                                [](std::ostream& out) {
                                  out << "partial";
                                  throw std::bad_alloc();
                                }),
               std::exception);
  EXPECT_TRUE(dir.files().empty());
}

TEST(AtomicFile, UnwritablePlacesAreProcessingErrors) {
  TempDir dir;
  testing::expect_error(
      [&] { write_atomically(dir / "missing" / "f.txt", [](std::ostream& out) { out << "x"; }); },
      ErrorKind::Processing, {"f.txt", "cannot create"});
  std::filesystem::create_directory(dir / "d");
  // Renaming a file over a directory fails: the temporary is removed, the directory stays.
  testing::expect_error([&] { write_atomically(dir / "d", [](std::ostream& out) { out << "x"; }); },
                        ErrorKind::Processing, {"cannot replace"});
  EXPECT_EQ(dir.files(), std::vector<std::string>{"d"});
  EXPECT_TRUE(std::filesystem::is_directory(dir / "d"));
}

}  // namespace
}  // namespace sketchsurf
