// Writing a user's file so that it is never left half-written, and never replaced by accident.
//
// What a write does depends on what `path` names (symbolic links are followed first, up to 40 of
// them, to the real file they name; the links themselves are never replaced):
//   - nothing yet, or a regular file: the contents go to a temporary file beside the real file
//     (".vdg-RRRRRR-PID-TAG", below); every write is checked, the file is flushed to the disk
//     (fsync) and closed, and only then renamed over the real file. A replaced file keeps its
//     permission bits; a new one gets 0666 & ~umask. On any failure (disk full, quota, file size
//     limit, I/O error) the temporary file is removed, the target is untouched and vdg::Error names
//     the target: "out/a.png: cannot write file: No space left on device".
//   - a character device (/dev/null, a terminal) or a FIFO: written directly, never replaced. A
//     FIFO with no reader is an error ("PATH: is a FIFO that no program is reading"), not a hang;
//     a reader that goes away while vdg writes (vdg sample ... | head -1) throws ReaderClosed.
//   - a folder, a socket, a block device: refused, "PATH: is a folder, not a file".
// A symbolic link is followed only to a file in the link's own folder or a folder beneath it; a
// link that leaves it (out/frame_0001.png -> ../../victim.png, planted in an output folder) is
// refused: "PATH: is a symbolic link to a file outside its folder (TARGET); not written through".
// The temporary file is in the same folder as its target, so the rename is atomic: a reader sees
// the old contents or the new ones, never a mixture. Not thread-safe for one target.
//
// Temporary files and interrupted runs. A temporary file is named ".vdg-RRRRRR-PID-TAG": 6 random
// letters or digits, the writer's process id, and 12 hexadecimal digits identifying this boot of
// this host, its process-id namespace and the user. While it is written its name is registered, so
// that SIGINT, SIGTERM or SIGHUP (installOutputSignalHandlers) removes it before the run ends. A
// run killed outright (SIGKILL, a power cut) cannot; the next write into that folder removes the
// temporary files it can prove are such leftovers: its own TAG, a PID no longer running, a regular
// file of this user, and no ".vdg-journal" in the folder (a FileTransaction's files wait for its
// recovery). Nothing else is ever removed.
#pragma once

#include <sys/types.h>

#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <system_error>

#include "vdg/geom/error.h"

namespace vdg {

// Thrown when the reader of a pipe or FIFO vdg writes to has gone (EPIPE): the output is no longer
// wanted, so the vdg tool ends quietly with exit status 0.
struct ReaderClosed : Error {
  using Error::Error;
};

// Writes `contents` to `path` as described above. Throws vdg::Error naming `path`.
void writeFileAtomically(const std::string& path, std::string_view contents);

// Calls write(stream) to collect the contents in memory, then writes them as above. Exceptions
// thrown by `write` propagate, and nothing is written.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// The file a write to `path` really changes: `path` with its symbolic links followed (a dangling
// link gives the missing file it names). Throws vdg::Error naming `path` for a loop of links.
std::string resolveOutputPath(const std::string& path);

// The file a write to `path` really changes, as resolveOutputPath, and refused (vdg::Error naming
// `path`) when `path` is a symbolic link to a file outside the link's folder and the folders
// beneath it. Every writer here goes through it.
std::string checkedOutputPath(const std::string& path);

// A fresh name ".vdg-XXXXXX" (6 random letters and digits) in the folder of `real_target`; nothing
// is created. `real_target` should come from resolveOutputPath. FileTransaction names its files so
// (its journal, not the process id, tells what becomes of them after a crash).
std::string temporaryPathFor(const std::string& real_target);

// Whether `a` and `b` name one file: the same device and inode, symbolic links followed (so a hard
// link or a symbolic link to a file is that file). False when either does not exist.
bool isSameFile(const std::string& a, const std::string& b);

// ---- What a failed run leaves -----------------------------------------------------------------
// A run that fails or is interrupted leaves nothing new behind: the files it created (renamed into
// place where no file was; a replaced file cannot be given back and stays replaced) and the
// folders makeOutputFolder made are removed again by removeNewOutputs, which the vdg tool calls
// when a run fails, and the interrupt handler (below). A created file is removed only while it is
// still the one written (the same device and inode); a folder only when it is empty.

// Makes `folder` and its missing parents (as mkdir -p) and remembers the ones it made. Throws
// vdg::Error "FOLDER: cannot make the folder: REASON" (or "FOLDER: is a file, not a folder").
void makeOutputFolder(const std::string& folder);
// The same without throwing, as std::filesystem::create_directories(folder, ec): true when it made
// `folder`; `ec` set on failure (std::errc::not_a_directory when a file is in the way).
bool makeOutputFolder(const std::string& folder, std::error_code& ec);
// Removes the files and then the folders this run made, as described above.
void removeNewOutputs();
// From now on the files this run created are kept even if it fails (frames left for the user when
// a video cannot be encoded); folders it made and left empty still go.
void keepNewOutputs();

// ---- Signals ---------------------------------------------------------------------------------
// For the vdg tool's main(), before anything is written:
//   - SIGPIPE and SIGXFSZ are ignored: a write to a closed pipe fails with EPIPE (ReaderClosed),
//     one past the file size limit (ulimit -f) with EFBIG, reported and cleaned up as a full disk;
//   - SIGINT, SIGTERM and SIGHUP end the run: the temporary files being written are removed (and
//     a FileTransaction's journal whose step was not decided yet), then what removeNewOutputs
//     removes, one line on stderr, "vdg: interrupted (SIGINT); the
//     files being written were removed", and exit status 128 + the signal (130, 143, 129). SIGHUP
//     stays ignored when it was ignored at the start (nohup); SIGINT and SIGTERM are always caught.
void installOutputSignalHandlers();

// A file to remove if the run is interrupted (see above) until keepOnInterrupt(token); the path
// is made absolute. At most 64 files at a time are remembered (more are not; the token is then -1).
int removeOnInterrupt(const std::string& path);
void keepOnInterrupt(int token);  // -1 is ignored
// A child process group (an encoder such as ffmpeg, started in a group of its own, so that the
// terminal's Ctrl-C does not reach it) that an interrupt kills before removing the files; 0 forgets
// it. One group at a time.
void killOnInterrupt(pid_t group);

// A file staged for an atomic replacement: its complete contents are in a temporary file beside
// the real target, flushed to the disk, and nothing has changed yet. commit() renames it over the
// target; destroying an uncommitted StagedFile removes the temporary file. Used by writeFile-
// Atomically and by FileTransaction (vdg/io/file_transaction.h), which commits several at once.
class StagedFile {
 public:
  // Writes `contents` to a new temporary file for `path`: `temp_path` when given (it must not
  // exist yet; see temporaryPathFor), else a fresh ".vdg-RRRRRR-PID-TAG" beside the real target
  // (after removing the proven leftovers of killed runs there, see above). Throws
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
  void forget();  // the temporary file is no longer this object's (unregisters it)
  std::string path_, target_, temp_path_;
  int interrupt_token_ = -1;
  dev_t device_ = 0;  // the identity of the temporary file (and of the target once committed)
  ino_t inode_ = 0;
};

}  // namespace vdg
