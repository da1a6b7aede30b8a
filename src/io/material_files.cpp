#include "material_files.h"

#include <algorithm>
#include <filesystem>

#include "vdg/geom/error.h"
#include "vdg/io/read_file.h"

namespace vdg::io {

std::string relativePathProblem(std::string_view name) {
  if (name.empty()) return "is an empty file name";
  if (name.front() == '/') return "is an absolute path";
  if (name.find('\\') != std::string_view::npos) return "has a backslash";
  if (name.find('\0') != std::string_view::npos) return "has a NUL character";
  if (name.find(':') != std::string_view::npos) return "has a ':' (a URI scheme or a drive letter)";
  std::size_t start = 0;
  while (start <= name.size()) {
    std::size_t end = name.find('/', start);
    if (end == std::string_view::npos) end = name.size();
    if (name.substr(start, end - start) == "..") return "has a '..' component";
    start = end + 1;
  }
  return {};
}

std::string folderOf(const std::string& path) {
  const std::string parent = std::filesystem::path(path).parent_path().string();
  return parent.empty() ? std::string(".") : parent;
}

std::string inFolder(const std::string& folder, const std::string& name) {
  return folder.empty() || folder == "." ? name : (std::filesystem::path(folder) / name).string();
}

void WarningSink::warn(const std::string& line) const {
  if (options_.strict) throw Error(line);
  if (options_.warnings) options_.warnings->push_back(line);
}

TextureCache::Entry TextureCache::decode(std::string_view data, const std::string& source) {
  ImageLimits limits;
  const std::size_t left = kMaxMeshTexturePixels - std::min(kMaxMeshTexturePixels, pixels_);
  limits.max_pixels = std::min(limits.max_pixels, left);
  try {
    auto image = std::make_shared<TextureImage>(decodeImage(data, source, limits));
    image->file_bytes = std::string(data);  // kept for exports (vdg/geom/material.h)
    pixels_ += static_cast<std::size_t>(image->width) * static_cast<std::size_t>(image->height);
    return {std::move(image), {}};
  } catch (const Error& e) {
    std::string why = e.what();
    if (left < kMaxImagePixels && why.find("pixels, more than the limit") != std::string::npos)
      why += " (left of the " + std::to_string(kMaxMeshTexturePixels) + " texture pixels one mesh may have)";
    return {nullptr, why};
  }
}

std::shared_ptr<const TextureImage> TextureCache::remember(const std::string& key, Entry entry, std::string* why) {
  const auto& stored = cache_.emplace(key, std::move(entry)).first->second;
  if (why) *why = stored.why;
  return stored.image;
}

std::shared_ptr<const TextureImage> TextureCache::file(const std::string& path, std::string* why) {
  const std::string key = "file:" + path;
  if (const auto it = cache_.find(key); it != cache_.end()) return remember(key, it->second, why);
  Entry entry;
  try {
    entry = decode(readFileLimited(path, "texture", kMaxImageFileBytes), path);
  } catch (const ReadRootError&) {
    throw;  // outside the read root: refused, as the file that refers to it would be
  } catch (const Error& e) {
    entry = {nullptr, e.what()};
  }
  return remember(key, std::move(entry), why);
}

std::shared_ptr<const TextureImage> TextureCache::bytes(const std::string& key, std::string_view data,
                                                        const std::string& source, std::string* why) {
  const std::string k = "bytes:" + key;
  if (const auto it = cache_.find(k); it != cache_.end()) return remember(k, it->second, why);
  return remember(k, decode(data, source), why);
}

}  // namespace vdg::io
