// Several files replaced as one step, and recovery of a step interrupted by a crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "file_limit.h"
#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/io/file_transaction.h"

namespace vdg {
namespace {

namespace fs = std::filesystem;

using testing::errorOf;

using testing::entries;
using testing::kFileLimit;

TEST(FileTransaction, CommitWritesEveryFileAndLeavesNoJournal) {
  testing::TempDir dir;
  testing::writeText(dir.file("a.txt"), "old a");
  FileTransaction t(dir.file(".vdg-journal"));
  t.write(dir.file("a.txt"), "new a");
  t.write(dir.file("b.txt"), "new b");
  t.write(dir.file("a.txt"), "newest a");  // the last contents win
  t.commit();
  EXPECT_EQ(testing::readText(dir.file("a.txt")), "newest a");
  EXPECT_EQ(testing::readText(dir.file("b.txt")), "new b");
  EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{"a.txt", "b.txt"}));
  EXPECT_NE(errorOf([&] { t.commit(); }).find("already committed"), std::string::npos);
}

TEST(FileTransaction, AFailedWriteChangesNoFile) {
  testing::TempDir dir;
  testing::writeText(dir.file("mesh.obj"), "old mesh");
  testing::writeText(dir.file("log.json"), "old log");
  const std::string message = testing::errorUnderFileLimit(kFileLimit, [&] {
    FileTransaction t(dir.file(".vdg-journal"));
    t.write(dir.file("mesh.obj"), "new mesh");
    t.write(dir.file("log.json"), std::string(3 * kFileLimit, 'x'));  // the disk is full by now
    t.write(dir.file("model.json"), "new model");
    t.commit();
  });
  EXPECT_EQ(message, dir.file("log.json") + ": cannot write file: File too large");
  EXPECT_EQ(testing::readText(dir.file("mesh.obj")), "old mesh");
  EXPECT_EQ(testing::readText(dir.file("log.json")), "old log");
  EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{"log.json", "mesh.obj"}));
}

TEST(FileTransaction, SpecialFilesAreRefusedBeforeAnythingChanges) {
  testing::TempDir dir;
  testing::writeText(dir.file("a.txt"), "old");
  fs::create_directories(dir.path() / "folder");
  FileTransaction t(dir.file(".vdg-journal"));
  t.write(dir.file("a.txt"), "new");
  t.write(dir.file("folder"), "x");
  EXPECT_NE(errorOf([&] { t.commit(); }).find("folder: is a folder"), std::string::npos);
  EXPECT_EQ(testing::readText(dir.file("a.txt")), "old");
  EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{"a.txt", "folder"}));
}

TEST(FileTransaction, LinksAreFollowed) {
  testing::TempDir dir;
  testing::writeText(dir.file("real.json"), "old");
  fs::create_symlink("real.json", dir.path() / "link.json");
  FileTransaction t(dir.file(".vdg-journal"));
  t.write(dir.file("link.json"), "new");
  t.commit();
  EXPECT_TRUE(fs::is_symlink(dir.path() / "link.json"));
  EXPECT_EQ(testing::readText(dir.file("real.json")), "new");
  // One file named twice, through a link, is refused.
  FileTransaction twice(dir.file(".vdg-journal"));
  twice.write(dir.file("link.json"), "a");
  twice.write(dir.file("real.json"), "b");
  EXPECT_NE(errorOf([&] { twice.commit(); }).find("named twice"), std::string::npos);
  EXPECT_EQ(testing::readText(dir.file("real.json")), "new");
}

std::string journal(const char* state, const std::vector<std::pair<std::string, std::string>>& files) {
  std::string text = std::string(R"({"version": 1, "state": ")") + state + R"(", "files": [)";
  for (std::size_t i = 0; i < files.size(); ++i)
    text +=
        (i ? ", " : "") + std::string(R"({"target": ")") + files[i].first + R"(", "temp": ")" + files[i].second + "\"}";
  return text + "]}";
}

TEST(FileTransaction, RecoveryCompletesAStepThatWasCommitting) {
  testing::TempDir dir;
  const std::string base = fs::absolute(dir.path()).string();
  // The crash came after a.txt was replaced and before b.txt was.
  testing::writeText(dir.file("a.txt"), "new a");
  testing::writeText(dir.file("b.txt"), "old b");
  testing::writeText(dir.file(".vdg-Bb2222"), "new b");
  testing::writeText(dir.file(".vdg-journal"), journal("committing", {{base + "/a.txt", base + "/.vdg-Aa1111"},
                                                                      {base + "/b.txt", base + "/.vdg-Bb2222"}}));
  const auto message = recoverFileTransaction(dir.file(".vdg-journal"));
  ASSERT_TRUE(message.has_value());
  EXPECT_EQ(*message, "completed an interrupted step: wrote " + base + "/a.txt, " + base + "/b.txt");
  EXPECT_EQ(testing::readText(dir.file("a.txt")), "new a");
  EXPECT_EQ(testing::readText(dir.file("b.txt")), "new b");
  EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{"a.txt", "b.txt"}));
  EXPECT_FALSE(recoverFileTransaction(dir.file(".vdg-journal")).has_value());
}

TEST(FileTransaction, RecoveryRollsBackAStepThatWasStaging) {
  testing::TempDir dir;
  const std::string base = fs::absolute(dir.path()).string();
  testing::writeText(dir.file("a.txt"), "old a");
  testing::writeText(dir.file(".vdg-Aa1111"), "half of the new");
  testing::writeText(dir.file(".vdg-journal"), journal("staging", {{base + "/a.txt", base + "/.vdg-Aa1111"},
                                                                   {base + "/b.txt", base + "/.vdg-Bb2222"}}));
  EXPECT_EQ(recoverFileTransaction(dir.file(".vdg-journal")).value_or(""),
            "rolled back an interrupted step: no file had been changed");
  EXPECT_EQ(testing::readText(dir.file("a.txt")), "old a");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"a.txt"});
}

TEST(FileTransaction, APendingJournalBlocksANewStep) {
  testing::TempDir dir;
  testing::writeText(dir.file(".vdg-journal"), journal("staging", {}));
  FileTransaction t(dir.file(".vdg-journal"));
  t.write(dir.file("a.txt"), "new");
  EXPECT_NE(errorOf([&] { t.commit(); }).find("not recovered yet"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir.path() / "a.txt"));
}

TEST(FileTransaction, FolderLockIsExclusive) {
  testing::TempDir dir;
  {
    const FolderLock first(dir.path().string());
    EXPECT_EQ(errorOf([&] { FolderLock second(dir.path().string()); }),
              dir.path().string() + ": another vdg is changing files here; try again when it has finished");
  }
  EXPECT_EQ(errorOf([&] { FolderLock again(dir.path().string()); }), "");  // released with the first
  EXPECT_NE(errorOf([&] { FolderLock none(dir.file("missing")); }).find("cannot open the folder"), std::string::npos);
}

TEST(FileTransaction, AJournalNotWrittenByVdgIsNotTrusted) {
  testing::TempDir dir;
  const std::string base = fs::absolute(dir.path()).string();
  testing::writeText(dir.file("victim.txt"), "keep");
  testing::writeText(dir.file("evil.txt"), "evil");
  const std::string j = dir.file(".vdg-journal");
  const std::pair<std::string, const char*> cases[] = {
      {journal("committing", {{base + "/victim.txt", base + "/evil.txt"}}), "not a step vdg wrote"},
      {journal("committing", {{base + "/victim.txt", "/tmp/.vdg-Aa1111"}}), "not a step vdg wrote"},
      {journal("committing", {{"victim.txt", ".vdg-Aa1111"}}), "not a step vdg wrote"},
      {journal("done", {}), "'state'"},
      {"{ not json", "not valid JSON"},
      {R"({"version": 1, "state": "committing", "files": [], "extra": 1})", "unknown key 'extra'"},
  };
  for (const auto& [text, needle] : cases) {
    testing::writeText(j, text);
    const std::string message = errorOf([&] { recoverFileTransaction(j); });
    EXPECT_NE(message.find(needle), std::string::npos) << message;
    EXPECT_EQ(message.rfind(j, 0), 0u) << message;
    EXPECT_EQ(testing::readText(dir.file("victim.txt")), "keep");
    EXPECT_TRUE(fs::exists(j));
  }
}

TEST(FileTransaction, AWriteOnAProtectedFileUnderAnyNameIsRefused) {
  testing::TempDir dir;
  testing::writeText(dir.file("cube.obj"), "base");
  fs::create_hard_link(dir.path() / "cube.obj", dir.path() / "hard.obj");
  fs::create_symlink("cube.obj", dir.path() / "soft.obj");
  for (const char* name : {"cube.obj", "hard.obj", "soft.obj"}) {
    FileTransaction t(dir.file(".vdg-journal"));
    t.protect(dir.file("cube.obj"), "the base mesh cube.obj");
    t.write(dir.file("front.edits.json"), "log");
    t.write(dir.file(name), "key", "key 'front': its mesh " + std::string(name));
    EXPECT_EQ(errorOf([&] { t.commit(); }),
              "key 'front': its mesh " + std::string(name) +
                  " would replace the base mesh cube.obj (the same file); nothing written");
    EXPECT_EQ(testing::readText(dir.file("cube.obj")), "base");
    EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{"cube.obj", "hard.obj", "soft.obj"}));
  }
  // Two targets that are one file through a hard link.
  FileTransaction twice(dir.file(".vdg-journal"));
  twice.write(dir.file("cube.obj"), "a");
  twice.write(dir.file("hard.obj"), "b");
  EXPECT_NE(errorOf([&] { twice.commit(); }).find("named twice in one step"), std::string::npos);
  EXPECT_EQ(testing::readText(dir.file("cube.obj")), "base");
}

TEST(FileTransaction, AStepWritesOnlyInTheJournalsFolderTree) {
  testing::TempDir dir;
  fs::create_directories(dir.path() / "model" / "keys");
  fs::create_directories(dir.path() / "elsewhere");
  FileTransaction t(dir.file("model/.vdg-journal"));
  t.write(dir.file("model/keys/front.obj"), "in a folder beneath: fine");
  t.write(dir.file("elsewhere/x.obj"), "outside");
  EXPECT_NE(errorOf([&] { t.commit(); }).find("outside the folder of"), std::string::npos);
  EXPECT_TRUE(fs::is_empty(dir.path() / "model" / "keys"));
  FileTransaction fine(dir.file("model/.vdg-journal"));
  fine.write(dir.file("model/keys/front.obj"), "key");
  fine.commit();
  EXPECT_EQ(testing::readText(dir.file("model/keys/front.obj")), "key");
}

TEST(FileTransaction, RecoveryTouchesNothingOutsideTheJournalsFolder) {
  testing::TempDir dir;
  fs::create_directories(dir.path() / "out");
  fs::create_directories(dir.path() / "victim" / "sub");
  const std::string base = fs::absolute(dir.path()).string();
  testing::writeText(dir.file("victim/model.obj"), "keep");
  testing::writeText(dir.file("victim/.vdg-Aa1111"), "evil");
  testing::writeText(dir.file("out/sub.obj"), "keep");
  const std::string j = dir.file("out/.vdg-journal");
  const std::string outside = "is outside the journal's folder";
  const std::pair<std::string, std::string> cases[] = {
      {journal("committing", {{base + "/victim/model.obj", base + "/victim/.vdg-Aa1111"}}), outside},
      {journal("staging", {{base + "/victim/model.obj", base + "/victim/.vdg-Aa1111"}}), outside},
      {journal("committing", {{base + "/out/../victim/model.obj", base + "/out/../victim/.vdg-Aa1111"}}),
       "not a step vdg wrote"},
      // A step of this folder and one elsewhere: nothing at all is done.
      {journal("committing", {{base + "/out/sub.obj", base + "/out/.vdg-Bb2222"},
                              {base + "/victim/model.obj", base + "/victim/.vdg-Aa1111"}}),
       outside},
  };
  testing::writeText(dir.file("out/.vdg-Bb2222"), "new");
  for (const auto& [text, needle] : cases) {
    testing::writeText(j, text);
    const std::string message = errorOf([&] { recoverFileTransaction(j); });
    EXPECT_NE(message.find(needle), std::string::npos) << message;
    EXPECT_EQ(message.rfind(j, 0), 0u) << message;
    EXPECT_EQ(testing::readText(dir.file("victim/model.obj")), "keep");
    EXPECT_EQ(testing::readText(dir.file("victim/.vdg-Aa1111")), "evil");
    EXPECT_EQ(testing::readText(dir.file("out/sub.obj")), "keep");
    EXPECT_TRUE(fs::exists(dir.path() / "out" / ".vdg-Bb2222"));
    EXPECT_TRUE(fs::exists(j));
  }
  // A link out of the folder is outside too: out/link -> ../victim.
  fs::create_directory_symlink("../victim", dir.path() / "out" / "link");
  testing::writeText(j, journal("committing", {{base + "/out/link/model.obj", base + "/out/link/.vdg-Aa1111"}}));
  EXPECT_NE(errorOf([&] { recoverFileTransaction(j); }).find(outside), std::string::npos);
  EXPECT_EQ(testing::readText(dir.file("victim/model.obj")), "keep");
  // A temporary file that is a link is not one vdg made.
  fs::remove(dir.path() / "out" / ".vdg-Bb2222");
  fs::create_symlink("../victim/model.obj", dir.path() / "out" / ".vdg-Bb2222");
  testing::writeText(j, journal("committing", {{base + "/out/sub.obj", base + "/out/.vdg-Bb2222"}}));
  EXPECT_NE(errorOf([&] { recoverFileTransaction(j); }).find("is not a regular file"), std::string::npos);
  EXPECT_EQ(testing::readText(dir.file("out/sub.obj")), "keep");
}

TEST(FileTransaction, RecoveryOfAModelFolderReachesItsKeysFolder) {
  testing::TempDir dir;
  fs::create_directories(dir.path() / "keys");
  const std::string base = fs::absolute(dir.path()).string();
  testing::writeText(dir.file("keys/front.obj"), "old");
  testing::writeText(dir.file("keys/.vdg-Aa1111"), "new");
  const std::string j = dir.file(".vdg-journal");
  testing::writeText(j, journal("committing", {{base + "/keys/front.obj", base + "/keys/.vdg-Aa1111"}}));
  EXPECT_NE(errorOf([&] { recoverFileTransaction(j); }).find("outside the journal's folder"), std::string::npos);
  // Trusted when the caller names it as its own (a key file of the model), and then only it.
  EXPECT_NE(
      errorOf([&] { recoverFileTransaction(j, {dir.file("keys/back.obj")}); }).find("outside the journal's folder"),
      std::string::npos);
  EXPECT_EQ(recoverFileTransaction(j, {dir.file("keys/back.obj"), dir.file("keys/./front.obj")}).value_or(""),
            "completed an interrupted step: wrote " + base + "/keys/front.obj");
  EXPECT_EQ(testing::readText(dir.file("keys/front.obj")), "new");
}

}  // namespace
}  // namespace vdg
