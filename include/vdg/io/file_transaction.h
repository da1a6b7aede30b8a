// Replacing several files as one step: after commit() all of them are replaced, after a failure
// none is, and after a crash in between (power cut, kill -9) the next run either completes the
// step or rolls it back. `vdg deform` writes a key mesh, its edit log and the manifest this way.
//
// Design. Every file is written as in vdg/io/atomic_file.h: a complete temporary file beside its
// real target (symbolic links followed), renamed over it. What makes several files one step is a
// journal, a small JSON file at a path the caller chooses (for `vdg deform`: ".vdg-journal" in the
// model's folder), itself always replaced atomically:
//   {"version": 1, "state": "staging" | "committing",
//    "files": [{"target": "/abs/real/path", "temp": "/abs/real/.vdg-XXXXXX"}, ...]}
// commit() runs these phases:
//   1. chooses a temporary name for every file and writes the journal in state "staging";
//   2. writes every temporary file completely, checking each write, and flushes it to the disk;
//   3. rewrites the journal in state "committing": from here on the step is decided;
//   4. renames each temporary file over its target, then removes the journal.
// A failure in phases 1-2 (disk full, a folder not writable) removes the temporary files and the
// journal and throws: nothing changed. A failure in phase 4 is rare (the temporaries are complete
// and beside their targets) and throws, leaving the journal for recovery.
// recoverFileTransaction() reads a journal left behind and, by its state, either removes the
// temporary files (staging: rolled back, the targets were never touched) or renames the ones still
// present over their targets (committing: completed; a missing temporary was renamed already).
// Recovery trusts a journal only when every target is in the journal's own folder (real paths, so
// neither ".." nor a link leads out), or is one of the files the caller names as its own (a model's
// key files in keys/), and every temporary file is a ".vdg-XXXXXX" name beside its target that is a regular
// file when present: a journal planted in an output folder cannot rename or remove anything
// elsewhere. A journal it does not trust is refused with one line and nothing is touched. Since
// recovery would refuse them, commit() refuses to write files outside the journal's folder tree.
// A write must not land on a file the step only reads: protect() names such files, and commit()
// refuses (before anything is written) when a target is one of them or another target under
// another name (a hard or symbolic link: compared by device and inode). One transaction at a time per
// journal: commit() refuses to start while a journal is present, and a caller that reads files,
// recovers and commits (`vdg deform`) holds a FolderLock on the journal's folder throughout, so
// that two processes neither interleave their steps nor recover each other's step in progress.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace vdg {

class FileTransaction {
 public:
  // `journal_path`: where the journal lives while commit() runs (its folder must exist).
  explicit FileTransaction(std::string journal_path);

  // Adds a file to write; nothing is written before commit(). The last contents given for one
  // path win. `path` must name a regular file or nothing (checked by commit()). `what` names it in
  // messages ("key 'front': its mesh front.obj"; default: the path).
  void write(const std::string& path, std::string contents, std::string what = {});
  // A file the step must not change, named in messages by `what` ("the base mesh cube.obj"). A
  // target that is this file (the same device and inode) makes commit() throw vdg::Error
  // "WHAT-OF-TARGET would replace WHAT (the same file); nothing written".
  void protect(const std::string& path, std::string what);
  bool empty() const { return files_.empty(); }

  // The checks commit() makes before writing anything (protected files, one file under two names,
  // links out of a folder, targets outside the journal's folder tree), for a caller that wants to
  // refuse before it computes the contents: write() the paths with empty contents, check(), then
  // write() them again with the contents. Throws vdg::Error as commit() would.
  void check() const { checkTargets(); }

  // Writes every file as one step (see above). Throws vdg::Error naming the file that failed, or
  // the journal when one is already present. A transaction commits once.
  void commit();

 private:
  struct File {
    std::string path, contents, what;
  };
  void checkTargets() const;
  std::string journal_path_;
  std::vector<File> files_;
  std::vector<std::pair<std::string, std::string>> protected_;  // path, what
  bool committed_ = false;
};

// An exclusive advisory lock (flock) on a folder, held while the object lives. Throws vdg::Error
// "FOLDER: another vdg is changing files here; try again when it has finished" when another
// holder has it (it does not wait), or naming the folder when it cannot be opened.
class FolderLock {
 public:
  explicit FolderLock(const std::string& folder);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

// Finishes an interrupted transaction whose journal is at `journal_path`. Returns nothing when
// there is no journal, else one line saying what was done: "completed an interrupted step: wrote
// A, B" or "rolled back an interrupted step: no file had been changed". Throws vdg::Error naming
// the journal when it cannot be read or trusted (then nothing is renamed or removed), or a rename
// fails. `also_trusted`: files outside the journal's folder that a step may have written (for
// `vdg deform`, the mesh, edit log and snapshot of each key of the model, wherever they are);
// compared by their real folder and name.
std::optional<std::string> recoverFileTransaction(const std::string& journal_path,
                                                  const std::vector<std::string>& also_trusted = {});

}  // namespace vdg
