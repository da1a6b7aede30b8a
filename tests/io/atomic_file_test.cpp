// The atomic writer against what a user's disk and a user's -o can hold: a full disk, symbolic
// links, devices, FIFOs, folders, long names, permission bits.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "file_limit.h"
#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"

namespace vdg {
namespace {

namespace fs = std::filesystem;

using testing::errorOf;

using testing::entries;
using testing::kFileLimit;

TEST(AtomicFile, DiskFullLeavesTheTargetByteIdentical) {
  testing::TempDir dir;
  const std::string path = dir.file("frame.png");
  const std::string original(1000, 'o');
  testing::writeText(path, original);
  const std::string big(3 * kFileLimit, 'n');
  const std::string message = testing::errorUnderFileLimit(kFileLimit, [&] { writeFileAtomically(path, big); });
  EXPECT_EQ(message, path + ": cannot write file: File too large");
  EXPECT_EQ(testing::readText(path), original);
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"frame.png"});
  // A new file is not created at all.
  const std::string fresh = dir.file("new.png");
  EXPECT_NE(testing::errorUnderFileLimit(kFileLimit, [&] { writeFileAtomically(fresh, big); }).find("new.png"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(fresh));
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"frame.png"});
  // Under the limit the same child writes fine: the limit, not the test, made it fail.
  EXPECT_EQ(testing::errorUnderFileLimit(kFileLimit, [&] { writeFileAtomically(path, "small"); }), "");
  EXPECT_EQ(testing::readText(path), "small");
}

TEST(AtomicFile, FailureInTheWriterLeavesTheOldFile) {
  testing::TempDir dir;
  const std::string path = dir.file("keep.txt");
  testing::writeText(path, "original");
  EXPECT_THROW(writeFileAtomically(path,
                                   [](std::ostream& out) {
                                     out << "half";
                                     throw Error("interrupted");
                                   }),
               Error);
  EXPECT_EQ(testing::readText(path), "original");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"keep.txt"});
}

TEST(AtomicFile, SymlinksAreFollowedAndStayLinks) {
  testing::TempDir dir;
  fs::create_directories(dir.path() / "real");
  testing::writeText(dir.file("real/model.json"), "old");
  fs::create_symlink("real/model.json", dir.path() / "link.json");
  writeFileAtomically(dir.file("link.json"), "new");
  EXPECT_TRUE(fs::is_symlink(dir.path() / "link.json"));
  EXPECT_EQ(testing::readText(dir.file("real/model.json")), "new");
  // The temporary file went beside the real file, and is gone.
  EXPECT_EQ(entries(dir.path() / "real"), std::vector<std::string>{"model.json"});
  // A chain of links, and a dangling link that names a file still to be made.
  fs::create_symlink("link.json", dir.path() / "link2.json");
  writeFileAtomically(dir.file("link2.json"), "newer");
  EXPECT_EQ(testing::readText(dir.file("real/model.json")), "newer");
  fs::create_symlink("real/later.json", dir.path() / "dangling.json");
  writeFileAtomically(dir.file("dangling.json"), "made");
  EXPECT_TRUE(fs::is_symlink(dir.path() / "dangling.json"));
  EXPECT_EQ(testing::readText(dir.file("real/later.json")), "made");
  // A loop of links is an error, not a hang.
  fs::create_symlink("loop_b", dir.path() / "loop_a");
  fs::create_symlink("loop_a", dir.path() / "loop_b");
  EXPECT_NE(errorOf([&] { writeFileAtomically(dir.file("loop_a"), "x"); }).find("too many levels of symbolic links"),
            std::string::npos);
}

TEST(AtomicFile, CharacterDevicesAreWrittenNotReplaced) {
  struct stat before {};
  ASSERT_EQ(::stat("/dev/null", &before), 0);
  ASSERT_TRUE(S_ISCHR(before.st_mode));
  writeFileAtomically("/dev/null", "discarded");
  struct stat after {};
  ASSERT_EQ(::lstat("/dev/null", &after), 0);
  EXPECT_TRUE(S_ISCHR(after.st_mode));
  EXPECT_EQ(after.st_rdev, before.st_rdev);
  EXPECT_EQ(after.st_ino, before.st_ino);
}

TEST(AtomicFile, FifosAreWrittenInPlaceAndNeedAReader) {
  testing::TempDir dir;
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(errorOf([&] { writeFileAtomically(fifo, "x"); }), fifo + ": is a FIFO that no program is reading");
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  writeFileAtomically(fifo, "through the pipe");
  char buffer[64] = {};
  const ssize_t n = ::read(reader, buffer, sizeof buffer);
  ::close(reader);
  EXPECT_EQ(std::string(buffer, n > 0 ? static_cast<std::size_t>(n) : 0), "through the pipe");
  struct stat st {};
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"pipe"});
}

TEST(AtomicFile, FoldersAreRefused) {
  testing::TempDir dir;
  fs::create_directories(dir.path() / "out");
  EXPECT_EQ(errorOf([&] { writeFileAtomically(dir.file("out"), "x"); }), dir.file("out") + ": is a folder, not a file");
  fs::create_symlink("out", dir.path() / "link");
  EXPECT_EQ(errorOf([&] { writeFileAtomically(dir.file("link"), "x"); }),
            dir.file("link") + ": is a folder, not a file");
  EXPECT_TRUE(fs::is_directory(dir.path() / "out"));
  EXPECT_TRUE(fs::is_empty(dir.path() / "out"));
  EXPECT_NE(errorOf([&] { StagedFile(dir.file("out"), "x"); }).find("is a folder"), std::string::npos);
}

TEST(AtomicFile, MissingFolderNamesTheFile) {
  testing::TempDir dir;
  EXPECT_EQ(errorOf([&] { writeFileAtomically(dir.file("no/such/a.obj"), "x"); }),
            dir.file("no/such/a.obj") + ": cannot write file: the folder " + dir.file("no/such") + " does not exist");
}

TEST(AtomicFile, LongestLegalNamesWork) {
  testing::TempDir dir;
  for (const std::size_t length : {250u, 255u}) {
    const std::string name = std::string(length - 4, 'n') + ".obj";
    writeFileAtomically(dir.file(name), "long");
    EXPECT_EQ(testing::readText(dir.file(name)), "long");
    writeFileAtomically(dir.file(name), "replaced");
    EXPECT_EQ(testing::readText(dir.file(name)), "replaced");
  }
  EXPECT_EQ(entries(dir.path()).size(), 2u);
}

TEST(AtomicFile, PermissionBitsAreKeptAndNewFilesFollowTheUmask) {
  testing::TempDir dir;
  const std::string path = dir.file("private.txt");
  testing::writeText(path, "secret");
  fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  writeFileAtomically(path, "still secret");
  EXPECT_EQ(fs::status(path).permissions(), fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  const mode_t old_mask = ::umask(027);
  writeFileAtomically(dir.file("fresh.txt"), "new");
  ::umask(old_mask);
  struct stat st {};
  ASSERT_EQ(::stat(dir.file("fresh.txt").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0640u);
}

TEST(AtomicFile, StagedFileChangesNothingUntilCommitted) {
  testing::TempDir dir;
  const std::string path = dir.file("a.txt");
  testing::writeText(path, "old");
  {
    StagedFile staged(path, "new");
    EXPECT_EQ(fs::path(staged.tempPath()).filename().string().size(), 11u);  // ".vdg-XXXXXX"
    EXPECT_EQ(testing::readText(path), "old");
    EXPECT_EQ(testing::readText(staged.tempPath()), "new");
  }
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"a.txt"});  // dropped: removed
  StagedFile staged(path, "new");
  staged.commit();
  EXPECT_EQ(testing::readText(path), "new");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"a.txt"});
}

}  // namespace
}  // namespace vdg
