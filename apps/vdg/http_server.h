// The static file server of `vdg view --serve`: HTTP/1.1 GET and HEAD on 127.0.0.1 only, confined to
// one folder (vdg/io/http_request.h parses the requests).
#pragma once

#include <functional>
#include <string>

namespace vdg::cli {

// Serves the files under `folder` on 127.0.0.1:`port` (0: a free port the system picks) until
// SIGINT or SIGTERM; then returns. `ready(port)` is called once the socket listens, with the port.
// Each connection gets one request and one answer (Connection: close), on a thread of its own (at
// most 32 at a time), with a 5-second limit on reading the request. A path is served only when it
// names a regular file inside `folder` once symbolic links are followed; otherwise 404 (a folder is
// never listed). Throws vdg::Error when the port cannot be had ("--port 8000: the port is in use").
void serveFolder(const std::string& folder, int port, const std::function<void(int)>& ready);

}  // namespace vdg::cli
