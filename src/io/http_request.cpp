// vdg/io/http_request.h: the request head of vdg view --serve, parsed without throwing.
#include "vdg/io/http_request.h"

#include <array>
#include <utility>

namespace vdg::http {
namespace {

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

Request refused(int status, std::string problem) {
  Request r;
  r.status = status;
  r.problem = std::move(problem);
  return r;
}

// The decoded path of an origin-form target, or the refusal.
Request decodeTarget(std::string_view target) {
  if (target.empty() || target.front() != '/') return refused(400, "the target does not start with '/'");
  const std::size_t end = target.find_first_of("?#");
  if (end != std::string_view::npos) target = target.substr(0, end);
  std::string decoded;
  decoded.reserve(target.size());
  for (std::size_t i = 0; i < target.size(); ++i) {
    const char c = target[i];
    if (static_cast<unsigned char>(c) <= 0x20 || c == 0x7f) return refused(400, "a control character in the target");
    if (c != '%') {
      decoded += c;
      continue;
    }
    const int hi = i + 2 < target.size() ? hexValue(target[i + 1]) : -1;
    const int lo = i + 2 < target.size() ? hexValue(target[i + 2]) : -1;
    if (hi < 0 || lo < 0) return refused(400, "a bad percent escape in the target");
    decoded += static_cast<char>(hi * 16 + lo);
    i += 2;
  }
  Request r;
  std::size_t start = 1;  // past the leading '/'
  while (start <= decoded.size()) {
    std::size_t slash = decoded.find('/', start);
    if (slash == std::string::npos) slash = decoded.size();
    const std::string_view segment = std::string_view(decoded).substr(start, slash - start);
    if (segment.find('\0') != std::string_view::npos || segment.find('\\') != std::string_view::npos)
      return refused(404, "a NUL or a backslash in the path");
    if (!segment.empty() && segment.front() == '.') return refused(404, "a hidden name or '..' in the path");
    if (!segment.empty()) {
      if (!r.path.empty()) r.path += '/';
      r.path += segment;
    }
    start = slash + 1;
  }
  if (r.path.empty() || decoded.back() == '/') r.path += r.path.empty() ? "index.html" : "/index.html";
  return r;
}

}  // namespace

std::optional<std::size_t> headLength(std::string_view data) {
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (data[i] != '\n') continue;
    if (i + 1 < data.size() && data[i + 1] == '\n') return i + 2;
    if (i + 2 < data.size() && data[i + 1] == '\r' && data[i + 2] == '\n') return i + 3;
  }
  return std::nullopt;
}

Request parseRequest(std::string_view head) {
  if (head.size() > kMaxRequestHead) return refused(431, "the request head is too long");
  const std::size_t line_end = head.find('\n');
  if (line_end == std::string_view::npos) return refused(400, "no request line");
  std::string_view line = head.substr(0, line_end);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  const std::size_t sp1 = line.find(' ');
  const std::size_t sp2 = sp1 == std::string_view::npos ? sp1 : line.find(' ', sp1 + 1);
  if (sp2 == std::string_view::npos || line.find(' ', sp2 + 1) != std::string_view::npos)
    return refused(400, "the request line is not METHOD TARGET VERSION");
  const std::string_view method = line.substr(0, sp1);
  const std::string_view target = line.substr(sp1 + 1, sp2 - sp1 - 1);
  const std::string_view version = line.substr(sp2 + 1);
  if (version != "HTTP/1.1" && version != "HTTP/1.0") return refused(505, "not HTTP/1.0 or HTTP/1.1");
  if (method != "GET" && method != "HEAD") return refused(405, "only GET and HEAD are served");
  if (target.size() > 2048) return refused(414, "the target is too long");
  // Header lines: each must hold a colon; their values are not used.
  std::string_view rest = head.substr(line_end + 1);
  while (!rest.empty()) {
    const std::size_t end = rest.find('\n');
    std::string_view header = rest.substr(0, end);
    if (!header.empty() && header.back() == '\r') header.remove_suffix(1);
    if (header.empty()) break;
    if (header.find(':') == std::string_view::npos || header.front() == ' ' || header.front() == '\t')
      return refused(400, "a header line without a name and a colon");
    if (end == std::string_view::npos) break;
    rest = rest.substr(end + 1);
  }
  Request r = decodeTarget(target);
  r.head = method == "HEAD";
  return r;
}

std::string_view contentType(std::string_view path) {
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 12> kTypes{{
      {".js", "text/javascript; charset=utf-8"},
      {".mjs", "text/javascript; charset=utf-8"},
      {".html", "text/html; charset=utf-8"},
      {".glb", "model/gltf-binary"},
      {".gltf", "model/gltf+json"},
      {".bin", "application/octet-stream"},
      {".png", "image/png"},
      {".jpg", "image/jpeg"},
      {".json", "application/json"},
      {".css", "text/css; charset=utf-8"},
      {".txt", "text/plain; charset=utf-8"},
      {".md", "text/plain; charset=utf-8"},
  }};
  for (const auto& [extension, type] : kTypes)
    if (path.size() >= extension.size() && path.substr(path.size() - extension.size()) == extension) return type;
  return "application/octet-stream";
}

std::string_view reasonPhrase(int status) {
  switch (status) {
    case 200:
      return "OK";
    case 400:
      return "Bad Request";
    case 404:
      return "Not Found";
    case 405:
      return "Method Not Allowed";
    case 408:
      return "Request Timeout";
    case 414:
      return "URI Too Long";
    case 431:
      return "Request Header Fields Too Large";
    case 500:
      return "Internal Server Error";
    case 505:
      return "HTTP Version Not Supported";
    default:
      return "Error";
  }
}

std::string responseHead(int status, std::string_view content_type, std::size_t content_length) {
  std::string head = "HTTP/1.1 " + std::to_string(status) + " " + std::string(reasonPhrase(status)) + "\r\n";
  head += "Content-Type: " + std::string(content_type) + "\r\n";
  head += "Content-Length: " + std::to_string(content_length) + "\r\n";
  head += "Cache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\nConnection: close\r\n\r\n";
  return head;
}

}  // namespace vdg::http
