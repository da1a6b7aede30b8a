// What a path names and where it lies, for the file layer's messages and sandbox checks (internal to
// vdg_io_base: read_file.cpp, atomic_file.cpp, file_transaction.cpp).
#pragma once

#include <sys/stat.h>

#include <filesystem>
#include <string>

namespace vdg::detail {

// "a folder", "a FIFO (named pipe)", ...: what a path that is not a regular file names.
inline std::string fileKindText(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Whether `inner` is `outer` or lies beneath it (both real, canonical paths; empty is never within).
inline bool isPathWithin(const std::filesystem::path& inner, const std::filesystem::path& outer) {
  if (inner.empty() || outer.empty()) return false;
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i)
    if (i == inner.end() || *i != *o) return false;
  return true;
}

}  // namespace vdg::detail
