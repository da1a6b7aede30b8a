// vdg morph SRC DST (--grid FILE | --lines FILE) (--t T -o OUT.png | --count N -o DIR) [--frames A-B] [--warp]
//   SRC and DST: an image each, or a folder of frames (an animated sequence: output frame i morphs
//   frame i of each; Parent 4.10, "morphing two animated sequences").
// vdg morph --drawings KEYS.json --count N -o DIR [--frames A-B] [--format svg|png]
//
// 2D metamorphosis (Parent 4.10): the two-pass mesh warp over the user's curvilinear grids, or the
// feature-based morph of Beier and Neely over pairs of feature lines; both warp the source and the
// destination onto the features interpolated with t and cross-dissolve them (--warp: only the
// source, warped, no dissolve). A key-framed grid file animates the grids over the output frames
// (Catmull-Rom between keys), as the features of two animated sequences move. --drawings
// inbetweens key drawings (Parent 4.5) into SVG or PNG frames. The mathematics lives in the morph
// library (vdg/morph/image_morph.h, inbetween.h), the files in vdg/io/morph_files.h; this file
// reads, checks, calls and writes (PNG atomically).
// See docs/morph.md and docs/morph-files.md.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/image_file.h"
#include "vdg/io/morph_files.h"
#include "vdg/morph/budget.h"
#include "vdg/morph/image_morph.h"
#include "vdg/morph/inbetween.h"
#include "vdg/render/image.h"
#include "video.h"

namespace vdg::cli {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxMorphFrames = 100000;
constexpr double kStrokeWidth = 2.0;  // pixels, the drawn inbetweens' line width

struct MorphOptions {
  std::string src, dst, grid, lines, drawings, output, video, format = "svg";
  double t = 0.0, frame = 0.0, budget = morph::kDefaultBudget;
  int frames = 0;            // --count N (the old `--frames N` too, with a deprecation note)
  std::string frames_range;  // --frames A-B: write only these frames of the N
  FrameRange range;          // parsed from frames_range; last < first: every frame
  bool t_given = false, frame_given = false, format_given = false, warp = false, quiet = false;
};

// --frames: a range A-B of the --count N frames, or (the old spelling) the count itself.
void parseFrames(MorphOptions& opt, bool count_given) {
  if (opt.frames_range.empty()) return;
  if (isPlainCount(opt.frames_range) && !count_given) {
    noteDeprecated("--frames N", "--count N");
    const auto n = parseNumberIn(opt.frames_range, {1, End::kClosed, kMaxMorphFrames, End::kClosed, true});
    if (!n)
      throw UsageError("--frames: expected a count in [1, " + std::to_string(kMaxMorphFrames) + "], got " +
                       quotedText(opt.frames_range));
    opt.frames = static_cast<int>(*n);
    return;
  }
  opt.range = parseFrameRange(opt.frames_range, "--frames");
  if (opt.frames == 0) throw UsageError("--frames A-B: needs --count N (the frames are a share of N)");
  if (opt.range.last >= opt.frames)
    throw UsageError("--frames: expected frames within 0-" + std::to_string(opt.frames - 1) + " (--count " +
                     std::to_string(opt.frames) + "), got " + quotedText(opt.frames_range));
}

bool isFolder(const std::string& path) {
  std::error_code ec;
  return !path.empty() && fs::is_directory(path, ec);
}

// The usage rules that need several options together (exit status 2).
void checkUsage(const MorphOptions& opt) {
  if (opt.format != "svg" && opt.format != "png")
    throw UsageError("--format: expected 'svg' or 'png', got " + quotedText(opt.format));
  const bool drawings = !opt.drawings.empty();
  if (drawings) {
    if (!opt.src.empty() || !opt.dst.empty()) throw UsageError("--drawings takes no SRC or DST images");
    if (!opt.grid.empty() || !opt.lines.empty()) throw UsageError("--drawings takes no --grid or --lines");
    if (opt.warp) throw UsageError("--warp: only for image morphs (SRC DST with --grid or --lines)");
    if (opt.t_given || opt.frame_given) throw UsageError("--drawings: give --count N (frames span the keys' times)");
    if (opt.frames == 0) throw UsageError("--drawings: give --count N");
  } else {
    if (opt.dst.empty()) throw UsageError("give SRC and DST images (or --drawings KEYS.json)");
    if (opt.grid.empty() == opt.lines.empty()) throw UsageError("give exactly one of --grid FILE or --lines FILE");
    if (opt.t_given == (opt.frames > 0))
      throw UsageError("give exactly one of --t T (one image) or --count N (a sequence)");
    if (opt.format_given) throw UsageError("--format: only for --drawings (image morphs write PNG)");
    if (opt.frame_given && opt.grid.empty() && !isFolder(opt.src) && !isFolder(opt.dst))
      throw UsageError("--frame: only with a key-framed --grid file or a sequence (a folder of frames)");
    if (opt.frame_given && !opt.t_given)
      throw UsageError("--frame: only with --t (with --count N, frame i is output frame i)");
  }
  if (!opt.video.empty()) {
    if (opt.frames == 0) throw UsageError("--video: needs --count N");
    if (opt.range.last >= opt.range.first) throw UsageError("--video: needs every frame (leave out --frames A-B)");
    if (!isVideoPath(opt.video))
      throw UsageError("--video: expected a file name ending in .mp4 or .gif, got " + quotedText(opt.video));
    if (drawings && opt.format != "png") throw UsageError("--video: needs --format png for --drawings");
    requireFfmpeg("--video " + opt.video, "leave out --video (the frames go to -o DIR)");
  }
}

// The frames to write: --frames A-B of the --count N, or all of them.
int firstFrame(const MorphOptions& opt) { return opt.range.last >= opt.range.first ? opt.range.first : 0; }
int lastFrame(const MorphOptions& opt) { return opt.range.last >= opt.range.first ? opt.range.last : opt.frames - 1; }

render::Image toRenderImage(const morph::Image& image) {
  const TextureImage bytes = morph::imageToRgba8(image);
  return {bytes.width, bytes.height, bytes.rgba};
}

// The folder of --count output; fails with one line when it cannot be made.
void makeFolder(const std::string& dir) {
  std::error_code ec;
  makeOutputFolder(dir, ec);  // removed again when the run fails
  if (ec || !fs::is_directory(dir)) throw Error("-o " + dir + ": cannot create the folder");
}

std::string framePath(const std::string& dir, int i, const char* ext) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.%s", i, ext);
  return (fs::path(dir) / name).string();
}

// ---- image morphs --------------------------------------------------------------------------------

// SRC or DST: one image (a still, used for every output frame) or an animated sequence, a folder
// whose PNG and JPEG files, in name order, are its frames 0, 1, ... (zero-padded names, as every vdg
// command writes them, sort in frame order). A sequence's frames are read one at a time, as the
// output frames need them.
class ImageSource {
 public:
  ImageSource(const std::string& path, const char* role) : path_(path), role_(role) {
    if (!isFolder(path)) {
      still_ = morph::imageFromRgba8(readImageFile(path, "image"));
      return;
    }
    std::error_code ec;
    for (fs::directory_iterator it(path, ec), end; !ec && it != end; it.increment(ec)) {
      std::string ext = it->path().extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
      if ((ext == ".png" || ext == ".jpg" || ext == ".jpeg") && it->is_regular_file(ec))
        frames_.push_back(it->path().string());
    }
    if (ec) throw Error(path + ": cannot list the folder (" + role_ + " sequence): " + ec.message());
    if (frames_.empty()) throw Error(path + ": the folder holds no PNG or JPEG frames (" + role_ + " sequence)");
    std::sort(frames_.begin(), frames_.end());
  }

  bool sequence() const { return !frames_.empty(); }
  int frameCount() const { return static_cast<int>(frames_.size()); }
  const std::string& path() const { return path_; }

  // Output frame `frame`'s image: the still, or the sequence's frame of that number.
  morph::Image at(int frame) const {
    if (!sequence()) return still_;
    return morph::imageFromRgba8(readImageFile(frames_[static_cast<std::size_t>(frame)], "image"));
  }
  // The file output frame `frame` reads (for messages).
  const std::string& fileAt(int frame) const { return sequence() ? frames_[static_cast<std::size_t>(frame)] : path_; }

  // Refuses (one line) a sequence too short for output frames up to `last`.
  void requireFrames(int last, const std::string& why) const {
    if (sequence() && last >= frameCount())
      throw Error(path_ + ": the " + role_ + " sequence has " + std::to_string(frameCount()) + " frames; " + why +
                  " needs frame " + std::to_string(last) + " (output frame i morphs frame i of each sequence)");
  }

 private:
  std::string path_, role_;
  morph::Image still_;
  std::vector<std::string> frames_;
};

// What one output image needs: both images and the correspondence.
class ImageMorph {
 public:
  explicit ImageMorph(const MorphOptions& opt) : opt_(opt), src_(opt.src, "source"), dst_(opt.dst, "destination") {
    if (!opt.grid.empty())
      grid_ = readMorphGrid(opt.grid);
    else
      lines_ = readMorphLines(opt.lines);
    if (opt.t_given && !opt.grid.empty() && grid_.keyed && !opt.frame_given)
      throw UsageError("--t with a key-framed grid (" + opt.grid +
                       ") needs --frame F, the output frame whose grids to use");
    if (opt.t_given && !opt.grid.empty() && !grid_.keyed && opt.frame_given && !sequences())
      throw UsageError("--frame: " + opt.grid + " is a still grid, not a key-framed one");
    const morph::Image first_src = src_.at(0), first_dst = dst_.at(0);
    requireSameSize(first_src, src_.fileAt(0), first_dst, dst_.fileAt(0));
    width_ = first_src.width;
    height_ = first_src.height;
  }

  int width() const { return width_; }
  int height() const { return height_; }
  bool sequences() const { return src_.sequence() || dst_.sequence(); }
  // Refuses a sequence too short for the output frames up to `last`.
  void requireFrames(int last, const std::string& why) const {
    src_.requireFrames(last, why);
    dst_.requireFrames(last, why);
  }

  // Refuses, before any pixel is computed, a morph whose estimated work (vdg/morph/budget.h) is
  // past --budget: every written frame costs a warp or two of every pixel, by every feature line
  // (O(pixels x lines)) or along the grid's curves.
  void checkCost(int frames) const {
    const int w = width_, h = height_;
    const int images = opt_.warp ? 1 : 2;
    const double each = !opt_.grid.empty() ? (opt_.warp ? morph::meshWarpCost(w, h, grid_.rows, grid_.cols)
                                                        : morph::meshMorphCost(w, h, grid_.rows, grid_.cols))
                                           : (opt_.warp ? morph::featureWarpCost(w, h, lines_.src.size())
                                                        : morph::featureMorphCost(w, h, lines_.src.size()));
    const std::string by = !opt_.grid.empty()
                               ? "a " + std::to_string(grid_.rows) + "x" + std::to_string(grid_.cols) + " grid"
                               : std::to_string(lines_.src.size()) + " lines";
    morph::checkBudget(each * frames, opt_.budget, opt_.grid.empty() ? opt_.lines : opt_.grid,
                       std::to_string(w) + "x" + std::to_string(h) + " pixels x " + by + " x " +
                           std::to_string(images) + (images == 1 ? " image" : " images") + " x " +
                           std::to_string(frames) + (frames == 1 ? " frame" : " frames"),
                       "give --budget N to allow more, or fewer " +
                           std::string(opt_.grid.empty() ? "lines" : "grid points") + ", pixels or frames");
  }

  // The image at morph time t; `frame` picks a key-framed grid's grids and each sequence's frame.
  // What the morph library refuses (a line collapsing at this t) is reported under the features'
  // file.
  morph::Image at(double t, double frame) const {
    const int index = static_cast<int>(frame);  // a whole number whenever a sequence is given
    const morph::Image src = src_.at(index);
    const morph::Image dst = opt_.warp ? morph::Image{} : dst_.at(index);
    requireSameSize(src, src_.fileAt(index), opt_.warp ? src : dst, dst_.fileAt(index));
    try {
      return compute(t, frame, src, dst);
    } catch (const Error& e) {
      throw Error((opt_.grid.empty() ? opt_.lines : opt_.grid) + ": " + e.what());
    }
  }

 private:
  morph::Image compute(double t, double frame, const morph::Image& src, const morph::Image& dst) const {
    if (!opt_.grid.empty()) {
      const morph::WarpGrid from = grid_.srcAt(frame), to = grid_.dstAt(frame);
      if (opt_.warp) return morph::meshWarp(src, from, morph::interpolateGrids(from, to, t));
      return morph::meshMorph(src, dst, from, to, t);
    }
    if (opt_.warp) {
      std::vector<morph::FeatureLine> to(lines_.src.size());
      for (std::size_t i = 0; i < to.size(); ++i)
        to[i] = {(1 - t) * lines_.src[i].p + t * lines_.dst[i].p, (1 - t) * lines_.src[i].q + t * lines_.dst[i].q};
      return morph::featureWarp(src, lines_.src, to, lines_.params);
    }
    return morph::featureMorph(src, dst, lines_.src, lines_.dst, t, lines_.params);
  }

  // Every image the morph reads has the first source frame's size.
  void requireSameSize(const morph::Image& src, const std::string& src_file, const morph::Image& dst,
                       const std::string& dst_file) const {
    const auto size = [](const morph::Image& image) {
      return std::to_string(image.width) + "x" + std::to_string(image.height);
    };
    if (src.width != dst.width || src.height != dst.height)
      throw Error(dst_file + ": is " + size(dst) + " pixels and " + src_file + " is " + size(src) +
                  "; the two images must have the same size");
    if (width_ > 0 && (src.width != width_ || src.height != height_))
      throw Error(src_file + ": is " + size(src) + " pixels and " + src_.fileAt(0) + " is " + std::to_string(width_) +
                  "x" + std::to_string(height_) + "; every frame of a sequence must have the same size");
  }

  const MorphOptions& opt_;
  MorphGridFile grid_;
  MorphLinesFile lines_;
  ImageSource src_, dst_;
  int width_ = 0, height_ = 0;
};

void runImageMorph(const MorphOptions& opt) {
  const ImageMorph morph(opt);
  if (opt.t_given && morph.sequences()) {
    if (!opt.frame_given || opt.frame != std::floor(opt.frame))
      throw UsageError(
          "--t with a sequence (a folder of frames) needs --frame F, the whole number of the frame to morph");
    morph.requireFrames(static_cast<int>(opt.frame), "--frame " + std::to_string(static_cast<int>(opt.frame)));
  }
  if (!opt.t_given) morph.requireFrames(lastFrame(opt), "--count " + std::to_string(opt.frames));
  morph.checkCost(opt.t_given ? 1 : lastFrame(opt) - firstFrame(opt) + 1);
  if (opt.t_given) {
    const morph::Image image = morph.at(opt.t, opt.frame);
    render::writePng(opt.output, toRenderImage(image));
    if (!opt.quiet)
      std::printf("wrote %s (%dx%d, t = %g%s)\n", opt.output.c_str(), image.width, image.height, opt.t,
                  opt.warp ? ", source warped only" : "");
    return;
  }
  makeFolder(opt.output);
  Progress progress("morph", opt.frames, opt.quiet);
  for (int i = firstFrame(opt); i <= lastFrame(opt); ++i) {
    const double t = static_cast<double>(i) / (opt.frames - 1);
    render::writePng(framePath(opt.output, i, "png"), toRenderImage(morph.at(t, i)));
    progress.step(i + 1);
  }
  progress.finish();
  if (!opt.video.empty()) encodeVideo("--video " + opt.video, opt.video, {opt.output, 0, opt.frames});
  if (!opt.quiet)
    std::printf("wrote %d frames (%dx%d) to %s%s\n", lastFrame(opt) - firstFrame(opt) + 1, morph.width(),
                morph.height(), opt.output.c_str(), opt.video.empty() ? "" : (" and " + opt.video).c_str());
}

// ---- inbetweened drawings ------------------------------------------------------------------------

std::string svgOf(const std::vector<morph::Polyline>& strokes, int width, int height) {
  std::ostringstream out;
  out.precision(9);
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << " " << height << "\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  for (const morph::Polyline& s : strokes) {
    out << "<polyline fill=\"none\" stroke=\"black\" stroke-width=\"" << kStrokeWidth
        << "\" stroke-linejoin=\"round\" stroke-linecap=\"round\" points=\"";
    for (std::size_t i = 0; i < s.size(); ++i) out << (i ? " " : "") << s[i].x() << "," << s[i].y();
    out << "\"/>\n";
  }
  out << "</svg>\n";
  return out.str();
}

// Black strokes kStrokeWidth wide on white, anti-aliased by each pixel centre's distance to the
// nearest segment (coverage falls from 1 to 0 over one pixel at the stroke's edge).
render::Image pngOf(const std::vector<morph::Polyline>& strokes, int width, int height) {
  std::vector<float> cover(static_cast<std::size_t>(width) * height, 0.0f);
  const double half = kStrokeWidth / 2;
  for (const morph::Polyline& s : strokes)
    for (std::size_t i = 0; i + 1 < s.size(); ++i) {
      const Eigen::Vector2d a = s[i], b = s[i + 1], ab = b - a;
      const double len2 = ab.squaredNorm();
      const int x0 = std::max(0, static_cast<int>(std::floor(std::min(a.x(), b.x()) - half - 1)));
      const int x1 = std::min(width - 1, static_cast<int>(std::ceil(std::max(a.x(), b.x()) + half + 1)));
      const int y0 = std::max(0, static_cast<int>(std::floor(std::min(a.y(), b.y()) - half - 1)));
      const int y1 = std::min(height - 1, static_cast<int>(std::ceil(std::max(a.y(), b.y()) + half + 1)));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const Eigen::Vector2d p(x + 0.5, y + 0.5);
          const double u = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
          const double d = (p - (a + u * ab)).norm();
          float& c = cover[static_cast<std::size_t>(y) * width + x];
          c = std::max(c, static_cast<float>(std::clamp(half + 0.5 - d, 0.0, 1.0)));
        }
    }
  render::Image image{width, height, std::vector<std::uint8_t>(cover.size() * 4)};
  for (std::size_t i = 0; i < cover.size(); ++i) {
    const auto v = static_cast<std::uint8_t>(std::lround(255.0 * (1.0 - cover[i])));
    image.rgba[4 * i] = image.rgba[4 * i + 1] = image.rgba[4 * i + 2] = v;
    image.rgba[4 * i + 3] = 255;
  }
  return image;
}

void runDrawings(const MorphOptions& opt) {
  const KeyDrawingsFile file = readKeyDrawings(opt.drawings);
  const morph::Inbetweener inbetweener(file.keys, file.curve);
  const double t0 = file.keys.front().time, t1 = file.keys.back().time;
  const bool png = opt.format == "png";
  // Every frame evaluates every point; a PNG frame also fills its canvas and each segment's box.
  const int count = lastFrame(opt) - firstFrame(opt) + 1;
  const double each = morph::inbetweenFrameCost(inbetweener.keys(), png ? file.width : 0, png ? file.height : 0);
  morph::checkBudget(
      each * count, opt.budget, opt.drawings,
      std::to_string(count) + (count == 1 ? " frame" : " frames") + " of " + morph::operationsText(each) +
          (png ? " (a " + std::to_string(file.width) + "x" + std::to_string(file.height) + " canvas)" : std::string()),
      "give --budget N to allow more, or fewer frames, points or a smaller canvas");
  makeFolder(opt.output);
  Progress progress("inbetween", opt.frames, opt.quiet);
  for (int i = firstFrame(opt); i <= lastFrame(opt); ++i) {
    const double time = opt.frames == 1 ? t0 : t0 + (t1 - t0) * i / (opt.frames - 1);
    const std::vector<morph::Polyline> strokes = inbetweener.at(time);
    if (png)
      render::writePng(framePath(opt.output, i, "png"), pngOf(strokes, file.width, file.height));
    else
      writeFileAtomically(framePath(opt.output, i, "svg"), svgOf(strokes, file.width, file.height));
    progress.step(i + 1);
  }
  progress.finish();
  if (!opt.video.empty()) encodeVideo("--video " + opt.video, opt.video, {opt.output, 0, opt.frames});
  if (!opt.quiet)
    std::printf("wrote %d %s frames (%dx%d) to %s%s\n", lastFrame(opt) - firstFrame(opt) + 1, png ? "PNG" : "SVG",
                file.width, file.height, opt.output.c_str(), opt.video.empty() ? "" : (" and " + opt.video).c_str());
}

}  // namespace

void addMorphCommand(CLI::App& app) {
  auto opt = std::make_shared<MorphOptions>();
  CLI::App* sub = app.add_subcommand(
      "morph",
      "Morph one image into another (two-pass mesh warp over grids, or feature lines), or inbetween key drawings");
  sub->add_option("SRC", opt->src,
                  "Source image (PNG or JPEG), or a folder of frames: an animated sequence, whose frame i output "
                  "frame i morphs");
  sub->add_option("DST", opt->dst, "Destination image or folder of frames, the same size as SRC");
  sub->add_option("--grid", opt->grid,
                  "Grid file: the source's and destination's curvilinear grids, still or at key frames "
                  "(docs/morph-files.md)");
  sub->add_option("--lines", opt->lines, "Lines file: pairs of feature lines, source and destination (Beier-Neely)");
  sub->add_option("--t", opt->t, "One image at morph time T in [0, 1] (0: SRC, 1: DST), written to -o OUT.png")
      ->check(numberIn({0.0, End::kClosed, 1.0, End::kClosed}));
  sub->add_option("--count", opt->frames,
                  "A sequence of N frames at t = i/(N-1), written to -o DIR as frame_0000.png ... (N >= 2; "
                  "with --drawings N >= 1, spanning the keys' times)")
      ->check(wholeNumber(1, kMaxMorphFrames));
  sub->add_option("--frames", opt->frames_range,
                  "Write only frames A-B (or N) of the --count N (a farm node's share); the old '--frames N' for "
                  "a count is still read as --count N in this version, with a deprecation note");
  sub->add_option("--frame", opt->frame,
                  "With --t and a key-framed grid or a sequence (required then): the output frame whose grids and "
                  "sequence frames to use")
      ->check(numberIn({0.0, End::kClosed, kMaxGridFrame, End::kClosed}));
  sub->add_option("-o,--output", opt->output, "OUT.png with --t; a folder with --frames")->required();
  sub->add_flag("--warp", opt->warp,
                "Only warp SRC onto the features interpolated with t (at t = 1 onto DST's); no cross-dissolve");
  sub->add_option("--drawings", opt->drawings,
                  "Key-drawings file: inbetween its keys into --frames N drawings instead of morphing images");
  sub->add_option("--format", opt->format, "--drawings frames as 'svg' (default) or 'png'");
  sub->add_option("--video", opt->video, "Also encode the PNG frames as OUT.mp4 or OUT.gif (needs ffmpeg)");
  sub->add_option("--budget", opt->budget,
                  "Refuse, before starting, work estimated above N operations (default 2e9: seconds to about a "
                  "minute; feature lines cost pixels x lines x 2 per frame; docs/morph.md, 'Budgets')")
      ->check(positiveNumber(morph::kMaxBudget));
  sub->add_flag("-q,--quiet", opt->quiet, "No progress bar and no summary line");
  sub->callback([opt, sub] {
    opt->t_given = sub->count("--t") > 0;
    opt->frame_given = sub->count("--frame") > 0;
    opt->format_given = sub->count("--format") > 0;
    parseFrames(*opt, sub->count("--count") > 0);
    checkUsage(*opt);
    if (!opt->drawings.empty()) {
      runDrawings(*opt);
    } else {
      if (opt->frames == 1) throw UsageError("--count: an image morph needs N >= 2 (frame 0 is SRC, frame N-1 DST)");
      runImageMorph(*opt);
    }
  });
}

}  // namespace vdg::cli
