// vdg view MODEL -o DIR [--serve [--port N]]
//
// Writes a self-contained folder that any static web server serves (docs/web.md): the page
// (index.html and its modules, from web/view/), the runtime web/vdg-three.js, the parts of three.js
// it imports (from web/node_modules/three), and the model as model.glb, exported by the same code as
// `vdg export`. The folder is written beside its final name and swapped in whole, so a reader never
// sees half of it; an existing folder is replaced only when vdg view wrote it (its ".vdg-view"
// file) or when it is empty. --serve then serves it on 127.0.0.1 (http_server.h) until Ctrl-C;
// without -o it serves a temporary folder that it removes at the end.
//
// The web files are found in the first of: $VDG_WEB_DIR, the installed share/vdg/web beside the
// executable's prefix, the install prefix compiled in, and the source tree's web/ compiled in.
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "cli.h"
#include "http_server.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/model.h"
#include "vdg/io/read_file.h"

namespace vdg::cli {

GltfExportInput exportInputForCli(const OpenedInput& input);  // cmd_export.cpp

namespace {

namespace fs = std::filesystem;

// The file that marks a folder as vdg view's own (and so replaceable by the next vdg view).
constexpr const char* kMarker = ".vdg-view";

struct WebFile {
  const char* source;  // relative to the web folder
  const char* target;  // relative to the output folder
};

// What the page needs besides the files of web/view/ (copied to the folder's top).
constexpr std::array<WebFile, 9> kWebFiles{{
    {"vdg-three.js", "vdg-three.js"},
    {"node_modules/three/build/three.module.js", "three/three.module.js"},
    {"node_modules/three/build/three.core.js", "three/three.core.js"},
    {"node_modules/three/LICENSE", "three/LICENSE"},  // three.js's MIT licence travels with its files
    {"node_modules/three/examples/jsm/loaders/GLTFLoader.js", "three/addons/loaders/GLTFLoader.js"},
    {"node_modules/three/examples/jsm/utils/BufferGeometryUtils.js", "three/addons/utils/BufferGeometryUtils.js"},
    {"node_modules/three/examples/jsm/utils/SkeletonUtils.js", "three/addons/utils/SkeletonUtils.js"},
    {"node_modules/three/examples/jsm/controls/OrbitControls.js", "three/addons/controls/OrbitControls.js"},
    {"node_modules/three/examples/jsm/libs/meshopt_decoder.module.js", "three/addons/libs/meshopt_decoder.module.js"},
}};

bool hasPage(const fs::path& web) {
  std::error_code ec;
  return fs::is_regular_file(web / "view" / "index.html", ec);
}

// The web folder (see the top of this file); throws vdg::Error saying what to do.
fs::path webFolder() {
  if (const char* env = std::getenv("VDG_WEB_DIR"); env && *env) {
    if (!hasPage(env))
      throw Error(std::string("VDG_WEB_DIR=") + env + ": not vdg's web folder (no view/index.html in it)");
    return env;
  }
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec && hasPage(exe.parent_path().parent_path() / "share" / "vdg" / "web"))
    return exe.parent_path().parent_path() / "share" / "vdg" / "web";
  for (const char* candidate : {VDG_WEB_INSTALL_DIR, VDG_WEB_SOURCE_DIR})
    if (hasPage(candidate)) return candidate;
  throw Error(std::string("cannot find vdg's web files (looked in share/vdg/web beside vdg, ") + VDG_WEB_INSTALL_DIR +
              " and " + VDG_WEB_SOURCE_DIR + "); set VDG_WEB_DIR to vdg's web/ folder");
}

// Every file copied into the folder, checked before anything is written.
std::vector<std::pair<fs::path, std::string>> filesToCopy(const fs::path& web) {
  std::error_code ec;
  std::vector<std::pair<fs::path, std::string>> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(web / "view", ec))
    if (entry.is_regular_file(ec) && entry.path().filename().string().front() != '.')
      files.emplace_back(entry.path(), entry.path().filename().string());
  for (const WebFile& file : kWebFiles) {
    const fs::path source = web / file.source;
    if (fs::is_regular_file(source, ec)) {
      files.emplace_back(source, file.target);
    } else if (std::string_view(file.source).starts_with("node_modules/")) {
      throw Error((web / "node_modules" / "three").string() +
                  ": three.js is missing (or incomplete); run scripts/install-deps, which installs web/'s pinned "
                  "three.js with npm");
    } else {
      throw Error(source.string() + ": the vdg runtime is missing from the web folder");
    }
  }
  return files;
}

// Refuses `dir` unless it is missing, empty, or vdg view's own.
void checkReplaceable(const fs::path& dir) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(dir, ec);
  if (!fs::exists(status)) return;
  if (!fs::is_directory(status))
    throw Error("-o " + dir.string() + ": is " + (fs::is_symlink(status) ? "a symbolic link" : "a file") +
                ", not a folder vdg view wrote; not replaced");
  if (fs::is_empty(dir, ec) || fs::exists(dir / kMarker, ec)) return;
  throw Error("-o " + dir.string() + ": is a folder vdg view did not write (no " + kMarker +
              " in it); not replaced: name a new or empty folder");
}

// Fills the fresh folder `stage`.
void fillFolder(const fs::path& stage, const OpenedInput& input,
                const std::vector<std::pair<fs::path, std::string>>& files) {
  for (const auto& [source, target] : files) {
    const fs::path out = stage / target;
    fs::create_directories(out.parent_path());
    writeFileAtomically(out.string(), readFileLimited(source.string(), "the web file", std::size_t{64} << 20));
  }
  const GltfExportReport report = writeGltfExport((stage / "model.glb").string(), exportInputForCli(input));
  if (!report.note.empty()) std::fprintf(stderr, "vdg: note: %s\n", report.note.c_str());
  writeFileAtomically((stage / kMarker).string(),
                      "This folder was written by vdg view; the next vdg view -o with its name may replace it.\n");
}

// Puts the complete folder `stage` in the place of `dir` in one step (renameat2 RENAME_EXCHANGE
// when `dir` exists, rename otherwise) and removes what was there before.
void swapIn(const fs::path& stage, const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(dir, ec))) {
    fs::rename(stage, dir);
    return;
  }
  if (::renameat2(AT_FDCWD, stage.c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE) != 0)
    throw Error("-o " + dir.string() + ": cannot replace the folder: " + std::strerror(errno));
  fs::remove_all(stage, ec);  // now the old folder
}

}  // namespace

// Writes the folder `dir` for `model`; see the top of this file.
void writeViewFolder(const std::string& model, const std::string& dir_text) {
  const fs::path web = webFolder();
  const auto files = filesToCopy(web);
  const OpenedInput input = openModel(model);
  if (!input.isModel()) throw Error(model + ": is a plain mesh; vdg view shows view-dependent models");
  fs::path dir = fs::path(dir_text).lexically_normal();
  if (dir.filename().empty()) dir = dir.parent_path();
  checkReplaceable(dir);
  const fs::path parent = dir.parent_path().empty() ? fs::path(".") : dir.parent_path();
  makeOutputFolder(parent.string());
  std::string stage_text = (parent / ".vdg-view-XXXXXX").string();
  if (!::mkdtemp(stage_text.data()))
    throw Error(parent.string() + ": cannot make a folder there: " + std::strerror(errno));
  const fs::path stage = stage_text;
  const mode_t mask = ::umask(0);  // mkdtemp makes 0700; the folder is meant for a web server
  ::umask(mask);
  ::chmod(stage_text.c_str(), 0777 & ~mask);
  try {
    fillFolder(stage, input, files);
    swapIn(stage, dir);
  } catch (...) {
    std::error_code ec;
    fs::remove_all(stage, ec);
    throw;
  }
}

void addViewCommand(CLI::App& app) {
  struct Options {
    std::string model, output;
    bool serve = false, quiet = false;
    int port = 8000;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "view", "Write a web page showing the model live in three.js (docs/web.md), and optionally serve it");
  sub->add_option("MODEL", opt->model, "Model manifest (*.vdg.json), or a glTF model vdg exported")->required();
  sub->add_option("-o,--output", opt->output,
                  "Output folder (new, empty, or one vdg view wrote; needed without --serve)");
  sub->add_flag("--serve", opt->serve, "Serve the folder on http://127.0.0.1:PORT/ until Ctrl-C");
  sub->add_option("--port", opt->port, "Port for --serve (default 8000; 0: any free port)")
      ->check(wholeNumber(0, 65535));
  sub->callback([opt, sub] {
    if (opt->output.empty() && !opt->serve) throw UsageError("give -o DIR, or --serve to serve a temporary folder");
    if (sub->count("--port") > 0 && !opt->serve) throw UsageError("--port needs --serve");
    std::string dir = opt->output, temporary;
    if (dir.empty()) {
      const char* tmp = std::getenv("TMPDIR");
      temporary = (fs::path(tmp && *tmp ? tmp : "/tmp") / "vdg-view-XXXXXX").string();
      if (!::mkdtemp(temporary.data())) throw Error(temporary + ": cannot make a temporary folder");
      dir = (fs::path(temporary) / "site").string();
    }
    writeViewFolder(opt->model, dir);
    if (!opt->quiet && !opt->output.empty())
      std::printf("wrote %s (open index.html through a web server)\n", dir.c_str());
    if (opt->serve) {
      serveFolder(dir, opt->port, [&](int port) {
        std::printf("serving %s at http://127.0.0.1:%d/ (Ctrl-C stops)\n", dir.c_str(), port);
        std::fflush(stdout);
      });
      if (!opt->quiet) std::printf("stopped serving\n");
    }
    std::error_code ec;
    if (!temporary.empty()) fs::remove_all(temporary, ec);
  });
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success but the address of --serve");
}

}  // namespace vdg::cli
