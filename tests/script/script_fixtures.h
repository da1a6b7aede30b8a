// Running script text in a scratch folder for the script tests.
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/scene/scene.h"
#include "vdg/script/script.h"

namespace vdg::testing {

// A scratch folder with scripts/ (the script folder) and out/ (the output folder).
struct ScriptBench {
  TempDir dir;
  std::string scripts = dir.file("scripts");
  std::string out = dir.file("out");
  std::vector<std::string> printed;
  std::string read_root;  // ScriptOptions::read_root (empty: the script folder)
  std::int64_t write_limit = script::ScriptOptions{}.write_limit;

  ScriptBench() {
    std::filesystem::create_directories(scripts);
    std::filesystem::create_directories(out);
  }
  script::ScriptOptions options() {
    script::ScriptOptions o;
    o.output_dir = out;
    o.read_root = read_root;
    o.write_limit = write_limit;
    o.print = [this](std::string_view line) { printed.emplace_back(line); };
    return o;
  }
  script::Shot run(const std::string& text, const std::string& name = "test.lua") {
    return script::runScriptText(text, name, scripts, options());
  }
  std::string errorOfRun(const std::string& text, const std::string& name = "test.lua") {
    return errorOf([&] { run(text, name); });
  }
  // Every path under the scratch folder outside out/ (files, folders, links).
  std::set<std::string> outsideOutput() const {
    std::set<std::string> paths;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir.path())) {
      const std::string p = e.path().string();
      if (p.rfind(out, 0) != 0) paths.insert(p);
    }
    return paths;
  }
};

// One field's value at a frame, through Scene::build.
inline std::vector<double> valueAt(const scene::Scene& s, const std::string& node, scene::Field field, double frame) {
  std::vector<double> v(static_cast<std::size_t>(scene::fieldDimension(field)));
  if (!s.fieldValue(s.findNode(node), field, frame, v)) return {};
  return v;
}

}  // namespace vdg::testing
