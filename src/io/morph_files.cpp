// The grid, lines and key-drawings files of `vdg morph` (vdg/io/morph_files.h, docs/morph-files.md).
#include "vdg/io/morph_files.h"

#include <algorithm>
#include <cmath>

#include "json_reader.h"
#include "line_pair_fields.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/json_text.h"
#include "vdg/io/read_file.h"

namespace vdg {
namespace {

// [x, y]: each coordinate named by its index in messages ("'dst'[3][1]: expected a number, ...").
Eigen::Vector2d point(const io::Json& j, const io::Ctx& ctx) {
  if (!j.is_array() || j.size() != 2) ctx.fail("expected a point [x, y], got " + io::describe(j));
  Eigen::Vector2d p;
  for (std::size_t i = 0; i < 2; ++i) {
    p[static_cast<Eigen::Index>(i)] = io::number(j[i], ctx.index(i));
    if (std::abs(p[static_cast<Eigen::Index>(i)]) > kMaxCoordinate)
      ctx.index(i).fail("expected a coordinate within +-10000000 pixels, got " + io::describe(j[i]));
  }
  return p;
}

// A time or frame in messages: "3", "0.5" (shortest text that reads back, as JSON writes it).
std::string shownNumber(double v) {
  std::string s = io::Json(v).dump();
  if (s.size() > 2 && s.compare(s.size() - 2, 2, ".0") == 0) s.resize(s.size() - 2);
  return s;
}

io::Json pointJson(const Eigen::Vector2d& p) { return io::Json::array({p.x(), p.y()}); }

// An array of exactly `count` points (count == 0: any number of points, at least `at_least`).
std::vector<Eigen::Vector2d> points(const io::Json& j, const io::Ctx& ctx, std::size_t count,
                                    std::size_t at_least = 0) {
  if (!j.is_array()) ctx.fail("expected an array of [x, y] points, got " + io::describe(j));
  if (count > 0 && j.size() != count)
    ctx.fail("expected " + std::to_string(count) + " [x, y] points, got " + std::to_string(j.size()));
  if (j.size() < at_least)
    ctx.fail("expected at least " + std::to_string(at_least) + " [x, y] points, got " + std::to_string(j.size()));
  std::vector<Eigen::Vector2d> out;
  out.reserve(j.size());
  for (std::size_t i = 0; i < j.size(); ++i) out.push_back(point(j[i], ctx.index(i)));
  return out;
}

io::Json pointsJson(const std::vector<Eigen::Vector2d>& ps) {
  io::Json out = io::Json::array();
  for (const auto& p : ps) out.push_back(pointJson(p));
  return out;
}

std::string finish(const io::Json& doc) { return compactScalarArrays(doc.dump(2)) + "\n"; }

// ---- grid ----------------------------------------------------------------------------------------

morph::WarpGrid gridFrom(const io::Json& j, const io::Ctx& ctx, int rows, int cols) {
  morph::WarpGrid grid;
  grid.rows = rows;
  grid.cols = cols;
  grid.points = points(j, ctx, static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols));
  morph::validateGrid(grid, ctx.prefix());
  return grid;
}

MorphGridFile gridFileFrom(const io::Json& doc, const io::Ctx& top) {
  io::formatVersion(doc, top, "morph grid files", 1, kMorphGridVersion);
  io::allowKeys(doc, top, {"version", "rows", "cols", "src", "dst", "keys"});
  MorphGridFile file;
  file.rows = static_cast<int>(io::integer(io::required(doc, "rows", top), top.key("rows"), 2, kMaxGridSide));
  file.cols = static_cast<int>(io::integer(io::required(doc, "cols", top), top.key("cols"), 2, kMaxGridSide));
  file.keyed = doc.contains("keys");
  if (file.keyed) {
    if (doc.contains("src") || doc.contains("dst"))
      top.fail("give either 'src' and 'dst' (a still grid) or 'keys' (grids at key frames), not both");
    const io::Ctx kctx = top.key("keys");
    const io::Json& keys = doc.at("keys");
    if (!keys.is_array() || keys.empty())
      kctx.fail("expected a non-empty array of {\"frame\", \"src\", \"dst\"} keys, got " + io::describe(keys));
    for (std::size_t k = 0; k < keys.size(); ++k) {
      const io::Ctx c = kctx.index(k);
      io::allowKeys(keys[k], c, {"frame", "src", "dst"});
      const double frame = io::numberIn(io::required(keys[k], "frame", c), c.key("frame"), 0.0, kMaxGridFrame);
      if (k > 0 && !(frame > file.src.back().time))
        c.key("frame").fail("expected a frame after the previous key's (" + shownNumber(file.src.back().time) +
                            "), got " + shownNumber(frame));
      file.src.push_back({frame, gridFrom(io::required(keys[k], "src", c), c.key("src"), file.rows, file.cols)});
      file.dst.push_back({frame, gridFrom(io::required(keys[k], "dst", c), c.key("dst"), file.rows, file.cols)});
    }
  } else {
    if (!doc.contains("src") && !doc.contains("dst")) top.fail("missing key 'src' and 'dst' (or 'keys')");
    file.src.push_back({0.0, gridFrom(io::required(doc, "src", top), top.key("src"), file.rows, file.cols)});
    file.dst.push_back({0.0, gridFrom(io::required(doc, "dst", top), top.key("dst"), file.rows, file.cols)});
  }
  morph::requireSameShape(file.src.front().grid, file.dst.front().grid, top.prefix());
  return file;
}

// ---- lines ---------------------------------------------------------------------------------------

MorphLinesFile linesFileFrom(const io::Json& doc, const io::Ctx& top) {
  // The shape and ranges are the shared lines file's (vdg/io/line_pairs.h, also read by vdg deform).
  const LinePairsFile pairs = io::linePairsFrom(doc, top, "morph lines files");
  const io::Ctx lctx = top.key("lines");
  MorphLinesFile file;
  file.params = {pairs.a, pairs.b, pairs.p};
  for (const LinePair& pair : pairs.pairs) {
    file.src.push_back({pair.src_p, pair.src_q});
    file.dst.push_back({pair.dst_p, pair.dst_q});
  }
  morph::validateFeatureParams(file.params, top.prefix());
  morph::validateFeatureLines(file.src, file.dst, lctx.prefix());
  // A pair whose lines point in opposite directions collapses to a point at some t in (0, 1) (the
  // interpolated line's direction is (1 - t) d_src + t d_dst): refused here, for every t at once.
  for (std::size_t i = 0; i < file.src.size(); ++i) {
    const Eigen::Vector2d d0 = file.src[i].q - file.src[i].p, d1 = file.dst[i].q - file.dst[i].p, dd = d1 - d0;
    const double t = dd.squaredNorm() > 0 ? std::clamp(-d0.dot(dd) / dd.squaredNorm(), 0.0, 1.0) : 0.0;
    if ((d0 + t * dd).norm() < morph::kMinFeatureLineLength)
      lctx.index(i).fail(
          "the source and destination lines point in opposite directions, so the line collapses to "
          "a point at t = " +
          shownNumber(t) + "; give the destination's endpoints the other way round");
  }
  return file;
}

// ---- key drawings --------------------------------------------------------------------------------

constexpr std::pair<const char*, morph::InbetweenCurve> kCurves[] = {
    {"linear", morph::InbetweenCurve::kLinear}, {"catmull-rom", morph::InbetweenCurve::kCatmullRom}};

const char* curveName(morph::InbetweenCurve c) {
  for (const auto& [name, value] : kCurves)
    if (value == c) return name;
  return "linear";
}

KeyDrawingsFile drawingsFileFrom(const io::Json& doc, const io::Ctx& top) {
  io::formatVersion(doc, top, "key-drawing files", 1, kKeyDrawingsVersion);
  io::allowKeys(doc, top, {"version", "curve", "width", "height", "keys"});
  KeyDrawingsFile file;
  if (doc.contains("curve")) file.curve = io::enumValue(doc.at("curve"), top.key("curve"), kCurves);
  if (doc.contains("width"))
    file.width = static_cast<int>(io::integer(doc.at("width"), top.key("width"), 1, kMaxDrawingSide));
  if (doc.contains("height"))
    file.height = static_cast<int>(io::integer(doc.at("height"), top.key("height"), 1, kMaxDrawingSide));
  const io::Ctx kctx = top.key("keys");
  const io::Json& keys = io::required(doc, "keys", top);
  if (!keys.is_array() || keys.empty())
    kctx.fail("expected a non-empty array of {\"time\", \"strokes\"} keys, got " + io::describe(keys));
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const io::Ctx c = kctx.index(k);
    io::allowKeys(keys[k], c, {"time", "strokes"});
    morph::KeyDrawing key;
    key.time = io::numberIn(io::required(keys[k], "time", c), c.key("time"), -kMaxGridFrame, kMaxGridFrame);
    if (k > 0 && !(key.time > file.keys.back().time))
      c.key("time").fail("expected a time after the previous key's (" + shownNumber(file.keys.back().time) + "), got " +
                         shownNumber(key.time));
    const io::Ctx sctx = c.key("strokes");
    const io::Json& strokes = io::required(keys[k], "strokes", c);
    if (!strokes.is_array() || strokes.empty())
      sctx.fail("expected a non-empty array of strokes (each an array of [x, y] points), got " + io::describe(strokes));
    if (k > 0 && strokes.size() != file.keys.front().strokes.size())
      sctx.fail("expected as many strokes as keys[0] has (" + std::to_string(file.keys.front().strokes.size()) +
                "), got " + std::to_string(strokes.size()));
    for (std::size_t s = 0; s < strokes.size(); ++s) key.strokes.push_back(points(strokes[s], sctx.index(s), 0, 2));
    file.keys.push_back(std::move(key));
  }
  // The inbetweener's own checks (and its arc-length resampling) must accept the keys.
  io::withContext(kctx, [&] {
    const morph::Inbetweener check(file.keys, file.curve);
    return check.keys().size();
  });
  return file;
}

template <typename F>
auto parseWith(const std::string& text, const std::string& where, F f) {
  return f(io::parseJson(text, where), io::Ctx{where, ""});
}

}  // namespace

morph::WarpGrid MorphGridFile::srcAt(double frame) const {
  return keyed ? morph::gridAtTime(src, frame) : src.front().grid;
}
morph::WarpGrid MorphGridFile::dstAt(double frame) const {
  return keyed ? morph::gridAtTime(dst, frame) : dst.front().grid;
}

namespace {
bool sameGrid(const morph::WarpGrid& a, const morph::WarpGrid& b) {
  return a.rows == b.rows && a.cols == b.cols && a.points == b.points;
}
bool sameKeys(const std::vector<morph::GridKey>& a, const std::vector<morph::GridKey>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].time != b[i].time || !sameGrid(a[i].grid, b[i].grid)) return false;
  return true;
}
bool sameLines(const std::vector<morph::FeatureLine>& a, const std::vector<morph::FeatureLine>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].p != b[i].p || a[i].q != b[i].q) return false;
  return true;
}
}  // namespace

bool MorphGridFile::operator==(const MorphGridFile& o) const {
  return rows == o.rows && cols == o.cols && keyed == o.keyed && sameKeys(src, o.src) && sameKeys(dst, o.dst);
}
bool MorphLinesFile::operator==(const MorphLinesFile& o) const {
  return sameLines(src, o.src) && sameLines(dst, o.dst) && params.a == o.params.a && params.b == o.params.b &&
         params.p == o.params.p;
}
bool KeyDrawingsFile::operator==(const KeyDrawingsFile& o) const {
  if (curve != o.curve || width != o.width || height != o.height || keys.size() != o.keys.size()) return false;
  for (std::size_t k = 0; k < keys.size(); ++k)
    if (keys[k].time != o.keys[k].time || keys[k].strokes != o.keys[k].strokes) return false;
  return true;
}

MorphGridFile parseMorphGrid(const std::string& text, const std::string& where) {
  return parseWith(text, where, gridFileFrom);
}
MorphLinesFile parseMorphLines(const std::string& text, const std::string& where) {
  return parseWith(text, where, linesFileFrom);
}
KeyDrawingsFile parseKeyDrawings(const std::string& text, const std::string& where) {
  return parseWith(text, where, drawingsFileFrom);
}
MorphGridFile readMorphGrid(const std::string& path) {
  return gridFileFrom(io::readJsonFile(path, "morph grid"), io::Ctx{path, ""});
}
MorphLinesFile readMorphLines(const std::string& path) {
  return linesFileFrom(io::readJsonFile(path, "morph lines"), io::Ctx{path, ""});
}
KeyDrawingsFile readKeyDrawings(const std::string& path) {
  return drawingsFileFrom(io::readJsonFile(path, "key drawings"), io::Ctx{path, ""});
}

std::string formatMorphGrid(const MorphGridFile& file) {
  io::Json doc = {{"version", kMorphGridVersion}, {"rows", file.rows}, {"cols", file.cols}};
  if (file.keyed) {
    io::Json keys = io::Json::array();
    for (std::size_t k = 0; k < file.src.size(); ++k)
      keys.push_back({{"frame", file.src[k].time},
                      {"src", pointsJson(file.src[k].grid.points)},
                      {"dst", pointsJson(file.dst[k].grid.points)}});
    doc["keys"] = std::move(keys);
  } else {
    doc["src"] = pointsJson(file.src.front().grid.points);
    doc["dst"] = pointsJson(file.dst.front().grid.points);
  }
  return finish(doc);
}

std::string formatMorphLines(const MorphLinesFile& file) {
  io::Json lines = io::Json::array();
  for (std::size_t i = 0; i < file.src.size(); ++i)
    lines.push_back({{"src", io::Json::array({pointJson(file.src[i].p), pointJson(file.src[i].q)})},
                     {"dst", io::Json::array({pointJson(file.dst[i].p), pointJson(file.dst[i].q)})}});
  const io::Json doc = {{"version", kMorphLinesVersion},
                        {"a", file.params.a},
                        {"b", file.params.b},
                        {"p", file.params.p},
                        {"lines", std::move(lines)}};
  return finish(doc);
}

std::string formatKeyDrawings(const KeyDrawingsFile& file) {
  io::Json keys = io::Json::array();
  for (const morph::KeyDrawing& key : file.keys) {
    io::Json strokes = io::Json::array();
    for (const morph::Polyline& s : key.strokes) strokes.push_back(pointsJson(s));
    keys.push_back({{"time", key.time}, {"strokes", std::move(strokes)}});
  }
  const io::Json doc = {{"version", kKeyDrawingsVersion},
                        {"curve", curveName(file.curve)},
                        {"width", file.width},
                        {"height", file.height},
                        {"keys", std::move(keys)}};
  return finish(doc);
}

void writeMorphGrid(const std::string& path, const MorphGridFile& file) {
  writeFileAtomically(path, formatMorphGrid(file));
}
void writeMorphLines(const std::string& path, const MorphLinesFile& file) {
  writeFileAtomically(path, formatMorphLines(file));
}
void writeKeyDrawings(const std::string& path, const KeyDrawingsFile& file) {
  writeFileAtomically(path, formatKeyDrawings(file));
}

}  // namespace vdg
