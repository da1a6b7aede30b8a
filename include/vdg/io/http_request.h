// The request side of `vdg view --serve`'s small static HTTP/1.1 server (apps/vdg/http_server.cpp):
// parsing a request head, confining its path to the served folder's names, and the media types.
// Pure functions on text (no sockets), so that a fuzzer (fuzz/fuzz_http_request.cpp) and unit
// tests can reach all of it.
//
// What is accepted: "GET" or "HEAD", one space, an origin-form target ("/a/b.js?query" ; the query
// and a fragment are ignored), one space, "HTTP/1.0" or "HTTP/1.1", CRLF (a bare LF is tolerated),
// header lines of "Name: value" (read over, not interpreted), an empty line. The head is at most
// kMaxRequestHead bytes. The target is percent-decoded once; a decoded NUL, a backslash, a
// segment "..", or a segment starting with "." (hidden files, vdg's own temporary files) is
// refused with 404; an empty path or one ending in "/" names its "index.html".
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace vdg::http {

// The longest request head read (request line and headers, with the empty line).
inline constexpr std::size_t kMaxRequestHead = 8192;

struct Request {
  int status = 200;     // 200: serve `path`; otherwise the error status to answer (400, 404, 405, 414, 505)
  bool head = false;    // HEAD: answer the headers only
  std::string path;     // the file's name relative to the served folder, '/'-separated, no leading '/'
  std::string problem;  // for an error status, what was wrong (for the log), else empty
};

// The length of the head in `data` (up to and including the empty line), or nullopt while it is
// not complete yet.
std::optional<std::size_t> headLength(std::string_view data);

// Parses a complete request head (as delimited by headLength). Never throws for any input.
Request parseRequest(std::string_view head);

// The media type of a file by its extension: text/javascript for .js/.mjs (module scripts need
// it), text/html, model/gltf-binary, model/gltf+json, image/png, image/jpeg, application/json,
// text/css, text/plain for .txt/.md, application/octet-stream otherwise.
std::string_view contentType(std::string_view path);

// "HTTP/1.1 STATUS REASON\r\n" with Content-Type, Content-Length, Cache-Control: no-store,
// X-Content-Type-Options: nosniff, Connection: close and the empty line.
std::string responseHead(int status, std::string_view content_type, std::size_t content_length);

// The reason phrase of a status ("OK", "Not Found", ...).
std::string_view reasonPhrase(int status);

}  // namespace vdg::http
