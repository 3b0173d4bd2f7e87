#include "surfacing/sketch/io/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

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
    // The writer's error, said with the file's name.
    EXPECT_EQ(e.what(), (dir / "f.txt").string() + ": stroke 3 is not finite");
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

TEST(StagedFiles, OutputsAppearTogetherAtCommit) {
  TempDir dir;
  testing::write_text(dir / "a.txt", "old a");
  {
    StagedFiles files;
    files.write(dir / "a.txt", [](const auto& file) {
      write_atomically(file, [](std::ostream& out) { out << "new a"; });
    });
    files.write(dir / "b.json", [](const auto& file) {
      EXPECT_EQ(file.extension(), ".json");  // writers that go by the extension still can
      write_atomically(file, [](std::ostream& out) { out << "new b"; });
    });
    EXPECT_EQ(testing::read_text(dir / "a.txt"), "old a");
    EXPECT_FALSE(std::filesystem::exists(dir / "b.json"));
    files.commit();
  }
  EXPECT_EQ(testing::read_text(dir / "a.txt"), "new a");
  EXPECT_EQ(testing::read_text(dir / "b.json"), "new b");
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"a.txt", "b.json"}));
}

TEST(StagedFiles, AFailureBeforeCommitChangesNoOutputAndLeavesNoTemporary) {
  TempDir dir;
  testing::write_text(dir / "a.txt", "old a");
  try {
    StagedFiles files;
    files.write(dir / "a.txt", [](const auto& file) {
      write_atomically(file, [](std::ostream& out) { out << "new a"; });
    });
    files.write(dir / "b.txt", [](const auto& file) {
      write_atomically(file, [](std::ostream& out) {
        out << "partial";
        throw Error::processing("stroke 0 point 2 is not finite");
      });
    });
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    // The message names the output, not its temporary name.
    EXPECT_EQ(e.what(), (dir / "b.txt").string() + ": stroke 0 point 2 is not finite");
  }
  EXPECT_EQ(testing::read_text(dir / "a.txt"), "old a");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"a.txt"});
}

TEST(AtomicFile, TemporariesOfProcessesThatDiedAreRemovedByTheNextWrite) {
  TempDir dir;
  const pid_t child = fork();
  if (child == 0) _exit(0);
  waitpid(child, nullptr, 0);  // a process id that no longer runs
  const std::string dead = std::to_string(child), alive = std::to_string(getppid());
  for (const std::string& name : std::vector<std::string>{
           "f.ply.tmp-" + dead + "-123", "f.ply.tmp-" + dead + "-9.ply.tmp-" + dead + "-4",
        "f.ply.tmp-" + alive + "-5", "g.ply.tmp-" + dead + "-6", "f.ply.tmp-junk"})
    testing::write_text(dir / name, "left over");
  write_atomically(dir / "f.ply", [](std::ostream& out) { out << "x"; });
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"f.ply", "f.ply.tmp-" + alive + "-5",
                                                   "f.ply.tmp-junk", "g.ply.tmp-" + dead + "-6"}));
}

}  // namespace
}  // namespace sketchsurf
