// The files of `vdg morph` (docs/morph-files.md): versioned JSON, read with the limits of
// vdg/io/read_file.h and the JSON nesting limit of every vdg format; every error is ONE line naming
// the file and the key path, e.g. "grid.json: 'dst'[3][1]: expected a finite number".
//
//   grid file (two-pass mesh warp, Parent 4.10):
//     {"version": 1, "rows": 3, "cols": 3, "src": [[x, y], ...], "dst": [[x, y], ...]}
//   rows * cols points each, row-major (left to right, top to bottom), pixel coordinates (x right,
//   y down). An animated morph gives the grids at key frames instead of "src"/"dst":
//     {"version": 1, "rows": 3, "cols": 3, "keys": [{"frame": 0, "src": [...], "dst": [...]}, ...]}
//   frames are output frame numbers, strictly increasing; between keys the grids are interpolated
//   with Catmull-Rom (morph::gridAtTime).
//
//   lines file (feature-based morph, Beier and Neely):
//     {"version": 1, "a": 1, "b": 2, "p": 0.5,
//      "lines": [{"src": [[px, py], [qx, qy]], "dst": [[px, py], [qx, qy]]}, ...]}
//   a, b, p optional (morph::FeatureParams's defaults). The same file as `vdg deform --lines`
//   reads: one reader (vdg/io/line_pairs.h) for both.
//
//   key-drawings file (inbetweening, Parent 4.5):
//     {"version": 1, "curve": "linear" | "catmull-rom", "width": 256, "height": 256,
//      "keys": [{"time": 0, "strokes": [[[x, y], ...], ...]}, ...]}
//   curve optional ("linear"), width/height the canvas of the written frames (optional, 512).
//
// Parsed files are checked as the morph library checks them (morph::validateGrid,
// requireSameShape, validateFeatureLines, the Inbetweener's key checks), with the file and key
// named in front of the library's message. The writers write what the readers read (a round trip
// gives equal values), atomically (vdg/io/atomic_file.h).
#pragma once

#include <string>
#include <vector>

#include "vdg/io/line_pairs.h"
#include "vdg/morph/image_morph.h"
#include "vdg/morph/inbetween.h"

namespace vdg {

inline constexpr int kMorphGridVersion = 1;
inline constexpr int kMorphLinesVersion = kLinePairsVersion;  // one file with vdg deform --lines
inline constexpr int kKeyDrawingsVersion = 1;

// Limits of what the files may ask for (each far beyond any hand-made file).
inline constexpr int kMaxGridSide = 1024;      // rows and cols each in [2, kMaxGridSide]
inline constexpr double kMaxGridFrame = 1e6;   // key frames in [0, kMaxGridFrame]
inline constexpr int kMaxDrawingSide = 16384;  // canvas width and height in [1, kMaxDrawingSide]
inline constexpr double kMaxCoordinate = 1e7;  // |x|, |y| of every point, pixels

struct MorphGridFile {
  int rows = 0, cols = 0;
  // A still grid: one key each, at frame 0 (keyed == false). An animated one: the keys in order,
  // src[k].time == dst[k].time == the key's frame.
  bool keyed = false;
  std::vector<morph::GridKey> src{}, dst{};

  // The grids at output frame `frame` (the only ones for a still grid; gridAtTime for keys).
  morph::WarpGrid srcAt(double frame) const;
  morph::WarpGrid dstAt(double frame) const;
  bool operator==(const MorphGridFile&) const;
};

struct MorphLinesFile {
  std::vector<morph::FeatureLine> src{}, dst{};  // pair i: src[i] and dst[i]
  morph::FeatureParams params{};
  bool operator==(const MorphLinesFile&) const;
};

struct KeyDrawingsFile {
  morph::InbetweenCurve curve = morph::InbetweenCurve::kLinear;
  int width = 512, height = 512;          // canvas of the frames, pixels
  std::vector<morph::KeyDrawing> keys{};  // as given (not resampled)
  bool operator==(const KeyDrawingsFile&) const;
};

// Parsers: `where` names the text in messages. Throw vdg::Error (one line) for bad JSON, unknown
// keys, a wrong version, a value of the wrong kind or out of range, or what the morph library's
// checks refuse.
MorphGridFile parseMorphGrid(const std::string& text, const std::string& where);
MorphLinesFile parseMorphLines(const std::string& text, const std::string& where);
KeyDrawingsFile parseKeyDrawings(const std::string& text, const std::string& where);
MorphGridFile readMorphGrid(const std::string& path);
MorphLinesFile readMorphLines(const std::string& path);
KeyDrawingsFile readKeyDrawings(const std::string& path);

// Writers: the JSON text the parsers read back to equal values (numbers printed to round-trip).
std::string formatMorphGrid(const MorphGridFile& file);
std::string formatMorphLines(const MorphLinesFile& file);
std::string formatKeyDrawings(const KeyDrawingsFile& file);
void writeMorphGrid(const std::string& path, const MorphGridFile& file);
void writeMorphLines(const std::string& path, const MorphLinesFile& file);
void writeKeyDrawings(const std::string& path, const KeyDrawingsFile& file);

}  // namespace vdg
