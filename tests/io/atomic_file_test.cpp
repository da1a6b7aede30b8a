// The atomic writer against what a user's disk and a user's -o can hold: a full disk, symbolic
// links, devices, FIFOs, folders, long names, permission bits.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>

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

TEST(AtomicFile, ALinkThatLeavesItsFolderIsNotWrittenThrough) {
  testing::TempDir dir;
  fs::create_directories(dir.path() / "out" / "r");
  testing::writeText(dir.file("victim.png"), "keep");
  fs::create_symlink("../../victim.png", dir.path() / "out" / "r" / "frame_0001.png");
  const std::string frame = dir.file("out/r/frame_0001.png");
  EXPECT_EQ(errorOf([&] { writeFileAtomically(frame, "new"); }),
            frame + ": is a symbolic link to a file outside its folder (" + dir.file("out/r/../../victim.png") +
                "); not written through");
  EXPECT_NE(errorOf([&] { StagedFile(frame, "new"); }).find("outside its folder"), std::string::npos);
  // Absolute links and dangling ones too; a link to a file beside it or beneath it is followed.
  fs::create_symlink(dir.file("victim.png"), dir.path() / "out" / "r" / "abs.png");
  EXPECT_NE(errorOf([&] { writeFileAtomically(dir.file("out/r/abs.png"), "new"); }).find("outside its folder"),
            std::string::npos);
  fs::create_symlink("../made.png", dir.path() / "out" / "r" / "dangling.png");
  EXPECT_NE(errorOf([&] { writeFileAtomically(dir.file("out/r/dangling.png"), "new"); }).find("outside its folder"),
            std::string::npos);
  EXPECT_EQ(testing::readText(dir.file("victim.png")), "keep");
  EXPECT_FALSE(fs::exists(dir.path() / "out" / "made.png"));
  EXPECT_EQ(entries(dir.path() / "out" / "r"), (std::vector<std::string>{"abs.png", "dangling.png", "frame_0001.png"}));
  fs::create_symlink("frame_0002.png", dir.path() / "out" / "r" / "beside.png");
  writeFileAtomically(dir.file("out/r/beside.png"), "made");
  EXPECT_EQ(testing::readText(dir.file("out/r/frame_0002.png")), "made");
}

TEST(AtomicFile, SameFileMeansTheSameDeviceAndInode) {
  testing::TempDir dir;
  testing::writeText(dir.file("base.obj"), "v 0 0 0\n");
  fs::create_hard_link(dir.path() / "base.obj", dir.path() / "hard.obj");
  fs::create_symlink("base.obj", dir.path() / "soft.obj");
  testing::writeText(dir.file("copy.obj"), "v 0 0 0\n");
  EXPECT_TRUE(isSameFile(dir.file("base.obj"), dir.file("hard.obj")));
  EXPECT_TRUE(isSameFile(dir.file("soft.obj"), dir.file("base.obj")));
  EXPECT_TRUE(isSameFile(dir.file("./base.obj"), dir.file("base.obj")));
  EXPECT_FALSE(isSameFile(dir.file("copy.obj"), dir.file("base.obj")));
  EXPECT_FALSE(isSameFile(dir.file("missing.obj"), dir.file("missing.obj")));
}

// Runs `f` in a child process; returns its wait status.
int inChild(const std::function<void()>& f) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    f();
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

TEST(AtomicFile, AnInterruptRemovesTheFilesBeingWrittenAndWhatTheRunMade) {
  for (const int sig : {SIGINT, SIGTERM}) {
    testing::TempDir dir;
    testing::writeText(dir.file("done.png"), "a finished frame");
    const int status = inChild([&] {
      installOutputSignalHandlers();
      makeOutputFolder(dir.file("new/sub"));
      writeFileAtomically(dir.file("new/sub/frame_0000.png"), "a frame of this run");
      writeFileAtomically(dir.file("done.png"), "replaced by this run");
      StagedFile half(dir.file("new/sub/frame.png"), "half");
      StagedFile other(dir.file("frame.png"), "half");
      const int token = removeOnInterrupt(dir.file("journal"));
      testing::writeText(dir.file("journal"), "staging");
      (void)token;
      ::raise(sig);
      ::_exit(0);  // not reached
    });
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 128 + sig);
    EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"done.png"});
    EXPECT_EQ(testing::readText(dir.file("done.png")), "replaced by this run");
  }
}

TEST(AtomicFile, AFailedRunRemovesWhatItMadeAndNothingElse) {
  testing::TempDir dir;
  fs::create_directories(dir.path() / "old");
  testing::writeText(dir.file("old/replaced.png"), "old");
  testing::writeText(dir.file("old/user.txt"), "the user's");
  const int status = inChild([&] {
    makeOutputFolder(dir.file("old/a/b"));
    writeFileAtomically(dir.file("old/a/b/frame_0000.png"), "made");
    writeFileAtomically(dir.file("old/replaced.png"), "new");  // replaced: cannot be given back
    makeOutputFolder(dir.file("kept/c"));
    writeFileAtomically(dir.file("kept/c/frame.png"), "made, then replaced by someone else");
    testing::writeText(dir.file("kept/c/.other"), "x");
    fs::rename(dir.path() / "kept" / "c" / ".other", dir.path() / "kept" / "c" / "frame.png");
    makeOutputFolder(dir.file("old"));  // was there: never removed
    removeNewOutputs();
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{"kept", "old"}));
  EXPECT_EQ(entries(dir.path() / "old"), (std::vector<std::string>{"replaced.png", "user.txt"}));
  EXPECT_EQ(testing::readText(dir.file("old/replaced.png")), "new");
  EXPECT_TRUE(fs::exists(dir.path() / "kept" / "c" / "frame.png"));
  // keepNewOutputs keeps the files (and so their folders).
  const int kept = inChild([&] {
    makeOutputFolder(dir.file("frames"));
    writeFileAtomically(dir.file("frames/frame_0000.png"), "made");
    keepNewOutputs();
    removeNewOutputs();
  });
  ASSERT_TRUE(WIFEXITED(kept));
  EXPECT_TRUE(fs::exists(dir.path() / "frames" / "frame_0000.png"));
  testing::writeText(dir.file("file"), "x");
  EXPECT_EQ(errorOf([&] { makeOutputFolder(dir.file("file")); }), dir.file("file") + ": is a file, not a folder");
}

TEST(AtomicFile, TheLeftoversOfAKilledRunAreRemovedWhenProvenOurs) {
  testing::TempDir dir;
  // This run's temporary name: ".vdg-RRRRRR-PID-TAG".
  std::string temp;
  {
    StagedFile probe(dir.file("probe"), "x");
    temp = fs::path(probe.tempPath()).filename().string();
  }
  const std::string own_pid = "-" + std::to_string(::getpid()) + "-";
  const auto at = temp.find(own_pid);
  ASSERT_NE(at, std::string::npos) << temp;
  const std::string tag = temp.substr(at + own_pid.size());
  ASSERT_EQ(tag.size(), 12u) << temp;
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  testing::TempDir out;
  const std::string stale = ".vdg-Aa1111-" + std::to_string(dead) + "-" + tag;
  const std::string running = ".vdg-Bb2222-1-" + tag;  // init is running
  const std::string foreign = ".vdg-Cc3333-" + std::to_string(dead) + "-000000000000";
  for (const std::string& name : {stale, running, foreign, std::string(".vdg-Dd4444"), std::string("frame.png")})
    testing::writeText(out.file(name), "left");
  fs::create_directories(out.path() / (".vdg-Ee5555-" + std::to_string(dead) + "-" + tag));  // not a file
  writeFileAtomically(out.file("frame.png"), "new");
  EXPECT_EQ(entries(out.path()),
            (std::vector<std::string>{".vdg-Bb2222-1-" + tag, foreign, ".vdg-Dd4444",
                                      ".vdg-Ee5555-" + std::to_string(dead) + "-" + tag, "frame.png"}));
  // A folder with a transaction's journal is left to its recovery.
  testing::TempDir journalled;
  testing::writeText(journalled.file(".vdg-journal"), "{}");
  testing::writeText(journalled.file(stale), "left");
  writeFileAtomically(journalled.file("frame.png"), "new");
  EXPECT_TRUE(fs::exists(journalled.path() / stale));
}

TEST(AtomicFile, AReaderThatGoesAwayIsReaderClosed) {
  testing::TempDir dir;
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const int status = inChild([&] {
    ::signal(SIGPIPE, SIG_IGN);
    std::thread reader([&] {
      const int fd = ::open(fifo.c_str(), O_RDONLY);
      char c = 0;
      (void)!::read(fd, &c, 1);
      ::close(fd);
    });
    std::string message;
    for (;;) {
      try {
        writeFileAtomically(fifo, std::string(std::size_t{1} << 22, 'x'));
        message = "written";
      } catch (const ReaderClosed&) {
        message = "closed";
      } catch (const Error& e) {
        message = e.what();
        if (message.find("no program is reading") != std::string::npos) continue;  // before the reader opened
      }
      break;
    }
    reader.join();
    ::_exit(message == "closed" ? 0 : 1);
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
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
    const std::string name = fs::path(staged.tempPath()).filename().string();
    EXPECT_EQ(name.rfind(".vdg-", 0), 0u) << name;  // ".vdg-RRRRRR-PID-TAG"
    EXPECT_NE(name.find("-" + std::to_string(::getpid()) + "-"), std::string::npos) << name;
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
