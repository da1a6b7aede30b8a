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

}  // namespace
}  // namespace vdg
