#include "vdg/io/point_pairs.h"

#include "json_reader.h"
#include "vdg/io/read_file.h"

namespace vdg {
namespace {

std::vector<PointPair> pairsFrom(const io::Json& doc, const io::Ctx& top, std::size_t vertex_count) {
  const io::Json* pairs = &doc;
  io::Ctx ctx = top;
  if (doc.is_object()) {
    io::allowKeys(doc, top, {"pairs"});
    pairs = &io::required(doc, "pairs", top);
    ctx = top.key("pairs");
  }
  if (!pairs->is_array()) ctx.fail("expected an array of pairs, got " + io::describe(*pairs));
  std::vector<PointPair> out;
  for (std::size_t i = 0; i < pairs->size(); ++i) {
    const io::Json& p = (*pairs)[i];
    const io::Ctx pctx = ctx.index(i);
    io::allowKeys(p, pctx, {"vertex", "point", "pixel"});
    if (p.contains("vertex") == p.contains("point")) pctx.fail("give exactly one of 'vertex' or 'point'");
    PointPair pair;
    if (p.contains("vertex")) {
      if (vertex_count == 0) pctx.key("vertex").fail("the mesh has no vertices");
      pair.vertex = io::integer(p.at("vertex"), pctx.key("vertex"), 0, static_cast<std::int64_t>(vertex_count) - 1);
    } else {
      pair.point = io::vector3(p.at("point"), pctx.key("point"));
    }
    const Eigen::VectorXd pixel = io::vector(io::required(p, "pixel", pctx), pctx.key("pixel"), 2);
    pair.pixel = {pixel[0], pixel[1]};
    out.push_back(pair);
  }
  return out;
}

}  // namespace

std::vector<PointPair> parsePointPairs(const std::string& text, const std::string& where, std::size_t vertex_count) {
  return pairsFrom(io::parseJson(text, where), io::Ctx{where, ""}, vertex_count);
}

std::vector<PointPair> readPointPairs(const std::string& path, std::size_t vertex_count) {
  return pairsFrom(io::readJsonFile(path, "point pairs"), io::Ctx{path, ""}, vertex_count);
}

}  // namespace vdg
