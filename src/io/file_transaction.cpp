// Several files replaced as one step, with a journal for crash recovery (design in the header).
#include "vdg/io/file_transaction.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <filesystem>
#include <system_error>

#include "json_reader.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"

namespace vdg {
namespace {

namespace fs = std::filesystem;

constexpr int kJournalVersion = 1;
constexpr std::pair<const char*, bool> kStates[] = {{"staging", false}, {"committing", true}};

struct JournalEntry {
  std::string target, temp;
};

std::string journalText(const char* state, const std::vector<JournalEntry>& entries) {
  nlohmann::ordered_json j;
  j["version"] = kJournalVersion;
  j["state"] = state;
  j["files"] = nlohmann::ordered_json::array();
  for (const JournalEntry& e : entries) j["files"].push_back({{"target", e.target}, {"temp", e.temp}});
  return j.dump(1) + "\n";
}

// A temporary name as vdg makes them (".vdg-" and 6 letters or digits) beside `target`.
bool isTemporaryBeside(const std::string& temp, const std::string& target) {
  const fs::path t(temp);
  const std::string name = t.filename().string();
  if (name.size() != 11 || !name.starts_with(".vdg-")) return false;
  for (char c : name.substr(5))
    if (!std::isalnum(static_cast<unsigned char>(c))) return false;
  return t.is_absolute() && t.parent_path() == fs::path(target).parent_path() && fs::path(target).is_absolute() &&
         fs::path(target).filename() != name;
}

void removeQuietly(const std::string& path) { ::unlink(path.c_str()); }

}  // namespace

FolderLock::FolderLock(const std::string& folder) {
  fd_ = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0)
    throw Error(folder + ": cannot open the folder: " + std::error_code(errno, std::generic_category()).message());
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(fd_);
    if (err == EWOULDBLOCK)
      throw Error(folder + ": another vdg is changing files here; try again when it has finished");
    throw Error(folder + ": cannot lock the folder: " + std::error_code(err, std::generic_category()).message());
  }
}

FolderLock::~FolderLock() { ::close(fd_); }  // closing releases the lock

FileTransaction::FileTransaction(std::string journal_path) : journal_path_(std::move(journal_path)) {}

void FileTransaction::write(const std::string& path, std::string contents) {
  for (File& f : files_)
    if (f.path == path) {
      f.contents = std::move(contents);
      return;
    }
  files_.push_back({path, std::move(contents)});
}

void FileTransaction::commit() {
  if (committed_) throw Error(journal_path_ + ": this transaction was already committed");
  committed_ = true;
  std::error_code ec;
  if (fs::exists(fs::symlink_status(journal_path_, ec)))
    throw Error(journal_path_ + ": an earlier step was interrupted and is not recovered yet; nothing written");

  // Phase 1: the temporary names, journalled before anything else is created.
  std::vector<JournalEntry> entries;
  for (const File& f : files_) {
    const std::string real = fs::absolute(resolveOutputPath(f.path)).lexically_normal().string();
    for (const JournalEntry& e : entries)
      if (e.target == real) throw Error(f.path + ": named twice in one step (through a link?); nothing written");
    entries.push_back({real, temporaryPathFor(real)});
  }
  writeFileAtomically(journal_path_, journalText("staging", entries));

  // Phase 2: every file complete on the disk, or nothing (StagedFile removes its temporary).
  std::vector<StagedFile> staged;
  staged.reserve(files_.size());
  try {
    for (std::size_t i = 0; i < files_.size(); ++i)
      staged.emplace_back(files_[i].path, files_[i].contents, entries[i].temp);
    // Phase 3: decided.
    writeFileAtomically(journal_path_, journalText("committing", entries));
  } catch (...) {
    staged.clear();
    removeQuietly(journal_path_);
    throw;
  }
  // Phase 4: a failure here leaves the journal and the remaining temporary files, and the next
  // recovery completes the step.
  for (StagedFile& f : staged) f.release();
  for (const JournalEntry& e : entries)
    if (::rename(e.temp.c_str(), e.target.c_str()) != 0)
      throw Error(e.target + ": cannot write file: " + std::error_code(errno, std::generic_category()).message() +
                  " (the step is recorded in " + journal_path_ + "; the next run completes it)");
  removeQuietly(journal_path_);
}

std::optional<std::string> recoverFileTransaction(const std::string& journal_path) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(journal_path, ec))) return std::nullopt;
  const io::Json doc = io::readJsonFile(journal_path, "transaction journal");
  const io::Ctx ctx{journal_path, ""};
  io::formatVersion(doc, ctx, "transaction journals", kJournalVersion, kJournalVersion);
  io::allowKeys(doc, ctx, {"version", "state", "files"});
  const bool committing = io::enumValue(io::required(doc, "state", ctx), ctx.key("state"), kStates);
  const io::Json& files = io::required(doc, "files", ctx);
  if (!files.is_array()) ctx.key("files").fail("expected an array, got " + io::describe(files));
  std::vector<JournalEntry> entries;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const io::Ctx fctx = ctx.key("files").index(i);
    io::allowKeys(files[i], fctx, {"target", "temp"});
    JournalEntry e{io::string(io::required(files[i], "target", fctx), fctx.key("target")),
                   io::string(io::required(files[i], "temp", fctx), fctx.key("temp"))};
    if (!isTemporaryBeside(e.temp, e.target))
      fctx.fail(
          "not a step vdg wrote (the temporary file must be .vdg-XXXXXX beside its target); "
          "check the files and remove the journal by hand");
    entries.push_back(std::move(e));
  }
  std::string names;
  for (const JournalEntry& e : entries) {
    const bool present = fs::exists(fs::symlink_status(e.temp, ec));
    if (!committing) {
      if (present) removeQuietly(e.temp);
      continue;
    }
    if (present && ::rename(e.temp.c_str(), e.target.c_str()) != 0)
      throw Error(journal_path + ": cannot complete the interrupted step: " + e.target + ": " +
                  std::error_code(errno, std::generic_category()).message());
    names += (names.empty() ? "" : ", ") + e.target;
  }
  removeQuietly(journal_path);
  if (!committing) return "rolled back an interrupted step: no file had been changed";
  return "completed an interrupted step: wrote " + (names.empty() ? std::string("nothing") : names);
}

}  // namespace vdg
