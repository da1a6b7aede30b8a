// vdg sample SPEC.json (--at T1,T2,... | --samples N) [--csv | -o PLOT.svg]
// Evaluates an ease function, a curve (optionally reparameterised by arc length), a track or a
// camera path described in JSON (docs/anim.md) and prints a table, CSV, or draws an SVG plot.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/io/anim_json.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/manifest.h"
#include "vdg/io/read_file.h"

namespace vdg::cli {
namespace {

constexpr long kMaxCurveSamples = 1000000;

struct Sampled {
  std::vector<std::string> header;  // parameter name, then the components
  std::vector<double> params;
  std::vector<std::vector<double>> rows;  // components per parameter
};

std::vector<double> parseList(const std::string& text) {
  std::vector<double> out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t comma = std::min(text.find(',', pos), text.size());
    std::string item = text.substr(pos, comma - pos);
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    double v = 0;
    auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), v);
    if (item.empty() || ec != std::errc() || end != item.data() + item.size() || !std::isfinite(v)) {
      throw UsageError("--at: expected finite numbers separated by commas, got " + quotedText(text));
    }
    out.push_back(v);
    pos = comma + 1;
  }
  return out;
}

// anim::loadAnimSpec, except that a model manifest (static or animated) given by mistake is named
// as one rather than refused for its "version" or its fields.
anim::AnimSpec loadSpec(const std::string& path) {
  const std::string text = readFileLimited(path, "animation spec", kMaxJsonFileBytes);
  try {
    return anim::parseAnimSpec(text, path);
  } catch (const Error&) {
    bool is_model = false;
    try {
      (void)parseManifest(text, path);
      is_model = true;
    } catch (const Error&) {
    }
    if (is_model)
      throw Error(path +
                  ": a model manifest, not an animation spec; vdg sample samples eases, curves, tracks and camera "
                  "paths (docs/anim.md); a model is evaluated by vdg eval (--frame F for an animated one) or vdg "
                  "render");
    throw;
  }
}

// The evaluation calls below get spans of the right size and finite parameters (parseList and
// the sample grid), so a refusal is a bug of ours.
void checkEvaluated(bool ok, double param) {
  if (!ok) throw Error("sample: evaluation refused the parameter " + std::to_string(param) + " (internal error)");
}

std::vector<std::string> componentNames(int dim, const char* const* names3) {
  std::vector<std::string> n;
  for (int d = 0; d < dim; ++d) n.push_back(dim <= 3 ? names3[d] : "p" + std::to_string(d));
  return n;
}

Sampled sample(const anim::AnimSpec& spec, const std::vector<double>& at, int samples) {
  using anim::AnimSpec;
  static const char* const kXyz[] = {"x", "y", "z"};
  Sampled out;
  double lo = 0.0, hi = 1.0;
  std::function<std::vector<double>(double)> eval;
  std::shared_ptr<void> keep;  // keeps the built object alive for `eval`
  switch (spec.kind) {
    case AnimSpec::Kind::kEase: {
      out.header = {"t", "value"};
      const anim::Ease e = spec.ease;
      eval = [e](double t) { return std::vector<double>{e(t)}; };
      break;
    }
    case AnimSpec::Kind::kCurve: {
      auto curve = std::make_shared<anim::Curve>(anim::Curve::build(spec.curve));
      out.header = componentNames(curve->dimension(), kXyz);
      if (spec.arc_length) {
        auto a = std::make_shared<anim::ArcLengthCurve>(anim::ArcLengthCurve::build(*curve, *spec.arc_length));
        out.header.insert(out.header.begin(), "s");
        eval = [a](double f) {
          std::vector<double> v(a->curve().dimension());
          checkEvaluated(a->evaluateAtFraction(f, v), f);
          return v;
        };
        keep = a;
      } else {
        out.header.insert(out.header.begin(), "t");
        lo = curve->startTime();
        hi = curve->endTime();
        eval = [curve](double t) {
          std::vector<double> v(curve->dimension());
          checkEvaluated(curve->evaluate(t, v), t);
          return v;
        };
        keep = curve;
      }
      break;
    }
    case AnimSpec::Kind::kTrack: {
      auto track = std::make_shared<anim::Track>(anim::Track::build(spec.track));
      static const char* const kWxyz[] = {"w", "x", "y", "z"};
      if (track->type() == anim::TrackType::kRotation) {
        out.header = {kWxyz, kWxyz + 4};
      } else if (track->type() == anim::TrackType::kScalar) {
        out.header = {"value"};
      } else {
        out.header = componentNames(track->dimension(), kXyz);
      }
      out.header.insert(out.header.begin(), "t");
      lo = track->startTime();
      hi = track->endTime();
      eval = [track](double t) {
        std::vector<double> v(track->dimension());
        checkEvaluated(track->evaluate(t, v), t);
        return v;
      };
      keep = track;
      break;
    }
    case AnimSpec::Kind::kCameraPath: {
      auto path = std::make_shared<anim::CameraPath>(anim::CameraPath::build(spec.camera_path));
      out.header = {"t", "eye_x", "eye_y", "eye_z", "target_x", "target_y", "target_z", "up_x", "up_y", "up_z"};
      lo = path->startTime();
      hi = path->endTime();
      eval = [path](double t) {
        Camera c;
        checkEvaluated(path->evaluate(t, c), t);
        return std::vector<double>{c.eye.x(),    c.eye.y(), c.eye.z(), c.target.x(), c.target.y(),
                                   c.target.z(), c.up.x(),  c.up.y(),  c.up.z()};
      };
      keep = path;
      break;
    }
  }
  if (!at.empty()) {
    out.params = at;
  } else {
    for (int i = 0; i < samples; ++i) out.params.push_back(samples == 1 ? lo : lo + (hi - lo) * i / (samples - 1));
  }
  for (double p : out.params) out.rows.push_back(eval(p));
  return out;
}

void printTable(const Sampled& s, bool csv) {
  std::ostringstream o;
  o.precision(10);
  for (std::size_t i = 0; i < s.header.size(); ++i) o << (i ? (csv ? "," : "\t") : "") << s.header[i];
  o << "\n";
  for (std::size_t r = 0; r < s.params.size(); ++r) {
    o << s.params[r];
    for (double v : s.rows[r]) o << (csv ? "," : "\t") << v;
    o << "\n";
  }
  std::cout << o.str();
}

// `text` (a file name) safe inside an SVG element: markup characters as entities, control
// characters escaped.
std::string xmlText(const std::string& text) {
  std::string out;
  for (char c : oneLineText(text)) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

// Left panel: every component against the parameter. Right panel (2+ components): the path in
// the plane of the first two components with a dot per sample, so uneven spacing shows.
void writeSvg(const std::string& path, const Sampled& s, const std::string& title) {
  constexpr double kW = 420, kH = 320, kPad = 40;
  const char* const kColours[] = {"#d62728", "#2ca02c", "#1f77b4", "#9467bd", "#ff7f0e", "#8c564b"};
  const std::size_t dims = s.rows.empty() ? 0 : s.rows[0].size();
  const bool path_panel = dims >= 2;
  auto range = [](auto values) {
    double lo = 1e300, hi = -1e300;
    for (double v : values) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!(hi > lo)) lo -= 0.5, hi += 0.5;
    return std::pair{lo, hi};
  };
  const auto [p_lo, p_hi] = range(s.params);
  std::vector<double> all;
  for (const auto& r : s.rows) all.insert(all.end(), r.begin(), r.end());
  const auto [v_lo, v_hi] = range(all);
  std::ostringstream o;
  o.precision(6);
  const double width = path_panel ? 2 * kW : kW;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << kH + 30
    << "\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  o << "<text x=\"8\" y=\"16\">" << xmlText(title) << "</text>\n";
  auto frame = [&](double x0, const std::string& xl, const std::string& yl, double xlo, double xhi, double ylo,
                   double yhi) {
    o << "<rect x=\"" << x0 + kPad << "\" y=\"" << 30 + kPad / 2 << "\" width=\"" << kW - 1.5 * kPad << "\" height=\""
      << kH - 1.5 * kPad << "\" fill=\"none\" stroke=\"#999\"/>\n";
    o << "<text x=\"" << x0 + kW / 2 << "\" y=\"" << kH + 22 << "\">" << xl << " [" << xlo << ", " << xhi
      << "]</text>\n";
    o << "<text x=\"" << x0 + 4 << "\" y=\"" << 30 + kPad / 2 - 4 << "\">" << yl << " [" << ylo << ", " << yhi
      << "]</text>\n";
  };
  auto mapX = [&](double x0, double v, double lo, double hi) {
    return x0 + kPad + (v - lo) / (hi - lo) * (kW - 1.5 * kPad);
  };
  auto mapY = [&](double v, double lo, double hi) {
    return 30 + kPad / 2 + (1 - (v - lo) / (hi - lo)) * (kH - 1.5 * kPad);
  };
  frame(0, s.header[0], "value", p_lo, p_hi, v_lo, v_hi);
  for (std::size_t d = 0; d < dims; ++d) {
    o << "<polyline fill=\"none\" stroke=\"" << kColours[d % 6] << "\" stroke-width=\"1.5\" points=\"";
    for (std::size_t r = 0; r < s.params.size(); ++r) {
      o << mapX(0, s.params[r], p_lo, p_hi) << "," << mapY(s.rows[r][d], v_lo, v_hi) << " ";
    }
    o << "\"/>\n<text x=\"" << kW - kPad << "\" y=\"" << 60 + 14 * d << "\" fill=\"" << kColours[d % 6] << "\">"
      << s.header[d + 1] << "</text>\n";
  }
  if (path_panel) {
    std::vector<double> xs, ys;
    for (const auto& r : s.rows) xs.push_back(r[0]), ys.push_back(r[1]);
    auto [x_lo, x_hi] = range(xs);
    auto [y_lo, y_hi] = range(ys);
    frame(kW, s.header[1], s.header[2], x_lo, x_hi, y_lo, y_hi);
    o << "<polyline fill=\"none\" stroke=\"#333\" points=\"";
    for (std::size_t r = 0; r < xs.size(); ++r)
      o << mapX(kW, xs[r], x_lo, x_hi) << "," << mapY(ys[r], y_lo, y_hi) << " ";
    o << "\"/>\n";
    for (std::size_t r = 0; r < xs.size(); ++r) {
      o << "<circle cx=\"" << mapX(kW, xs[r], x_lo, x_hi) << "\" cy=\"" << mapY(ys[r], y_lo, y_hi)
        << "\" r=\"2\" fill=\"#1f77b4\"/>\n";
    }
  }
  o << "</svg>\n";
  const std::string text = o.str();
  writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace

void addSampleCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("sample",
                                 "Evaluate an ease function, curve, track or camera path from a JSON spec "
                                 "(see docs/anim.md) and print or plot the samples.");
  struct Options {
    std::string spec, at, svg;
    int samples = 0;
    bool csv = false;
  };
  auto opt = std::make_shared<Options>();
  cmd->add_option("SPEC", opt->spec,
                  "JSON file: {\"ease\": ...}, {\"curve\": ...}, {\"track\": ...} or "
                  "{\"camera_path\": ...}")
      ->required();
  cmd->add_option("--at", opt->at, "Comma-separated parameter values T1,T2,... (time, or arc-length fraction)");
  cmd->add_option("--samples", opt->samples, "N evenly spaced samples over the spec's range")
      ->check(wholeNumber(1, kMaxCurveSamples));
  cmd->add_flag("--csv", opt->csv, "Print CSV: a header line, then the parameter and the value's components");
  cmd->add_option("-o,--output", opt->svg, "Write an SVG plot to this file instead of printing");
  cmd->callback([opt]() {
    if (opt->at.empty() == (opt->samples == 0)) throw UsageError("give exactly one of --at T1,T2,... or --samples N");
    if (opt->csv && !opt->svg.empty()) throw UsageError("--csv and -o exclude each other");
    const std::vector<double> at = opt->at.empty() ? std::vector<double>{} : parseList(opt->at);
    const anim::AnimSpec spec = loadSpec(opt->spec);
    const Sampled s = sample(spec, at, opt->samples);
    if (!opt->svg.empty()) {
      writeSvg(opt->svg, s, opt->spec);
    } else {
      printTable(s, opt->csv);
    }
  });
}

}  // namespace vdg::cli
