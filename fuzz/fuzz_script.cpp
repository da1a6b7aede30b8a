// libFuzzer target: animation-language script text -> runScriptText, with a small instruction
// budget and memory limit, in a scratch script folder and output folder. Every input must end in a
// Shot or a clean vdg::Error (syntax and run-time errors, sandbox refusals, the budget, the memory
// limit); see fuzz_support.h for what counts as a finding. A returned scene must build.
#include <filesystem>
#include <random>

#include "fuzz_support.h"
#include "vdg/scene/scene.h"
#include "vdg/script/script.h"

namespace {

// One scratch folder per process: scripts/ (empty: vdg.load and io.open reads find nothing) and
// out/ (where io.open may write).
const std::filesystem::path& scratch() {
  static const std::filesystem::path dir = [] {
    std::random_device rd;
    const auto d = std::filesystem::temp_directory_path() / ("vdg-fuzz-script-" + std::to_string(rd()));
    std::filesystem::create_directories(d / "scripts");
    std::filesystem::create_directories(d / "out");
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size > fuzz::kMaxInputBytes) return -1;
  script::ScriptOptions options;
  options.output_dir = (scratch() / "out").string();
  options.instruction_budget = 200000;
  options.memory_limit = std::size_t{32} << 20;
  options.print = [](std::string_view) {};
  fuzz::expectCleanRejection("runScriptText", [&] {
    const script::Shot shot =
        script::runScriptText(fuzz::text(data, size), "fuzz.lua", (scratch() / "scripts").string(), options);
    if (!shot.scene.nodes.empty()) (void)scene::Scene::build(shot.scene, "fuzz.lua");
  });
  return 0;
}
