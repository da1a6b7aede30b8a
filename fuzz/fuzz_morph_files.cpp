// libFuzzer target: the three files of vdg morph (vdg/io/morph_files.h). The first byte chooses the
// parser (mod 3: 0 grid files, parseMorphGrid; 1 lines files, parseMorphLines; 2 key-drawing files,
// parseKeyDrawings), the rest is the text. An accepted file must survive the round trip through its
// writer (format -> parse gives equal values), and goes one step further: its grids or lines warp
// a small image, its key drawings are inbetweened at a few times. See fuzz_support.h for what
// counts as a finding.
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "vdg/io/morph_files.h"

namespace {

// Writing an accepted file and reading it back must not throw.
template <typename F>
auto mustWrite(const char* what, F f) {
  try {
    return f();
  } catch (const vdg::Error& e) {
    std::fprintf(stderr, "FINDING: %s: an accepted file does not write or read back: %s\n", what, e.what());
    std::abort();
  }
}

// An 8 x 8 test image, the size of the morphs' work kept small whatever the file's coordinates.
vdg::morph::Image smallImage() {
  vdg::morph::Image image{8, 8, std::vector<float>(8 * 8 * 4)};
  for (std::size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = static_cast<float>(i % 7) / 6.0f;
  return image;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size < 1 || size > fuzz::kMaxInputBytes) return -1;
  const std::string text = fuzz::text(data + 1, size - 1);
  switch (data[0] % 3) {
    case 0:
      fuzz::expectCleanRejection("parseMorphGrid", [&] {
        const MorphGridFile grid = parseMorphGrid(text, "GRID.json");
        const MorphGridFile again =
            mustWrite("morph grid", [&] { return parseMorphGrid(formatMorphGrid(grid), "round trip"); });
        fuzz::require(again == grid, "a grid file changed in the round trip through formatMorphGrid");
        const double last = grid.src.back().time;
        for (const double frame : {0.0, last / 2, last, last + 1}) {
          const morph::WarpGrid from = grid.srcAt(frame), to = grid.dstAt(frame);
          fuzz::require(from.points.size() == static_cast<std::size_t>(grid.rows * grid.cols), "a grid lost points");
          (void)morph::meshWarp(smallImage(), from, to);
        }
      });
      break;
    case 1:
      fuzz::expectCleanRejection("parseMorphLines", [&] {
        const MorphLinesFile lines = parseMorphLines(text, "LINES.json");
        const MorphLinesFile again =
            mustWrite("morph lines", [&] { return parseMorphLines(formatMorphLines(lines), "round trip"); });
        fuzz::require(again == lines, "a lines file changed in the round trip through formatMorphLines");
        (void)morph::featureMorph(smallImage(), smallImage(), lines.src, lines.dst, 0.5, lines.params);
      });
      break;
    default:
      fuzz::expectCleanRejection("parseKeyDrawings", [&] {
        const KeyDrawingsFile drawings = parseKeyDrawings(text, "KEYS.json");
        const KeyDrawingsFile again =
            mustWrite("key drawings", [&] { return parseKeyDrawings(formatKeyDrawings(drawings), "round trip"); });
        fuzz::require(again == drawings, "a key-drawing file changed in the round trip through formatKeyDrawings");
        const morph::Inbetweener inbetweener(drawings.keys, drawings.curve);
        const double t0 = drawings.keys.front().time, t1 = drawings.keys.back().time;
        for (const double t : {t0 - 1, t0, (t0 + t1) / 2, t1}) {
          const std::vector<morph::Polyline> strokes = inbetweener.at(t);
          fuzz::require(strokes.size() == drawings.keys.front().strokes.size(), "an inbetween lost strokes");
        }
      });
      break;
  }
  return 0;
}
