// vdg view --serve: a small static HTTP/1.1 server with POSIX sockets (see http_server.h).
#include "http_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <thread>

#include "vdg/geom/error.h"
#include "vdg/io/http_request.h"

namespace vdg::cli {
namespace {

namespace fs = std::filesystem;

volatile std::sig_atomic_t g_stop = 0;
extern "C" void onStopSignal(int) { g_stop = 1; }

constexpr int kMaxConnections = 32;
constexpr int kReadTimeoutSeconds = 5;

// Sends all of `data`; false when the peer has gone.
bool sendAll(int fd, std::string_view data) {
  while (!data.empty()) {
    const ssize_t n = ::send(fd, data.data(), data.size(), MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

void sendError(int fd, int status) {
  const std::string body = std::to_string(status) + " " + std::string(http::reasonPhrase(status)) + "\n";
  sendAll(fd, http::responseHead(status, "text/plain; charset=utf-8", body.size()) + body);
}

// The file `path` names under `root` (canonical), or empty when it is not a regular file inside it.
fs::path confinedFile(const fs::path& root, const std::string& path) {
  std::error_code ec;
  const fs::path file = fs::canonical(root / path, ec);
  if (ec) return {};
  const std::string text = file.string(), prefix = root.string() + "/";
  if (text.compare(0, prefix.size(), prefix) != 0) return {};
  if (!fs::is_regular_file(file, ec)) return {};
  return file;
}

// Reads one request head from `fd` (at most kMaxRequestHead bytes); empty when none came in time.
std::string readHead(int fd, bool& too_long) {
  std::string data;
  char buffer[2048];
  too_long = false;
  while (!http::headLength(data)) {
    if (data.size() > http::kMaxRequestHead) {
      too_long = true;
      return data;
    }
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return {};
    data.append(buffer, static_cast<std::size_t>(n));
  }
  return data.substr(0, *http::headLength(data));
}

void answer(int fd, const fs::path& root) {
  bool too_long = false;
  const std::string head = readHead(fd, too_long);
  if (too_long) return sendError(fd, 431);
  if (head.empty()) return;
  const http::Request request = http::parseRequest(head);
  if (request.status != 200) return sendError(fd, request.status);
  const fs::path file = confinedFile(root, request.path);
  if (file.empty()) return sendError(fd, 404);
  std::ifstream in(file, std::ios::binary);
  const std::string body((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) return sendError(fd, 500);
  const std::string response_head = http::responseHead(200, http::contentType(request.path), body.size());
  if (sendAll(fd, response_head) && !request.head) sendAll(fd, body);
}

int listenOn(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw Error(std::string("cannot open a socket: ") + std::strerror(errno));
  const int yes = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 || ::listen(fd, 64) != 0) {
    const int error = errno;
    ::close(fd);
    throw Error("--port " + std::to_string(port) + ": cannot serve on 127.0.0.1 there: " + std::strerror(error) +
                (error == EADDRINUSE ? " (try another port, or --port 0 for a free one)" : ""));
  }
  return fd;
}

}  // namespace

void serveFolder(const std::string& folder, int port, const std::function<void(int)>& ready) {
  const fs::path root = fs::canonical(folder);
  const int listener = listenOn(port);
  sockaddr_in bound{};
  socklen_t length = sizeof bound;
  ::getsockname(listener, reinterpret_cast<sockaddr*>(&bound), &length);

  struct sigaction stop {
  }, old_int{}, old_term{};
  stop.sa_handler = onStopSignal;  // no SA_RESTART: poll() returns at once with EINTR
  sigemptyset(&stop.sa_mask);
  g_stop = 0;
  ::sigaction(SIGINT, &stop, &old_int);
  ::sigaction(SIGTERM, &stop, &old_term);
  ready(ntohs(bound.sin_port));

  // Shared with the answering threads, so that one outliving this function still finds it.
  struct Shared {
    fs::path root;
    std::atomic<int> open_connections{0};
  };
  const auto shared = std::make_shared<Shared>();
  shared->root = root;
  std::atomic<int>& open_connections = shared->open_connections;
  while (!g_stop) {
    pollfd waiting{listener, POLLIN, 0};
    if (::poll(&waiting, 1, 250) <= 0) continue;
    const int fd = ::accept4(listener, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) continue;
    if (open_connections.load() >= kMaxConnections) {
      ::close(fd);
      continue;
    }
    timeval timeout{kReadTimeoutSeconds, 0};
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof timeout);
    ++open_connections;
    std::thread([fd, shared] {
      answer(fd, shared->root);
      ::close(fd);
      --shared->open_connections;
    }).detach();
  }
  ::close(listener);
  // The answers under way finish (each is bounded by the 5-second limits).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2 * kReadTimeoutSeconds + 1);
  while (open_connections.load() > 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ::sigaction(SIGINT, &old_int, nullptr);
  ::sigaction(SIGTERM, &old_term, nullptr);
}

}  // namespace vdg::cli
