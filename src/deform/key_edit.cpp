// Key authoring steps (Rademacher 99, section 3.1): new keys, edit cameras, steps, replay, undo.
#include "vdg/deform/key_edit.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>

#include "vdg/geom/error.h"
#include "vdg/geom/text.h"

namespace vdg {
namespace {

// `text` for a message: printable ASCII kept, every other byte as \xHH, cut after 80 bytes.
std::string shown(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  constexpr std::size_t kShown = 80;
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < kShown; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  if (text.size() > kShown) out += "...";
  return out;
}

// Well-formed UTF-8 (no overlong forms, no surrogates, at most U+10FFFF) without control characters.
bool isCleanUtf8(std::string_view s) {
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x20 || c == 0x7f) return false;
    if (c < 0x80) {
      ++i;
      continue;
    }
    std::size_t len = 0;
    std::uint32_t cp = 0;
    if ((c & 0xE0) == 0xC0) {
      len = 2;
      cp = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      len = 3;
      cp = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      len = 4;
      cp = c & 0x07;
    } else {
      return false;
    }
    if (i + len > s.size()) return false;
    for (std::size_t k = 1; k < len; ++k) {
      const auto cc = static_cast<unsigned char>(s[i + k]);
      if ((cc & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (cc & 0x3F);
    }
    const std::uint32_t min = len == 2 ? 0x80 : len == 3 ? 0x800 : 0x10000;
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF) || (cp >= 0x80 && cp < 0xA0)) return false;
    i += len;
  }
  return true;
}

std::string normalMeshPath(const std::string& path) {
  return std::filesystem::path(path).lexically_normal().generic_string();
}

}  // namespace

bool isValidKeyName(std::string_view name) {
  if (name.empty() || name.size() > kMaxKeyNameLength || name.front() == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u < 0x80 && (std::isalnum(u) || c == '_' || c == '-' || c == '.');
  });
}

void checkKeyName(std::string_view name) {
  if (!isValidKeyName(name))
    throw Error("key name '" + shown(name) + "': not allowed (key names are file names: use " + kKeyNameRule + ")");
}

void checkKeyMeshPath(std::string_view mesh_path) {
  const std::string at = "--mesh " + shown(mesh_path) + ": ";
  if (mesh_path.empty()) throw Error(at + "is empty");
  if (!isCleanUtf8(mesh_path)) throw Error(at + "must be valid UTF-8 without control characters");
  const std::filesystem::path p{std::string(mesh_path)};
  if (p.is_absolute() || mesh_path.front() == '/')
    throw Error(at + "must be relative to the manifest's folder, and inside it");
  const std::filesystem::path normal = p.lexically_normal();
  if (normal.empty() || *normal.begin() == ".." || normal == ".")
    throw Error(at + "must stay inside the manifest's folder (no '..' leading out of it)");
  if (!hasExtension(normal.extension().string(), ".obj") || normal.stem().empty())
    throw Error(at + "a key mesh must be an OBJ file (NAME.obj)");
}

TriMesh posedBase(const RawViewDependentModel& model, int frame) {
  const std::size_t frames = model.frameCount();
  if (frame < 0 || static_cast<std::size_t>(frame) >= frames)
    throw Error("frame " + std::to_string(frame) + " is outside the base animation's frames 0.." +
                std::to_string(frames - 1) + (model.animated() ? "" : " (the base is static)"));
  if (!model.animated()) return model.base;
  TriMesh posed = model.base;
  posed.positions = model.base_frames[static_cast<std::size_t>(frame)];
  return posed;
}

std::size_t addKey(RawViewDependentModel& model, const NewKey& key) {
  checkKeyName(key.name);
  for (const RawKey& k : model.keys)
    if (k.name == key.name) throw Error("key '" + key.name + "' already exists");
  const std::string mesh_path = key.mesh_path.empty() ? key.name + ".obj" : key.mesh_path;
  checkKeyMeshPath(mesh_path);
  for (const RawKey& k : model.keys)
    if (normalMeshPath(k.mesh_path) == normalMeshPath(mesh_path))
      throw Error("key '" + key.name + "': mesh " + mesh_path + " belongs to key '" + k.name + "'");
  if (key.camera.has_value() == key.view.has_value())
    throw Error("key '" + key.name + "' is new: give its camera or its view (one of them)");
  if (key.view && !(key.view->allFinite() && key.view->norm() > 0))
    throw Error("key '" + key.name + "': the view direction must be finite and non-zero");
  RawViewDependentModel updated = model;
  RawKey k;
  k.name = key.name;
  k.mesh_path = mesh_path;
  k.mesh = posedBase(model, key.frame);
  k.camera = key.camera;
  k.frame = key.frame;
  if (key.view) k.view = key.view->normalized();
  updated.keys.push_back(std::move(k));
  updated.resolveViews();
  updated.validate();  // a (frame, view) that another key has is refused here, naming both keys
  model = std::move(updated);
  return model.keys.size() - 1;
}

Camera keyEditCamera(const RawViewDependentModel& model, const RawKey& key) {
  if (key.camera) return *key.camera;
  const Bounds b = computeBounds(posedBase(model, key.frame).positions);
  const double size = std::max(static_cast<double>(b.diagonal()), 1e-6);
  return cameraFromView(model.resolvedCenter(), key.view, 2.0 * size, 1.1 * size);
}

EditLog startEditLog(const RawViewDependentModel& model, const RawKey& key, const std::string& snapshot_name) {
  EditLog log;
  log.key = key.name;
  log.origin = key.mesh.positions == posedBase(model, key.frame).positions ? "base" : snapshot_name;
  return log;
}

std::vector<EditReport> deformKey(RawViewDependentModel& model, std::size_t key_index, EditLog& log,
                                  std::span<const EditOp> ops, const std::optional<std::array<int, 2>>& image_size,
                                  const std::string& source) {
  if (key_index >= model.keys.size())
    throw Error("key index " + std::to_string(key_index) + " is out of range (the model has " +
                std::to_string(model.keys.size()) + " keys)");
  RawKey& key = model.keys[key_index];
  const Camera camera = keyEditCamera(model, key);
  std::vector<float> positions = key.mesh.positions;  // a copy: nothing changes unless every op succeeds
  const std::vector<EditReport> reports = applyEdits(camera, key.mesh.triangles, positions, ops, image_size, source);
  std::swap(key.mesh.positions, positions);
  try {
    model.validate();
  } catch (...) {
    std::swap(key.mesh.positions, positions);
    throw;
  }
  log.entries.push_back({camera, image_size, std::vector<EditOp>(ops.begin(), ops.end())});
  return reports;
}

std::vector<float> replayEditLog(const TriMesh& origin, const EditLog& log, const std::string& source) {
  std::vector<float> positions = origin.positions;
  for (std::size_t e = 0; e < log.entries.size(); ++e)
    applyEdits(log.entries[e].camera, origin.triangles, positions, log.entries[e].ops, log.entries[e].image_size,
               source + ": 'entries'[" + std::to_string(e) + "]");
  return positions;
}

std::vector<float> undoLastStep(const TriMesh& origin, EditLog& log, const std::string& source) {
  if (log.entries.empty()) throw Error(source + ": nothing to undo (the edit log has no step)");
  EditLog shorter = log;
  shorter.entries.pop_back();
  std::vector<float> positions = replayEditLog(origin, shorter, source);
  log = std::move(shorter);
  return positions;
}

}  // namespace vdg
