#include "cli.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"
#include "vdg/geom/text.h"

namespace vdg::cli {
bool findOnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::stringstream dirs(path);
  for (std::string dir; std::getline(dirs, dir, ':');) {
    std::error_code ec;
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / program;
    if (std::filesystem::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) return true;
  }
  return false;
}

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

namespace {

// A range bound as people write it: whole values without a fraction or exponent ("1000000").
std::string boundText(double v) {
  if (v == std::floor(v) && std::abs(v) < 1e15) return std::to_string(static_cast<long long>(v));
  return numberText(v);
}

}  // namespace

std::string describeRange(const NumberRange& r) {
  const std::string kind = r.whole ? "a whole number" : "a number";
  const bool lo = r.lo_end != End::kUnbounded, hi = r.hi_end != End::kUnbounded;
  if (lo && hi)
    return kind + " in " + (r.lo_end == End::kOpen ? "(" : "[") + boundText(r.lo) + ", " + boundText(r.hi) +
           (r.hi_end == End::kOpen ? ")" : "]");
  if (lo) return kind + (r.lo_end == End::kOpen ? " > " : " >= ") + boundText(r.lo);
  if (hi) return kind + (r.hi_end == End::kOpen ? " < " : " <= ") + boundText(r.hi);
  return r.whole ? kind : "a finite number";
}

std::optional<double> parseNumberIn(std::string_view text, const NumberRange& r) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty() || text.front() == '+') return std::nullopt;
  const char* const end = text.data() + text.size();
  double value = 0.0;
  if (r.whole) {
    long long whole = 0;
    const auto [next, ec] = std::from_chars(text.data(), end, whole);
    if (ec != std::errc() || next != end) return std::nullopt;
    value = static_cast<double>(whole);
  } else {
    const auto [next, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || next != end || !std::isfinite(value)) return std::nullopt;
  }
  if ((r.lo_end == End::kClosed && !(value >= r.lo)) || (r.lo_end == End::kOpen && !(value > r.lo)) ||
      (r.hi_end == End::kClosed && !(value <= r.hi)) || (r.hi_end == End::kOpen && !(value < r.hi)))
    return std::nullopt;
  return value;
}

CLI::Validator numberIn(const NumberRange& range) {
  std::string help = describeRange(range);
  help = help.substr(help.find(' ') + 1);  // "number in (0, 180)" after the type name
  return CLI::Validator(
      [range](std::string& text) -> std::string {
        if (parseNumberIn(text, range)) return {};
        return "expected " + describeRange(range) + ", got " + quotedText(text);
      },
      help);
}

CLI::Validator finiteNumber() { return numberIn({}); }

CLI::Validator positiveNumber(double hi) {
  return numberIn({0.0, End::kOpen, hi, hi > 0.0 ? End::kClosed : End::kUnbounded});
}

CLI::Validator openRange(double lo, double hi) { return numberIn({lo, End::kOpen, hi, End::kOpen}); }

CLI::Validator wholeNumber(long lo, long hi) {
  return numberIn({static_cast<double>(lo), End::kClosed, static_cast<double>(hi), End::kClosed, true});
}

namespace {

// The message of a bad image size, or empty when `text` is one; fills `size`.
std::string checkImageSize(const std::string& text, char separator, int max_side, ImageSize& size) {
  const NumberRange side{1, End::kClosed, static_cast<double>(max_side), End::kClosed, true};
  const auto sep = text.find(separator);
  std::optional<double> w, h;
  if (sep != std::string::npos) {
    w = parseNumberIn(std::string_view(text).substr(0, sep), side);
    h = parseNumberIn(std::string_view(text).substr(sep + 1), side);
  }
  if (!w || !h) {
    const std::string form = separator == 'x' ? "WIDTHxHEIGHT" : std::string("WIDTH") + separator + "HEIGHT";
    return "expected " + form + " in pixels, each side a whole number in [1, " + std::to_string(max_side) + "], got " +
           quotedText(text);
  }
  size = {static_cast<int>(*w), static_cast<int>(*h)};
  return {};
}

}  // namespace

ImageSize parseImageSize(const std::string& text, char separator, int max_side, const std::string& option) {
  ImageSize size;
  if (const std::string message = checkImageSize(text, separator, max_side, size); !message.empty())
    throw UsageError(option + ": " + message);
  return size;
}

CLI::Validator imageSize(char separator, int max_side) {
  return CLI::Validator(
      [separator, max_side](std::string& text) {
        ImageSize size;
        return checkImageSize(text, separator, max_side, size);
      },
      "sides in [1, " + std::to_string(max_side) + "]");
}

Eigen::Vector3d parseVec3(const std::string& text, const std::string& option) {
  Eigen::Vector3d v;
  const char* p = text.data();
  const char* end = text.data() + text.size();
  for (int i = 0; i < 3; ++i) {
    while (p < end && *p == ' ') ++p;
    double value = 0;
    auto [next, ec] = std::from_chars(p, end, value);
    if (ec != std::errc() || !std::isfinite(value))
      throw UsageError(option + ": expected three finite numbers X,Y,Z, got " + quotedText(text));
    v[i] = value;
    p = next;
    while (p < end && *p == ' ') ++p;
    if (i < 2) {
      if (p == end || *p != ',')
        throw UsageError(option + ": expected three finite numbers X,Y,Z, got " + quotedText(text));
      ++p;
    }
  }
  if (p != end) throw UsageError(option + ": expected three finite numbers X,Y,Z, got " + quotedText(text));
  return v;
}

Eigen::Vector3d parseDirection(const std::string& text, const std::string& option) {
  const std::optional<Eigen::Vector3d> unit = normalizedOrNone(parseVec3(text, option));  // 1e308 too
  if (!unit) throw UsageError(option + ": the direction must not be zero, got " + quotedText(text));
  return *unit;
}

FrameRange parseFrameRange(const std::string& text, const std::string& option) {
  FrameRange r;
  const auto dash = text.find('-', 1);
  auto parse_int = [&](const std::string& s) {
    int value = 0;
    auto [next, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (ec != std::errc() || next != s.data() + s.size() || value < 0)
      throw UsageError(option + ": expected a frame range A-B or a frame N (whole numbers >= 0), got " +
                       quotedText(text));
    return value;
  };
  if (dash == std::string::npos) {
    r.first = r.last = parse_int(text);
  } else {
    r.first = parse_int(text.substr(0, dash));
    r.last = parse_int(text.substr(dash + 1));
    if (r.last < r.first) throw UsageError(option + ": expected A-B with A <= B, got " + quotedText(text));
  }
  return r;
}

void noteDeprecated(std::string_view old_spelling, std::string_view new_spelling) {
  std::fprintf(stderr, "vdg: %.*s is deprecated (it will be removed in the next version): use %.*s\n",
               static_cast<int>(old_spelling.size()), old_spelling.data(), static_cast<int>(new_spelling.size()),
               new_spelling.data());
}

bool isPlainCount(std::string_view text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

CLI::Validator oldCommaSize() {
  return CLI::Validator(
      [](std::string& text) {
        const auto comma = text.find(',');
        if (comma != std::string::npos && text.find('x') == std::string::npos) {
          noteDeprecated("--size W,H", "--size WxH");
          text[comma] = 'x';
        }
        return std::string();
      },
      "");
}

Progress::Progress(std::string label, long total, bool quiet)
    : label_(std::move(label)), total_(total), enabled_(!quiet && total > 1 && ::isatty(STDERR_FILENO)) {}

Progress::~Progress() { finish(); }

void Progress::finish() {
  if (enabled_ && last_percent_ >= 0) std::fputc('\n', stderr);
  last_percent_ = -1;
  enabled_ = false;
}

void Progress::step(long done) {
  if (!enabled_) return;
  const int percent = static_cast<int>(100 * done / total_);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  constexpr int kWidth = 30;
  const int filled = kWidth * percent / 100;
  std::fprintf(stderr, "\r%s [%.*s%*s] %3d%% (%ld/%ld)", label_.c_str(), filled, "##############################",
               kWidth - filled, "", percent, done, total_);
  std::fflush(stderr);
}

}  // namespace vdg::cli
