// Feature-line pair files (vdg/io/line_pairs.h): the one reader of the lines JSON.
#include "vdg/io/line_pairs.h"

#include <cmath>

#include "line_pair_fields.h"

namespace vdg {
namespace io {
namespace {

// A number as JSON writes it, without a trailing ".0".
std::string shown(double v) {
  std::string s = Json(v).dump();
  if (s.size() > 2 && s.compare(s.size() - 2, 2, ".0") == 0) s.resize(s.size() - 2);
  return s;
}

Eigen::Vector2d point(const Json& j, const Ctx& ctx) {
  if (!j.is_array() || j.size() != 2) ctx.fail("expected a point [x, y], got " + describe(j));
  Eigen::Vector2d p;
  for (std::size_t i = 0; i < 2; ++i) {
    p[static_cast<Eigen::Index>(i)] = number(j[i], ctx.index(i));
    if (std::abs(p[static_cast<Eigen::Index>(i)]) > kMaxLinePairCoordinate)
      ctx.index(i).fail("expected a coordinate within +-10000000 pixels, got " + describe(j[i]));
  }
  return p;
}

}  // namespace

void linePointsFrom(const Json& j, const Ctx& ctx, Eigen::Vector2d& p, Eigen::Vector2d& q) {
  if (!j.is_array()) ctx.fail("expected an array of [x, y] points, got " + describe(j));
  if (j.size() != 2) ctx.fail("expected 2 [x, y] points, got " + std::to_string(j.size()));
  p = point(j[0], ctx.index(0));
  q = point(j[1], ctx.index(1));
}

std::vector<LinePair> linePairListFrom(const Json& lines, const Ctx& ctx) {
  if (!lines.is_array() || lines.empty())
    ctx.fail("expected a non-empty array of {\"src\", \"dst\"} line pairs, got " + describe(lines));
  std::vector<LinePair> out;
  out.reserve(lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const Ctx c = ctx.index(i);
    allowKeys(lines[i], c, {"src", "dst"});
    LinePair pair;
    linePointsFrom(required(lines[i], "src", c), c.key("src"), pair.src_p, pair.src_q);
    linePointsFrom(required(lines[i], "dst", c), c.key("dst"), pair.dst_p, pair.dst_q);
    out.push_back(pair);
  }
  return out;
}

nlohmann::ordered_json linePairListJson(const std::vector<LinePair>& pairs) {
  using OJson = nlohmann::ordered_json;
  auto pointJson = [](const Eigen::Vector2d& p) { return OJson::array({p.x(), p.y()}); };
  OJson lines = OJson::array();
  for (const LinePair& pair : pairs) {
    OJson one;
    one["src"] = OJson::array({pointJson(pair.src_p), pointJson(pair.src_q)});
    one["dst"] = OJson::array({pointJson(pair.dst_p), pointJson(pair.dst_q)});
    lines.push_back(std::move(one));
  }
  return lines;
}

LinePairsFile linePairsFrom(const Json& doc, const Ctx& top, const std::string& what) {
  formatVersion(doc, top, what, 1, kLinePairsVersion);
  allowKeys(doc, top, {"version", "a", "b", "p", "lines"});
  LinePairsFile file;
  if (doc.contains("a")) {
    file.a = number(doc.at("a"), top.key("a"));
    if (!(file.a > 0.0 && file.a <= kMaxLinePairA))
      top.key("a").fail("expected a number above 0 and at most 1000000, got " + shown(file.a));
  }
  if (doc.contains("b")) file.b = numberIn(doc.at("b"), top.key("b"), 0.0, kMaxLinePairB);
  if (doc.contains("p")) file.p = numberIn(doc.at("p"), top.key("p"), 0.0, 1.0);
  file.pairs = linePairListFrom(required(doc, "lines", top), top.key("lines"));
  return file;
}

}  // namespace io

LinePairsFile parseLinePairs(const std::string& text, const std::string& where) {
  return io::linePairsFrom(io::parseJson(text, where), io::Ctx{where, ""}, "line pair files");
}

LinePairsFile readLinePairs(const std::string& path) {
  return io::linePairsFrom(io::readJsonFile(path, "line pairs"), io::Ctx{path, ""}, "line pair files");
}

}  // namespace vdg
