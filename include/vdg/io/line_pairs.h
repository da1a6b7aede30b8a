// Feature-line pairs (Beier and Neely 92): the lines file shared by `vdg morph --lines` (a source
// and a destination image) and `vdg deform --lines` (the model's image in the key view and the
// drawing), so that one file serves both:
//   {"version": 1, "a": 1, "b": 2, "p": 0.5,
//    "lines": [{"src": [[px, py], [qx, qy]], "dst": [[px, py], [qx, qy]]}, ...]}
// Pixel coordinates (x right, y down); a, b and p optional (defaults below). Read with the
// limits of vdg/io/read_file.h and the JSON nesting limit of every vdg format; every error is one
// line naming the file and the key path ("PAIRS.json: 'lines'[2].'dst'[1][0]: expected a number").
// This reader checks the shape and the ranges; what each user refuses on top (zero-length lines,
// lines pointing in opposite directions for a morph) its own library checks.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace vdg {

inline constexpr int kLinePairsVersion = 1;
inline constexpr double kMaxLinePairCoordinate = 1e7;  // |x|, |y| of every endpoint, pixels
inline constexpr double kMaxLinePairA = 1e6;           // a in (0, kMaxLinePairA]
inline constexpr double kMaxLinePairB = 16.0;          // b in [0, kMaxLinePairB]: (length^p / a)^b stays finite

struct LinePair {
  Eigen::Vector2d src_p{0, 0}, src_q{0, 0};  // the source line, P -> Q
  Eigen::Vector2d dst_p{0, 0}, dst_q{0, 0};  // the destination line
  bool operator==(const LinePair&) const = default;
};

struct LinePairsFile {
  std::vector<LinePair> pairs;  // at least one
  double a = 1.0, b = 2.0, p = 0.5;
  bool operator==(const LinePairsFile&) const = default;
};

// Throw vdg::Error (one line, naming `where` or `path`) for bad JSON, unknown keys, a wrong version,
// no lines, or a value of the wrong kind or out of range.
LinePairsFile parseLinePairs(const std::string& text, const std::string& where);
LinePairsFile readLinePairs(const std::string& path);

}  // namespace vdg
