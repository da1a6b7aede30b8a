#include "vdg/io/atomic_file.h"

#include <unistd.h>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "vdg/geom/error.h"

namespace vdg {
namespace {

std::string temporaryPathFor(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path target(path);
  const std::string name = "." + target.filename().string() + ".tmp." + std::to_string(::getpid()) + "." +
                           std::to_string(counter.fetch_add(1));
  return (target.parent_path() / name).string();
}

void commit(const std::string& temp, const std::string& path) {
  std::error_code ec;
  std::filesystem::rename(temp, path, ec);
  if (ec) {
    std::filesystem::remove(temp, ec);
    throw Error(path + ": cannot write file: " + ec.message());
  }
}

}  // namespace

void writeFileAtomicallyVia(const std::string& path, const std::function<void(const std::string&)>& write) {
  const std::string temp = temporaryPathFor(path);
  try {
    write(temp);
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(temp, ec);
    throw;
  }
  commit(temp, path);
}

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  writeFileAtomicallyVia(path, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(path + ": cannot write file (is the folder there and writable?)");
    write(out);
    out.flush();
    if (!out) throw Error(path + ": write failed (disk full?)");
  });
}

}  // namespace vdg
