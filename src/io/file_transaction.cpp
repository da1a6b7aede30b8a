// Several files replaced as one step, with a journal for crash recovery (design in the header).
#include "vdg/io/file_transaction.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <filesystem>
#include <system_error>

#include "json_reader.h"
#include "path_facts.h"
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

// The real (canonical) path of the folder `path` is in; empty when it cannot be found.
fs::path realFolderOf(const fs::path& path) {
  std::error_code ec;
  fs::path folder = fs::weakly_canonical(fs::absolute(path, ec).parent_path(), ec);
  return ec ? fs::path() : folder;
}

// Whether `target` is one of `trusted`: the same real folder and the same name.
bool isTrusted(const std::string& target, const std::vector<std::string>& trusted) {
  const fs::path folder = realFolderOf(target);
  for (const std::string& t : trusted)
    if (fs::path(t).filename() == fs::path(target).filename() && realFolderOf(t) == folder && !folder.empty())
      return true;
  return false;
}

// Why recovery does not trust entry `e` of the journal in `journal_folder`, or "" when it does.
std::string distrust(const JournalEntry& e, const fs::path& journal_folder, const std::vector<std::string>& trusted) {
  if (!isTemporaryBeside(e.temp, e.target) || fs::path(e.target).lexically_normal() != fs::path(e.target))
    return "not a step vdg wrote (the temporary file must be .vdg-XXXXXX beside its target)";
  const fs::path folder = realFolderOf(e.target);
  if ((folder.empty() || folder != journal_folder) && !isTrusted(e.target, trusted))
    return "not a step vdg wrote here: its target " + e.target + " is outside the journal's folder";
  struct stat st {};
  if (::lstat(e.temp.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    return "not a step vdg wrote: its temporary file " + e.temp + " is not a regular file";
  return {};
}

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

void FileTransaction::write(const std::string& path, std::string contents, std::string what) {
  if (what.empty()) what = path;
  for (File& f : files_)
    if (f.path == path) {
      f.contents = std::move(contents);
      f.what = std::move(what);
      return;
    }
  files_.push_back({path, std::move(contents), std::move(what)});
}

void FileTransaction::protect(const std::string& path, std::string what) {
  protected_.emplace_back(path, std::move(what));
}

void FileTransaction::checkTargets() const {
  const fs::path journal_folder = realFolderOf(journal_path_);
  for (std::size_t i = 0; i < files_.size(); ++i) {
    const File& f = files_[i];
    for (const auto& [path, what] : protected_)
      if (isSameFile(f.path, path))
        throw Error(f.what + " would replace " + what + " (the same file); nothing written");
    for (std::size_t j = 0; j < i; ++j)
      if (isSameFile(f.path, files_[j].path))
        throw Error(f.path + ": named twice in one step (it is the same file as " + files_[j].path +
                    "); nothing written");
    const std::string real = checkedOutputPath(f.path);
    if (!detail::isPathWithin(realFolderOf(real), journal_folder))
      throw Error(f.what + ": outside the folder of " + journal_path_ +
                  " (a step writes files in that folder and the folders beneath it); nothing written");
  }
}

void FileTransaction::commit() {
  if (committed_) throw Error(journal_path_ + ": this transaction was already committed");
  committed_ = true;
  std::error_code ec;
  if (fs::exists(fs::symlink_status(journal_path_, ec)))
    throw Error(journal_path_ + ": an earlier step was interrupted and is not recovered yet; nothing written");

  checkTargets();

  // Phase 1: the temporary names, journalled before anything else is created.
  std::vector<JournalEntry> entries;
  for (const File& f : files_) {
    const std::string real = fs::absolute(checkedOutputPath(f.path)).lexically_normal().string();
    for (const JournalEntry& e : entries)
      if (e.target == real) throw Error(f.path + ": named twice in one step (through a link?); nothing written");
    entries.push_back({real, temporaryPathFor(real)});
  }
  // Until phase 3 an interrupt (SIGINT, SIGTERM) removes the journal and the temporary files.
  const int journal_token = removeOnInterrupt(journal_path_);
  try {
    writeFileAtomically(journal_path_, journalText("staging", entries));
  } catch (...) {
    keepOnInterrupt(journal_token);
    throw;
  }

  // Phase 2: every file complete on the disk, or nothing (StagedFile removes its temporary).
  std::vector<StagedFile> staged;
  staged.reserve(files_.size());
  try {
    for (std::size_t i = 0; i < files_.size(); ++i)
      staged.emplace_back(files_[i].path, files_[i].contents, entries[i].temp);
  } catch (...) {
    staged.clear();
    removeQuietly(journal_path_);
    keepOnInterrupt(journal_token);
    throw;
  }
  // Phase 3: decided. From here an interrupt leaves the journal and the temporary files: the next
  // run rolls the step back (journal still "staging") or completes it ("committing").
  keepOnInterrupt(journal_token);
  for (StagedFile& f : staged) f.release();
  try {
    writeFileAtomically(journal_path_, journalText("committing", entries));
  } catch (...) {
    for (const JournalEntry& e : entries) removeQuietly(e.temp);
    removeQuietly(journal_path_);
    throw;
  }
  // Phase 4: a failure here leaves the journal and the remaining temporary files, and the next
  // recovery completes the step.
  for (const JournalEntry& e : entries)
    if (::rename(e.temp.c_str(), e.target.c_str()) != 0)
      throw Error(e.target + ": cannot write file: " + std::error_code(errno, std::generic_category()).message() +
                  " (the step is recorded in " + journal_path_ + "; the next run completes it)");
  removeQuietly(journal_path_);
}

std::optional<std::string> recoverFileTransaction(const std::string& journal_path,
                                                  const std::vector<std::string>& also_trusted) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(journal_path, ec))) return std::nullopt;
  const io::Json doc = io::readJsonFile(journal_path, "transaction journal");
  const io::Ctx ctx{journal_path, ""};
  io::formatVersion(doc, ctx, "transaction journals", kJournalVersion, kJournalVersion);
  io::allowKeys(doc, ctx, {"version", "state", "files"});
  const bool committing = io::enumValue(io::required(doc, "state", ctx), ctx.key("state"), kStates);
  const io::Json& files = io::required(doc, "files", ctx);
  if (!files.is_array()) ctx.key("files").fail("expected an array, got " + io::describe(files));
  const fs::path journal_folder = realFolderOf(journal_path);
  std::vector<JournalEntry> entries;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const io::Ctx fctx = ctx.key("files").index(i);
    io::allowKeys(files[i], fctx, {"target", "temp"});
    JournalEntry e{io::string(io::required(files[i], "target", fctx), fctx.key("target")),
                   io::string(io::required(files[i], "temp", fctx), fctx.key("temp"))};
    if (const std::string why = distrust(e, journal_folder, also_trusted); !why.empty())
      fctx.fail(why + "; check the files and remove the journal by hand");
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
