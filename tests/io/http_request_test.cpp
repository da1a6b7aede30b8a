// vdg/io/http_request.h: the request heads vdg view --serve accepts, the paths it serves and the ones
// it refuses, and the media types (the server itself is tested by tests/cli/view_cli.sh and
// tests/web/browser).
#include "vdg/io/http_request.h"

#include <gtest/gtest.h>

#include <string>

namespace vdg::http {
namespace {

Request get(const std::string& target) { return parseRequest("GET " + target + " HTTP/1.1\r\nHost: x\r\n\r\n"); }

TEST(HttpRequest, HeadLengthWaitsForTheEmptyLine) {
  EXPECT_FALSE(headLength("GET / HTTP/1.1\r\nHost: x\r\n"));
  EXPECT_EQ(headLength("GET / HTTP/1.1\r\n\r\nbody"), std::optional<std::size_t>(18));
  EXPECT_EQ(headLength("GET / HTTP/1.0\n\n"), std::optional<std::size_t>(16));
}

TEST(HttpRequest, ServesPathsInsideTheFolder) {
  EXPECT_EQ(get("/").path, "index.html");
  EXPECT_EQ(get("/three/addons/loaders/GLTFLoader.js?v=1#x").path, "three/addons/loaders/GLTFLoader.js");
  EXPECT_EQ(get("/a%20b.js").path, "a b.js");
  EXPECT_EQ(get("//a//b.js").path, "a/b.js");
  EXPECT_EQ(get("/docs/").path, "docs/index.html");
  EXPECT_EQ(get("/model.glb").status, 200);
  EXPECT_FALSE(get("/model.glb").head);
  const Request head = parseRequest("HEAD /view.js HTTP/1.0\n\n");
  EXPECT_EQ(head.status, 200);
  EXPECT_TRUE(head.head);
}

TEST(HttpRequest, RefusesPathsThatLeaveTheFolderOrAreHidden) {
  for (const char* target : {"/../etc/passwd", "/a/../../b", "/%2e%2e/x", "/.vdg-view", "/.vdg-view-abc123/index.html",
                             "/a%00.js", "/a%5cb", "/a\\b"}) {
    const Request r = get(target);
    EXPECT_EQ(r.status, 404) << target;
    EXPECT_TRUE(r.path.empty()) << target;
    EXPECT_FALSE(r.problem.empty()) << target;
  }
}

TEST(HttpRequest, RefusesMalformedRequests) {
  EXPECT_EQ(parseRequest("POST / HTTP/1.1\r\n\r\n").status, 405);
  EXPECT_EQ(parseRequest("GET / HTTP/2.0\r\n\r\n").status, 505);
  EXPECT_EQ(parseRequest("GET /\r\n\r\n").status, 400);
  EXPECT_EQ(parseRequest("GET  / HTTP/1.1\r\n\r\n").status, 400);
  EXPECT_EQ(parseRequest("GET x HTTP/1.1\r\n\r\n").status, 400);
  EXPECT_EQ(parseRequest("GET /%zz HTTP/1.1\r\n\r\n").status, 400);
  EXPECT_EQ(parseRequest("GET /%4 HTTP/1.1\r\n\r\n").status, 400);
  EXPECT_EQ(parseRequest("GET /a\x01 HTTP/1.1\r\n\r\n").status, 400);
  EXPECT_EQ(parseRequest("GET / HTTP/1.1\r\nno colon here\r\n\r\n").status, 400);
  EXPECT_EQ(parseRequest("GET /" + std::string(3000, 'a') + " HTTP/1.1\r\n\r\n").status, 414);
  EXPECT_EQ(parseRequest("GET / HTTP/1.1\r\nX: " + std::string(kMaxRequestHead, 'a') + "\r\n\r\n").status, 431);
  EXPECT_EQ(parseRequest("").status, 400);
}

TEST(HttpRequest, MediaTypesModuleScriptsNeed) {
  EXPECT_EQ(contentType("view.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(contentType("a.mjs"), "text/javascript; charset=utf-8");
  EXPECT_EQ(contentType("index.html"), "text/html; charset=utf-8");
  EXPECT_EQ(contentType("model.glb"), "model/gltf-binary");
  EXPECT_EQ(contentType("t.png"), "image/png");
  EXPECT_EQ(contentType("s.json"), "application/json");
  EXPECT_EQ(contentType("js"), "application/octet-stream");
  const std::string head = responseHead(404, "text/plain", 14);
  EXPECT_EQ(head.rfind("HTTP/1.1 404 Not Found\r\n", 0), 0u);
  EXPECT_NE(head.find("Content-Length: 14\r\n"), std::string::npos);
  EXPECT_EQ(head.substr(head.size() - 4), "\r\n\r\n");
}

}  // namespace
}  // namespace vdg::http
