// The one JSON reading layer of vdg's file formats (private to src/io).
//
// Every JSON format (manifests, camera files, edit scripts and logs, animation specs) is parsed
// here, with the same limits and one message style:
//   "FILE: 'keys'[2].'view': expected 3 numbers, got a string"
// i.e. where (the file, or a caller's label), the key path inside the document, and what was
// expected. Values from the user are never dumped into messages: containers are described by
// kind and size, strings are cut short, and every message is one line (vdg::Error escapes control
// characters). Nesting deeper than kMaxJsonDepth is refused while parsing, so no later recursive
// walk (destruction, printing) can exhaust the stack.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>

#include "vdg/geom/error.h"

namespace vdg::io {

using Json = nlohmann::json;

// Deeper nesting than any vdg format needs (the deepest, an animation spec, uses about 6 levels).
inline constexpr int kMaxJsonDepth = 64;

// Parses `text`. Throws vdg::Error "WHERE: not valid JSON at line L, column C: REASON" or
// "WHERE: JSON nested deeper than 64 levels (at line L, column C)".
Json parseJson(std::string_view text, const std::string& where);
// Reads `path` (a regular file of at most kMaxJsonFileBytes, see vdg/io/read_file.h) and parses it
// with where = path. `what` names the kind of file in messages ("model", "edit script").
Json readJsonFile(const std::string& path, const std::string& what);

// A short, one-line description of a value for messages: "a string \"abc\"", "the number 3",
// "an array of 7 items", "an object", "null", "true". Never walks into containers.
std::string describe(const Json& value);

// A position in a document: `where` (the file, or a caller's label) and the key path inside it.
struct Ctx {
  std::string where;
  std::string path;  // e.g. "'track'.'keys'[1]"; empty at the top

  Ctx key(const std::string& k) const { return {where, path.empty() ? "'" + k + "'" : path + ".'" + k + "'"}; }
  Ctx index(std::size_t i) const { return {where, path + "[" + std::to_string(i) + "]"}; }
  // A path segment given verbatim, for example "key 'front' (keys[0])".
  Ctx labelled(const std::string& label) const { return {where, label}; }
  std::string prefix() const { return path.empty() ? where : where + ": " + path; }
  [[noreturn]] void fail(const std::string& what) const { throw Error(prefix() + ": " + what); }
};

// Rejects keys of object `j` not in `keys` (they are usually typos), or `j` not being an object.
void allowKeys(const Json& j, const Ctx& ctx, std::initializer_list<const char*> keys);
// `j` must be an object holding `key`; returns it.
const Json& required(const Json& j, const char* key, const Ctx& ctx);

double number(const Json& j, const Ctx& ctx);  // finite
double numberOr(const Json& obj, const char* key, double fallback, const Ctx& ctx);
// A finite number in [lo, hi]; the message gives the range.
double numberIn(const Json& j, const Ctx& ctx, double lo, double hi);
// An integer in [lo, hi] (no fraction, no overflow: 4294967297 is not 1).
std::int64_t integer(const Json& j, const Ctx& ctx, std::int64_t lo, std::int64_t hi);
bool boolean(const Json& j, const Ctx& ctx);
// The "version" field of a versioned format: an integer this vdg reads (oldest..current), else
// "WHERE: 'version': this vdg reads WHAT versions 1 to 2, got 7". Missing: `missing` when >= 0,
// else an error.
int formatVersion(const Json& doc, const Ctx& ctx, const std::string& what, int oldest, int current, int missing = -1);
std::string string(const Json& j, const Ctx& ctx);
// An array of numbers; `expected` > 0 demands exactly that many.
Eigen::VectorXd vector(const Json& j, const Ctx& ctx, long expected = 0);
Eigen::Vector3d vector3(const Json& j, const Ctx& ctx);

// A string from a fixed table of names.
template <typename Enum, std::size_t N>
Enum enumValue(const Json& j, const Ctx& ctx, const std::pair<const char*, Enum> (&names)[N]) {
  const std::string s = string(j, ctx);
  std::string list;
  for (const auto& [name, value] : names) {
    if (s == name) return value;
    list += list.empty() ? "" : ", ";
    list += std::string("'") + name + "'";
  }
  ctx.fail("unknown value '" + (s.size() > 40 ? s.substr(0, 40) + "..." : s) + "' (expected one of " + list + ")");
}

// Re-raises a builder's vdg::Error (which names the field) under this context.
template <typename F>
auto withContext(const Ctx& ctx, F f) {
  try {
    return f();
  } catch (const Error& e) {
    throw Error(ctx.prefix() + ": " + e.what());
  }
}

}  // namespace vdg::io
