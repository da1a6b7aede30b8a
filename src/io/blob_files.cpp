// BLOBS.json (vdg/io/blob_files.h, docs/implicit.md).
#include "vdg/io/blob_files.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "json_reader.h"
#include "vdg/geom/text.h"
#include "vdg/io/anim_json.h"

namespace vdg {
namespace {

using io::Ctx;
using io::Json;
using morph::FieldKind;

constexpr std::pair<const char*, FieldKind> kKinds[] = {
    {"blinn", FieldKind::kBlinn}, {"blobby", FieldKind::kBlinn},        {"wyvill", FieldKind::kWyvill},
    {"soft", FieldKind::kWyvill}, {"nishimura", FieldKind::kNishimura}, {"metaball", FieldKind::kNishimura},
};

constexpr int kLastFileFrame = 999999;

// A number in [lo, hi] (the bounds of vdg/morph/implicit.h); "expected a number > 0" when lo > 0
// and the number is not.
void checkIn(double v, const Ctx& ctx, double lo, double hi) {
  if (lo > 0 && !(v > 0)) ctx.fail("expected a number > 0, got " + numberText(v));
  if (!(v >= lo && v <= hi))
    ctx.fail("expected a number in [" + numberText(lo) + ", " + numberText(hi) + "], got " + numberText(v));
}
double boundedNumber(const Json& j, const Ctx& ctx, double lo, double hi) {
  const double v = io::number(j, ctx);
  checkIn(v, ctx, lo, hi);
  return v;
}

anim::RawTrack constant(const Eigen::VectorXd& value, anim::TrackType type) {
  anim::RawTrack t;
  t.type = type;
  anim::RawKey key;
  key.value = value;
  t.keys.push_back(key);
  return t;
}

// A number (or 3 numbers) or a track of them; `dim` is 1 or 3. Key values must pass `check`.
template <typename Check>
anim::RawTrack quantity(const Json& j, const Ctx& ctx, long dim, Check check) {
  const anim::TrackType type = dim == 1 ? anim::TrackType::kScalar : anim::TrackType::kVector;
  if (!j.is_object()) {
    const Eigen::VectorXd v = dim == 1 ? Eigen::VectorXd::Constant(1, io::number(j, ctx)) : io::vector(j, ctx, 3);
    check(v, ctx);
    return constant(v, type);
  }
  anim::RawTrack t = anim::parseTrack(j.dump(), ctx.prefix());
  const char* want = dim == 1 ? "a track of numbers" : "a track of 3 numbers";
  if (t.type != type) ctx.fail(std::string("expected ") + want + ", got a " + anim::trackTypeName(t.type) + " track");
  for (std::size_t k = 0; k < t.keys.size(); ++k) {
    const Ctx kctx = ctx.key("keys").index(k).key("value");
    if (t.keys[k].value.size() != dim) kctx.fail(std::string("expected ") + (dim == 1 ? "a number" : "3 numbers"));
    check(t.keys[k].value, kctx);
  }
  return t;
}

BlobFile blobFileFrom(const Json& doc, const std::string& where) {
  const Ctx top{where, ""};
  if (!doc.is_object())
    top.fail("expected an object with 'version', 'threshold' and 'primitives', got " + io::describe(doc));
  io::allowKeys(doc, top, {"version", "threshold", "frames", "voxel", "primitives", "comment"});
  io::formatVersion(doc, top, "blob files", 1, kBlobFileVersion);
  BlobFile file;
  morph::RawBlobAnimation& anim = file.animation;
  anim.threshold = boundedNumber(io::required(doc, "threshold", top), top.key("threshold"), morph::kMinBlobValue,
                                 morph::kMaxBlobValue);
  if (doc.contains("voxel"))
    file.voxel_size = boundedNumber(doc.at("voxel"), top.key("voxel"), morph::kMinBlobValue, morph::kMaxBlobValue);

  const Json& prims = io::required(doc, "primitives", top);
  const Ctx pctx = top.key("primitives");
  if (!prims.is_array() || prims.empty())
    pctx.fail("expected a non-empty array of primitives, got " + io::describe(prims));
  if (prims.size() > morph::kMaxBlobPrimitives)
    pctx.fail("expected at most " + std::to_string(morph::kMaxBlobPrimitives) + " primitives, got " +
              std::to_string(prims.size()));
  const auto coordinates = [](const Eigen::VectorXd& v, const Ctx& c) {
    for (int k = 0; k < 3; ++k)
      checkIn(v[k], c.index(static_cast<std::size_t>(k)), -morph::kMaxBlobValue, morph::kMaxBlobValue);
  };
  const auto radius = [](const Eigen::VectorXd& v, const Ctx& c) {
    checkIn(v[0], c, morph::kMinBlobValue, morph::kMaxBlobValue);
  };
  const auto strength = [](const Eigen::VectorXd& v, const Ctx& c) {
    checkIn(v[0], c, -morph::kMaxBlobValue, morph::kMaxBlobValue);
  };
  for (std::size_t i = 0; i < prims.size(); ++i) {
    const Json& p = prims[i];
    const Ctx c = pctx.index(i);
    io::allowKeys(p, c, {"kind", "center", "radius", "strength", "blobbiness", "comment"});
    morph::RawBlobTrack t;
    t.kind = io::enumValue(io::required(p, "kind", c), c.key("kind"), kKinds);
    t.center = quantity(io::required(p, "center", c), c.key("center"), 3, coordinates);
    t.radius = quantity(io::required(p, "radius", c), c.key("radius"), 1, radius);
    t.strength = p.contains("strength") ? quantity(p.at("strength"), c.key("strength"), 1, strength)
                                        : constant(Eigen::VectorXd::Constant(1, 1.0), anim::TrackType::kScalar);
    if (p.contains("blobbiness")) {
      if (t.kind != FieldKind::kBlinn) c.key("blobbiness").fail("only a 'blinn' primitive has a blobbiness");
      t.blobbiness =
          boundedNumber(p.at("blobbiness"), c.key("blobbiness"), morph::kMinBlobbiness, morph::kMaxBlobbiness);
    }
    anim.primitives.push_back(std::move(t));
  }

  if (doc.contains("frames")) {
    const Json& f = doc.at("frames");
    const Ctx fctx = top.key("frames");
    if (!f.is_array() || f.size() != 2) fctx.fail("expected [first, last], got " + io::describe(f));
    anim.first_frame = static_cast<int>(io::integer(f[0], fctx.index(0), 0, kLastFileFrame));
    anim.last_frame = static_cast<int>(io::integer(f[1], fctx.index(1), 0, kLastFileFrame));
    if (anim.first_frame > anim.last_frame)
      fctx.fail("the first frame " + std::to_string(anim.first_frame) + " is after the last " +
                std::to_string(anim.last_frame));
    if (anim.last_frame - anim.first_frame + 1 > kMaxBlobFrames)
      fctx.fail("at most " + std::to_string(kMaxBlobFrames) + " frames, got " +
                std::to_string(anim.last_frame - anim.first_frame + 1));
  } else {
    // The whole frames the keys span, rounded outwards.
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const morph::RawBlobTrack& t : anim.primitives)
      for (const anim::RawTrack* track : {&t.center, &t.radius, &t.strength})
        if (track->keys.size() > 1)
          for (const anim::RawKey& k : track->keys) lo = std::min(lo, k.time), hi = std::max(hi, k.time);
    if (lo <= hi) {
      anim.first_frame = static_cast<int>(std::clamp(std::floor(lo), 0.0, double(kLastFileFrame)));
      anim.last_frame =
          static_cast<int>(std::clamp(std::ceil(hi), double(anim.first_frame),
                                      std::min<double>(kLastFileFrame, anim.first_frame + kMaxBlobFrames - 1)));
    }
  }
  (void)morph::BlobAnimation::build(anim, where);  // tracks that do not build (overflowing spans, ...)
  return file;
}

}  // namespace

BlobFile parseBlobFile(const std::string& text, const std::string& where) {
  return blobFileFrom(io::parseJson(text, where), where);
}

BlobFile readBlobFile(const std::string& path) { return blobFileFrom(io::readJsonFile(path, "blob"), path); }

}  // namespace vdg
