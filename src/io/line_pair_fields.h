// The JSON of feature-line pairs (private to src/io; see vdg/io/line_pairs.h): the whole lines file
// and one "lines" array, shared by the lines files of vdg morph (morph_files.cpp) and the "lines"
// op of edit scripts (edit_script.cpp), so that both read the same shape with the same messages.
#pragma once

#include <vector>

#include "json_reader.h"
#include "vdg/io/line_pairs.h"

namespace vdg::io {

// A lines file's document at `top`; `what` names the kind of file in the version message.
LinePairsFile linePairsFrom(const Json& doc, const Ctx& top, const std::string& what);
// One non-empty "lines" array at `ctx` (its own position, e.g. "'lines'").
std::vector<LinePair> linePairListFrom(const Json& lines, const Ctx& ctx);
// [[px, py], [qx, qy]] at `ctx`.
void linePointsFrom(const Json& j, const Ctx& ctx, Eigen::Vector2d& p, Eigen::Vector2d& q);
// The JSON of a list of pairs, as linePairListFrom reads it.
nlohmann::ordered_json linePairListJson(const std::vector<LinePair>& pairs);

}  // namespace vdg::io
