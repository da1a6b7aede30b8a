// vdg.load, Model.save_manifest and Model.export_gltf: the io library's readers and writers, as
// the vdg tool calls them (openModel as every subcommand; the manifest and its meshes written as
// one FileTransaction, as vdg deform and vdg studio write a model's files; the glTF export of
// `vdg export`).
#include <filesystem>
#include <limits>
#include <set>

#include "binding.h"
#include "vdg/geom/error.h"
#include "vdg/geom/text.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/file_transaction.h"
#include "vdg/io/gltf_compress.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/image_file.h"
#include "vdg/io/manifest.h"
#include "vdg/io/model.h"
#include "vdg/io/obj.h"

namespace vdg::python {
namespace {

namespace fs = std::filesystem;

// The journal vdg deform and vdg studio use in a model's folder (one step at a time per folder).
constexpr const char* kJournalName = ".vdg-journal";

void checkMeshFolder(const std::string& mesh_folder) {
  const fs::path p(mesh_folder);
  bool ok = !mesh_folder.empty() && p.is_relative() && mesh_folder.find('\\') == std::string::npos &&
            mesh_folder.find(':') == std::string::npos;
  for (const fs::path& part : p) ok = ok && part != "..";
  if (!ok)
    throw py::value_error("mesh_folder: expected a relative folder inside the manifest's folder (no '..'), got '" +
                          mesh_folder + "'");
}

// A file name for a key's mesh: its name with characters other than letters, digits, '-', '_' and
// '.' replaced by '_', made unique among `used` (which holds "base" for the base mesh).
std::string meshFileStem(const std::string& name, std::set<std::string>& used) {
  std::string stem;
  for (const char c : name)
    stem += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.') ? c : '_';
  if (stem.empty() || stem.front() == '.') stem = "key" + stem;
  std::string unique = stem;
  for (int i = 2; used.count(unique); ++i) unique = stem + "_" + std::to_string(i);
  used.insert(unique);
  return unique;
}

// Makes `folder` and its missing parents; returns the ones it made, outermost first.
std::vector<fs::path> makeFolders(const fs::path& folder) {
  std::vector<fs::path> missing;
  for (fs::path p = folder; !p.empty() && !fs::exists(p); p = p.parent_path()) missing.insert(missing.begin(), p);
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw Error(folder.string() + ": cannot make the folder: " + ec.message());
  return missing;
}

// The raw model as the saved manifest describes it, its files queued in `transaction`.
RawViewDependentModel queueFiles(const Model& m, const fs::path& folder, const std::string& mesh_folder,
                                 FileTransaction& transaction) {
  RawViewDependentModel out = m.raw;
  // The base's materials: one MTL and each texture's original bytes beside the base's OBJ files.
  std::vector<std::string> textures(out.base.materials.size());
  const bool materials = !out.base.face_materials.empty() && !out.base.materials.empty();
  if (materials) {
    for (std::size_t i = 0; i < textures.size(); ++i) {
      const Material& material = out.base.materials[i];
      if (!material.texture || material.texture->file_bytes.empty()) continue;
      const bool png = imageFormatOf(material.texture->file_bytes) == ImageFormat::kPng;
      textures[i] = "base-texture-" + std::to_string(i) + (png ? ".png" : ".jpg");
      const std::string relative = mesh_folder + "/" + textures[i];
      transaction.write((folder / relative).string(), material.texture->file_bytes, relative);
    }
  }
  bool mtl_written = false;
  const auto queue = [&](const std::string& relative, const TriMesh& mesh, const std::string& header) {
    if (!materials) {
      transaction.write((folder / relative).string(), formatObj(mesh, header), relative);
      return;
    }
    ObjWithMaterials text = formatObjWithMaterials(mesh, header, "base.mtl", textures);
    transaction.write((folder / relative).string(), std::move(text.obj), relative);
    if (!mtl_written) transaction.write((folder / mesh_folder / "base.mtl").string(), std::move(text.mtl), "base.mtl");
    mtl_written = true;
  };
  const auto queueKey = [&](const std::string& relative, const TriMesh& mesh, const std::string& header) {
    transaction.write((folder / relative).string(), formatObj(mesh, header), relative);
  };
  if (out.animated()) {
    BaseAnimationSpec spec;
    spec.obj_sequence = mesh_folder + "/base_%04d.obj";
    spec.last = static_cast<int>(out.base_frames.size()) - 1;
    spec.fps = out.base_animation->fps;
    spec.loop = out.base_animation->loop;
    out.base_animation = spec;
    out.base_skin.clear();
    out.base_path.clear();
    for (std::size_t f = 0; f < out.base_frames.size(); ++f) {
      TriMesh frame = out.base;
      frame.positions = out.base_frames[f];
      queue(sequenceFileName(spec.obj_sequence, static_cast<int>(f)), frame,
            "vdg (Python): base frame " + std::to_string(f));
    }
  } else {
    out.base_path = mesh_folder + "/base.obj";
    queue(out.base_path, out.base, "vdg (Python): base");
  }
  std::set<std::string> used{"base", "base-texture"};
  for (RawKey& key : out.keys) {
    key.mesh_path = mesh_folder + "/" + meshFileStem(key.name, used) + ".obj";
    queueKey(key.mesh_path, key.mesh, "vdg (Python): key '" + key.name + "'");
  }
  // A part's mask file stays where it was: the saved manifest holds the mask itself.
  for (RawPart& part : out.parts) part.mask_path.clear();
  return out;
}

}  // namespace

Model loadModel(py::handle path) {
  const std::string p = pathArg(path, "path");
  OpenedInput input = openModel(p);
  Model m;
  m.raw = std::move(input.raw);
  m.model = input.model;
  m.animated = input.animated;
  m.source = p;
  return m;
}

void saveManifest(const Model& m, py::handle path, const std::string& mesh_folder) {
  const std::string p = pathArg(path, "path");
  if (hasExtension(p, ".obj") || hasGltfExtension(p))
    throw py::value_error("path: expected a manifest file name (*.vdg.json), got '" + p + "'");
  checkMeshFolder(mesh_folder);
  if (m.raw.offsets == OffsetSpace::kSkinned)
    throw Error(p +
                ": skinned offsets need their glTF base, which a saved manifest's OBJ sequence cannot hold; "
                "export_gltf keeps them");
  const fs::path folder = fs::path(p).parent_path().empty() ? fs::path(".") : fs::path(p).parent_path();
  if (!fs::is_directory(folder)) throw Error(p + ": the folder " + folder.string() + " does not exist");
  const FolderLock lock(folder.string());
  const std::string journal = (folder / kJournalName).string();
  recoverFileTransaction(journal);
  FileTransaction transaction(journal);
  RawViewDependentModel out = queueFiles(m, folder, mesh_folder, transaction);
  out.source = p;
  out.validate();
  transaction.write(p, formatManifest(out), "the manifest " + p);
  const std::vector<fs::path> made = makeFolders(folder / mesh_folder);
  try {
    transaction.commit();
  } catch (...) {
    std::error_code ec;
    for (auto it = made.rbegin(); it != made.rend(); ++it) fs::remove(*it, ec);  // only when left empty
    throw;
  }
}

py::list exportGltf(const Model& m, py::handle path, const std::string& compress, py::handle max_targets) {
  const std::string p = pathArg(path, "path");
  if (!hasGltfExtension(p)) throw py::value_error("path: expected a .glb or .gltf file name, got '" + p + "'");
  const std::optional<GltfCompression> compression = gltfCompressionFromName(compress);
  if (!compression) throw py::value_error("compress: expected 'none', 'quantize' or 'meshopt', got '" + compress + "'");
  std::size_t max = std::numeric_limits<std::size_t>::max();
  if (!max_targets.is_none()) {
    const long long n = integerArg(max_targets, "max_targets");
    if (n < 0) throw py::value_error("max_targets: expected a count >= 0, got " + std::to_string(n));
    max = static_cast<std::size_t>(n);
  }
  const std::string where = m.source.empty() ? std::string("model") : m.source;
  fs::path bin;
  if (hasExtension(p, ".gltf")) bin = fs::path(p).parent_path() / (fs::path(p).stem().string() + ".bin");
  // Never write over the model's own files (vdg export's rule), under any name.
  if (!m.source.empty()) {
    const fs::path folder = fs::path(m.source).parent_path();
    std::vector<std::string> inputs{m.source};
    if (!m.raw.base_path.empty()) inputs.push_back((folder / m.raw.base_path).string());
    for (const RawKey& key : m.raw.keys)
      if (!key.mesh_path.empty()) inputs.push_back((folder / key.mesh_path).string());
    for (const std::string& in : inputs)
      if (isSameFile(p, in) || (!bin.empty() && isSameFile(bin.string(), in)))
        throw Error(p + " (or its buffer) is the same file as " + in +
                    ", one of the model's own files; vdg does not "
                    "write over its input");
  }
  GltfExportInput input;
  if (m.model) {
    input = gltfExportInput(*m.model);
  } else {
    std::optional<RawRig> rig;
    if (!m.raw.base_animation->gltf.empty()) rig = readBaseRig(m.raw);
    input = gltfExportInput(*m.animated, m.raw, rig ? &*rig : nullptr);
  }
  input.compression = *compression;
  checkMaxTargets(input, max, where);
  const GltfExportReport report = writeGltfExport(p, input);
  py::list written;
  written.append(p);
  if (!bin.empty()) written.append(bin.string());
  for (const std::string& file : report.files) written.append(file);
  return written;
}

}  // namespace vdg::python
