// libFuzzer target: the feature-line pairs file shared by `vdg morph --lines` and `vdg deform
// --lines` (vdg/io/line_pairs.h, parseLinePairs). An accepted file becomes a "lines" edit op (the
// settings vdg deform gives it); when the op's own checks accept it (checkFeatureLines), it must
// survive the edit-op JSON round trip (editOpToJson -> parseEditOp gives the same pairs and
// settings) and warp a small grid seen by a parallel camera to finite positions. See
// fuzz_support.h for what counts as a finding.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "vdg/deform/edits.h"
#include "vdg/deform/feature_lines.h"
#include "vdg/io/edit_script.h"
#include "vdg/io/line_pairs.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size > fuzz::kMaxInputBytes) return -1;
  const std::string text = fuzz::text(data, size);
  fuzz::expectCleanRejection("parseLinePairs", [&] {
    const LinePairsFile file = parseLinePairs(text, "PAIRS.json");
    fuzz::require(!file.pairs.empty(), "an accepted lines file has no pairs");
    LinesOp op;
    op.settings = {file.a, file.b, file.p, FeatureLineSettings{}.falloff_px};
    for (const LinePair& pair : file.pairs) op.pairs.push_back({pair.src_p, pair.src_q, pair.dst_p, pair.dst_q});
    if (checkFeatureLines(op.pairs, op.settings)) return;  // e.g. a line of no length: refused by the op
    const EditOp back = parseEditOp(editOpToJson(op), "round trip");
    fuzz::require(editKind(back) == EditKind::kLines, "a lines op came back as another op");
    fuzz::require(std::get<LinesOp>(back).pairs == op.pairs && std::get<LinesOp>(back).settings == op.settings,
                  "a lines op changed in the round trip through editOpToJson");
    // A 5 x 5 grid in [-1, 1]^2 seen by a 64 x 64 parallel camera.
    std::vector<float> positions;
    std::vector<std::int32_t> triangles;
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) positions.insert(positions.end(), {0.5f * i - 1.0f, 0.5f * j - 1.0f, 0.0f});
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const int a = 5 * j + i;
        triangles.insert(triangles.end(), {a, a + 1, a + 6, a, a + 6, a + 5});
      }
    Camera camera;
    camera.ortho_height = 2.5;
    const std::vector<EditOp> ops{op};
    // A warp far beyond the image may overflow float: applyEdits reports that as vdg::Error.
    applyEdits(camera, triangles, positions, ops, std::array<int, 2>{64, 64}, "fuzz");
    for (float x : positions) fuzz::require(std::isfinite(x), "the warp left a non-finite position");
  });
  return 0;
}
