#include "cli.h"

#include <unistd.h>
#include <charconv>

namespace vdg::cli {

Eigen::Vector3d parseVec3(const std::string& text, const std::string& option) {
  Eigen::Vector3d v;
  const char* p = text.data();
  const char* end = text.data() + text.size();
  for (int i = 0; i < 3; ++i) {
    while (p < end && *p == ' ') ++p;
    double value = 0;
    auto [next, ec] = std::from_chars(p, end, value);
    if (ec != std::errc() || !std::isfinite(value))
      throw UsageError(option + ": expected three numbers X,Y,Z, got '" + text + "'");
    v[i] = value;
    p = next;
    while (p < end && *p == ' ') ++p;
    if (i < 2) {
      if (p == end || *p != ',') throw UsageError(option + ": expected three numbers X,Y,Z, got '" + text + "'");
      ++p;
    }
  }
  if (p != end) throw UsageError(option + ": expected three numbers X,Y,Z, got '" + text + "'");
  return v;
}

FrameRange parseFrameRange(const std::string& text, const std::string& option) {
  FrameRange r;
  const auto dash = text.find('-', 1);
  auto parse_int = [&](const std::string& s) {
    int value = 0;
    auto [next, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (ec != std::errc() || next != s.data() + s.size() || value < 0)
      throw UsageError(option + ": expected a frame range A-B or a frame N, got '" + text + "'");
    return value;
  };
  if (dash == std::string::npos) {
    r.first = r.last = parse_int(text);
  } else {
    r.first = parse_int(text.substr(0, dash));
    r.last = parse_int(text.substr(dash + 1));
    if (r.last < r.first) throw UsageError(option + ": range '" + text + "' ends before it starts");
  }
  return r;
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
