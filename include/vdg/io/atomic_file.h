// Writing a user's file so that it is never left half-written, and never replaced by accident.
//
// What a write does depends on what `path` names (symbolic links are followed first, up to 40 of
// them, to the real file they name; the links themselves are never replaced):
//   - nothing yet, or a regular file: the contents go to a temporary file ".vdg-XXXXXX" (12
//     characters, so any legal file name still works) in the real file's folder; every write is
//     checked, the file is flushed to the disk (fsync) and closed, and only then renamed over the
//     real file. A replaced file keeps its permission bits; a new one gets 0666 & ~umask. On any
//     failure (disk full, quota, file size limit, I/O error) the temporary file is removed, the
//     target is untouched and vdg::Error names the target: "out/a.png: cannot write file: No
//     space left on device".
//   - a character device (/dev/null, a terminal) or a FIFO: written directly, never replaced. A
//     FIFO with no reader is an error ("PATH: is a FIFO that no program is reading"), not a hang.
//   - a folder, a socket, a block device: refused, "PATH: is a folder, not a file".
// The temporary file is in the same folder as its target, so the rename is atomic: a reader sees
// the old contents or the new ones, never a mixture. Not thread-safe for one target.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <string_view>

namespace vdg {

// Writes `contents` to `path` as described above. Throws vdg::Error naming `path`.
void writeFileAtomically(const std::string& path, std::string_view contents);

// Calls write(stream) to collect the contents in memory, then writes them as above. Exceptions
// thrown by `write` propagate, and nothing is written.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// The file a write to `path` really changes: `path` with its symbolic links followed (a dangling
// link gives the missing file it names). Throws vdg::Error naming `path` for a loop of links.
std::string resolveOutputPath(const std::string& path);

// A fresh name ".vdg-XXXXXX" (6 random letters and digits) in the folder of `real_target`; nothing
// is created. `real_target` should come from resolveOutputPath.
std::string temporaryPathFor(const std::string& real_target);

// A file staged for an atomic replacement: its complete contents are in a temporary file beside
// the real target, flushed to the disk, and nothing has changed yet. commit() renames it over the
// target; destroying an uncommitted StagedFile removes the temporary file. Used by writeFile-
// Atomically and by FileTransaction (vdg/io/file_transaction.h), which commits several at once.
class StagedFile {
 public:
  // Writes `contents` to a new temporary file for `path`: `temp_path` when given (it must not
  // exist yet; see temporaryPathFor), else a fresh ".vdg-XXXXXX" beside the real target. Throws
  // vdg::Error naming `path` when `path` names anything but a regular file or nothing (a device, a
  // FIFO, a folder), or when a write fails (the temporary file is then removed).
  StagedFile(const std::string& path, std::string_view contents, const std::string& temp_path = {});
  StagedFile(StagedFile&& other) noexcept;
  StagedFile& operator=(StagedFile&&) = delete;
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;
  ~StagedFile();

  const std::string& path() const { return path_; }           // as the caller named it
  const std::string& target() const { return target_; }       // the real file (links followed)
  const std::string& tempPath() const { return temp_path_; }  // empty once committed

  // Renames the temporary file over the target. Throws vdg::Error naming path() on failure (the
  // temporary file is then removed). Calling it twice is a programmer error (asserted).
  void commit();
  // Forgets the temporary file without removing it (the caller renames or removes it); returns it.
  std::string release();

 private:
  std::string path_, target_, temp_path_;
};

}  // namespace vdg
