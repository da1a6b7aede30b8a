// libFuzzer target: an HTTP request head -> vdg::http::parseRequest (vdg view --serve). Any input
// must be answered without a crash, and an accepted path must stay inside the served folder: no
// leading '/', no empty, "." or ".." segment, no hidden name, no NUL or backslash.
// See fuzz_support.h for what counts as a finding.
#include <optional>
#include <string>
#include <string_view>

#include "fuzz_support.h"
#include "vdg/io/http_request.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size > fuzz::kMaxInputBytes) return -1;
  const std::string text_storage = fuzz::text(data, size);
  const std::string_view text = text_storage;
  const std::optional<std::size_t> length = http::headLength(text);
  fuzz::require(!length || *length <= text.size(), "headLength beyond the data");
  const http::Request request = http::parseRequest(length ? text.substr(0, *length) : text);
  if (request.status != 200) {
    fuzz::require(!request.problem.empty(), "a refused request without a reason");
    return 0;
  }
  const std::string_view path = request.path;
  fuzz::require(!path.empty() && path.front() != '/', "an accepted path that is empty or absolute");
  std::size_t start = 0;
  while (start <= path.size()) {
    std::size_t slash = path.find('/', start);
    if (slash == std::string_view::npos) slash = path.size();
    const std::string_view segment = path.substr(start, slash - start);
    fuzz::require(!segment.empty() && segment.front() != '.', "an accepted path with an empty or dot segment");
    fuzz::require(segment.find('\0') == std::string_view::npos && segment.find('\\') == std::string_view::npos,
                  "an accepted path with a NUL or a backslash");
    start = slash + 1;
  }
  (void)http::contentType(path);
  (void)http::responseHead(200, http::contentType(path), size);
  return 0;
}
