// The read confinement (vdg/io/read_file.h, ScopedReadRoot): while a root is set, only files that
// lie below it once opened are read, whatever path, symbolic link or swap led to them.
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/io/read_file.h"

namespace vdg {
namespace {

namespace fs = std::filesystem;
using testing::errorOf;
using testing::TempDir;
using testing::writeText;

// root/ (the read root) holds inside.txt; outside.txt lies beside it.
struct RootBench {
  TempDir dir;
  std::string root = fs::canonical(dir.path()).string() + "/root";
  std::string inside = root + "/inside.txt";
  std::string outside = fs::canonical(dir.path()).string() + "/outside.txt";
  RootBench() {
    writeText(inside, "inside");
    writeText(outside, "outside");
  }
};

TEST(ReadRoot, WithoutARootEveryFileIsRead) {
  RootBench b;
  EXPECT_EQ(currentReadRoot(), "");
  EXPECT_EQ(readFileLimited(b.outside, "model", 100), "outside");
}

TEST(ReadRoot, FilesBelowTheRootAreRead) {
  RootBench b;
  fs::create_directories(b.root + "/sub");
  fs::create_symlink("../inside.txt", b.root + "/sub/link.txt");
  const ScopedReadRoot confinement(b.root);
  EXPECT_EQ(currentReadRoot(), b.root);
  EXPECT_EQ(readFileLimited(b.inside, "model", 100), "inside");
  EXPECT_EQ(readFileLimited(b.root + "/sub/link.txt", "model", 100), "inside");  // a link that stays inside
  EXPECT_NO_THROW(checkInputFile(b.inside, "model"));
}

TEST(ReadRoot, FilesOutsideAreRefusedWhateverLeadsThere) {
  RootBench b;
  fs::create_symlink(b.outside, b.root + "/link.bin");
  fs::create_directories(b.root + "/d");
  fs::create_directory_symlink(fs::path(b.outside).parent_path(), b.root + "/d/up");
  const ScopedReadRoot confinement(b.root);
  const std::string message = "'";
  EXPECT_EQ(errorOf([&] { (void)readFileLimited(b.root + "/link.bin", "glTF buffer", 100); }),
            b.root + "/link.bin: the glTF buffer leads outside the read root '" + b.root + message);
  EXPECT_EQ(errorOf([&] { checkInputFile(b.outside, "model"); }),
            b.outside + ": the model leads outside the read root '" + b.root + message);
  EXPECT_EQ(errorOf([&] { (void)readFileLimited(b.root + "/d/up/outside.txt", "texture", 100); }),
            b.root + "/d/up/outside.txt: the texture leads outside the read root '" + b.root + message);
  EXPECT_THROW((void)readFileLimited(b.root + "/link.bin", "x", 100), ReadRootError);
}

TEST(ReadRoot, NestedRootsRestoreTheOuterOne) {
  RootBench b;
  fs::create_directories(b.root + "/sub");
  writeText(b.root + "/sub/a.txt", "a");
  {
    const ScopedReadRoot outer(b.root);
    {
      const ScopedReadRoot inner(b.root + "/sub");
      EXPECT_THROW((void)readFileLimited(b.inside, "model", 100), ReadRootError);
      EXPECT_EQ(readFileLimited(b.root + "/sub/a.txt", "model", 100), "a");
    }
    EXPECT_EQ(readFileLimited(b.inside, "model", 100), "inside");
  }
  EXPECT_EQ(currentReadRoot(), "");
  EXPECT_EQ(errorOf([&] { const ScopedReadRoot none(b.root + "/missing"); }),
            b.root + "/missing: the read root is not a folder: No such file or directory");
}

// The check is made on what was opened: a descriptor opened through a link to a file outside stays
// outside after the link has been swapped for a regular file inside (a check of the path would now
// pass).
TEST(ReadRoot, TheCheckIsOnTheOpenedFileNotOnThePath) {
  RootBench b;
  const std::string swapped = b.root + "/swapped.bin";
  fs::create_symlink(b.outside, swapped);
  const int fd = ::open(swapped.c_str(), O_RDONLY | O_CLOEXEC);
  ASSERT_GE(fd, 0);
  fs::remove(swapped);
  writeText(swapped, "inside now");
  EXPECT_FALSE(openedBelow(fd, swapped, b.root));
  ::close(fd);
  const int inside = ::open(swapped.c_str(), O_RDONLY | O_CLOEXEC);
  EXPECT_TRUE(openedBelow(inside, swapped, b.root));
  ::close(inside);
}

// A path flipped between a file inside and a link to a file outside while it is read over and over:
// every read gives the inside bytes or is refused, never the outside bytes.
TEST(ReadRoot, ARacedSwapNeverReadsOutside) {
  RootBench b;
  const std::string path = b.root + "/flip.txt";
  writeText(b.root + "/real.txt", "inside");
  fs::create_symlink(b.outside, b.root + "/away.txt");
  std::atomic<bool> stop{false};
  std::thread flipper([&] {
    for (int i = 0; !stop; ++i) {
      const std::string next = b.root + "/next.txt";
      std::error_code ec;
      fs::remove(next, ec);
      fs::create_symlink(i % 2 ? b.root + "/real.txt" : b.outside, next, ec);
      ::rename(next.c_str(), path.c_str());
    }
  });
  constexpr int kReads = 3000;
  int read_inside = 0, refused = 0;
  {
    const ScopedReadRoot confinement(b.root);
    for (int i = 0; i < kReads; ++i) {
      try {
        const std::string text = readFileLimited(path, "model", 100);
        EXPECT_EQ(text, "inside");
        ++read_inside;
      } catch (const ReadRootError&) {
        ++refused;
      } catch (const Error&) {  // the name missing between two swaps
      }
    }
  }
  stop = true;
  flipper.join();
  EXPECT_GT(read_inside + refused, 0);
}

}  // namespace
}  // namespace vdg
