// Private to vdg_io: what the OBJ and glTF readers share for the files a mesh refers to (material
// libraries, textures, glTF buffers): the path policy, the warning sink of MeshReadOptions, and a
// texture cache with a budget per mesh read.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <string_view>

#include "vdg/geom/material.h"
#include "vdg/io/image_file.h"
#include "vdg/io/mesh_read_options.h"

namespace vdg::io {

// Why `name` may not be opened on a mesh file's behalf, or empty when it may: a file name relative
// to the referring file's folder, without a ".." component, a backslash, a ':' (a URI scheme or a
// drive letter) or a NUL character, and not absolute.
std::string relativePathProblem(std::string_view name);

// The folder of `path` ("." when it has none).
std::string folderOf(const std::string& path);
// `name` inside `folder` ("." gives `name` itself, so that messages show the name as written).
std::string inFolder(const std::string& folder, const std::string& name);

// MeshReadOptions' warnings: appended, or thrown as vdg::Error when strict.
class WarningSink {
 public:
  explicit WarningSink(const MeshReadOptions& options) : options_(options) {}
  void warn(const std::string& line) const;
  bool materials() const { return options_.materials; }

 private:
  const MeshReadOptions& options_;
};

// All texture pixels one mesh read may decode together: 2^28 (1 GiB of RGBA8), so that many small
// files claiming large images cannot exhaust memory.
inline constexpr std::size_t kMaxMeshTexturePixels = std::size_t{1} << 28;

// Decoded textures of one mesh read, each file decoded once; a failure is remembered too.
class TextureCache {
 public:
  // The texture in file `path` (already checked by the path policy), or null with `*why` set to
  // one line naming the file and the reason.
  std::shared_ptr<const TextureImage> file(const std::string& path, std::string* why);
  // The same for bytes held in memory (a glTF bufferView or data: URI); `key` identifies them in
  // the cache, `source` names them in messages.
  std::shared_ptr<const TextureImage> bytes(const std::string& key, std::string_view data, const std::string& source,
                                            std::string* why);

 private:
  struct Entry {
    std::shared_ptr<const TextureImage> image;
    std::string why;
  };
  std::shared_ptr<const TextureImage> remember(const std::string& key, Entry entry, std::string* why);
  Entry decode(std::string_view data, const std::string& source);

  std::map<std::string, Entry> cache_;
  std::size_t pixels_ = 0;
};

}  // namespace vdg::io
