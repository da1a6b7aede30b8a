#include "json_reader.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "vdg/io/read_file.h"

namespace vdg::io {
namespace {

// Thrown from DepthLimitedSax when the nesting limit is reached.
struct TooDeep {};

// nlohmann's DOM builder with the nesting limit checked as each container opens. Not the callback
// parser (Json::parse with a callback): after every object or array it scans the enclosing
// container for discarded values, so an array of n objects cost O(n^2) (a lines file of 100,000
// pairs took 5 s to parse, a 64 MiB file of small objects would take hours).
class DepthLimitedSax : public nlohmann::detail::json_sax_dom_parser<Json> {
 public:
  explicit DepthLimitedSax(Json& result) : json_sax_dom_parser(result, true) {}
  bool start_object(std::size_t elements) {
    if (++depth_ > kMaxJsonDepth) throw TooDeep{};
    return json_sax_dom_parser::start_object(elements);
  }
  bool end_object() {
    --depth_;
    return json_sax_dom_parser::end_object();
  }
  bool start_array(std::size_t elements) {
    if (++depth_ > kMaxJsonDepth) throw TooDeep{};
    return json_sax_dom_parser::start_array(elements);
  }
  bool end_array() {
    --depth_;
    return json_sax_dom_parser::end_array();
  }

 private:
  int depth_ = 0;  // containers open
};

// Line and column (1-based) of byte offset `byte` in `text`.
std::string position(std::string_view text, std::size_t byte) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// nlohmann's messages read "[json.exception.parse_error.101] parse error at line 1, column 2:
// syntax error while parsing value - invalid literal; last read: 'x'"; keep the reason only.
std::string reason(const std::string& what) {
  std::string text = what;
  if (text.rfind("[json.exception.", 0) == 0 && text.find("] ") != std::string::npos)
    text = text.substr(text.find("] ") + 2);
  const auto colon = text.find(": ");
  if (colon != std::string::npos) text = text.substr(colon + 2);
  const auto last_read = text.find("; last read:");
  if (last_read != std::string::npos) text = text.substr(0, last_read);
  if (text.rfind("syntax error while parsing ", 0) == 0) text = text.substr(27);
  if (text.size() > 120) text = text.substr(0, 120) + "...";
  return text;
}

}  // namespace

Json parseJson(std::string_view text, const std::string& where) {
  std::size_t deep_at = 0;
  try {
    Json result;
    DepthLimitedSax sax(result);
    Json::sax_parse(text.begin(), text.end(), &sax);
    return result;
  } catch (const TooDeep&) {
    // Find where the limit was crossed, for the message (strings are skipped).
    int depth = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
      const char c = text[i];
      if (in_string) {
        if (c == '\\')
          ++i;
        else if (c == '"')
          in_string = false;
      } else if (c == '"') {
        in_string = true;
      } else if (c == '[' || c == '{') {
        if (++depth > kMaxJsonDepth) {
          deep_at = i;
          break;
        }
      } else if (c == ']' || c == '}') {
        --depth;
      }
    }
    throw Error(where + ": JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels (at " +
                position(text, deep_at) + ")");
  } catch (const Json::parse_error& e) {
    throw Error(where + ": not valid JSON at " + position(text, e.byte > 0 ? e.byte - 1 : 0) + ": " + reason(e.what()));
  } catch (const Json::exception& e) {  // for instance a number too large for a double
    throw Error(where + ": not valid JSON: " + reason(e.what()));
  }
}

Json readJsonFile(const std::string& path, const std::string& what) {
  return parseJson(readFileLimited(path, what, kMaxJsonFileBytes), path);
}

std::string describe(const Json& value) {
  switch (value.type()) {
    case Json::value_t::null:
      return "null";
    case Json::value_t::boolean:
      return value.get<bool>() ? "true" : "false";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float:
      return "the number " + value.dump();
    case Json::value_t::string: {
      std::string s = value.get<std::string>();
      constexpr std::size_t kShown = 40;
      if (s.size() > kShown) s = s.substr(0, kShown) + "...";
      return "the string \"" + s + "\"";
    }
    case Json::value_t::array:
      return "an array of " + std::to_string(value.size()) + (value.size() == 1 ? " item" : " items");
    case Json::value_t::object:
      return "an object";
    default:
      return std::string("a ") + value.type_name();
  }
}

void allowKeys(const Json& j, const Ctx& ctx, std::initializer_list<const char*> keys) {
  if (!j.is_object()) ctx.fail("expected an object, got " + describe(j));
  for (const auto& item : j.items()) {
    bool known = false;
    for (const char* k : keys) known = known || item.key() == k;
    if (!known) {
      std::string list;
      for (const char* k : keys) list += (list.empty() ? "'" : ", '") + std::string(k) + "'";
      std::string name = item.key();
      if (name.size() > 40) name = name.substr(0, 40) + "...";
      ctx.fail("unknown key '" + name + "' (expected one of " + list + ")");
    }
  }
}

const Json& required(const Json& j, const char* key, const Ctx& ctx) {
  if (!j.is_object()) ctx.fail("expected an object, got " + describe(j));
  const auto it = j.find(key);
  if (it == j.end()) ctx.fail(std::string("missing key '") + key + "'");
  return *it;
}

double number(const Json& j, const Ctx& ctx) {
  if (!j.is_number()) ctx.fail("expected a number, got " + describe(j));
  const double v = j.get<double>();
  if (!std::isfinite(v)) ctx.fail("expected a finite number");
  return v;
}

double numberOr(const Json& obj, const char* key, double fallback, const Ctx& ctx) {
  return obj.contains(key) ? number(obj.at(key), ctx.key(key)) : fallback;
}

double numberIn(const Json& j, const Ctx& ctx, double lo, double hi) {
  const double v = number(j, ctx);
  if (v < lo || v > hi) {
    std::ostringstream range;
    range.precision(17);
    range << "expected a number from " << lo << " to " << hi << ", got " << v;
    ctx.fail(range.str());
  }
  return v;
}

std::int64_t integer(const Json& j, const Ctx& ctx, std::int64_t lo, std::int64_t hi) {
  const std::string range = "expected an integer from " + std::to_string(lo) + " to " + std::to_string(hi);
  if (j.is_number_unsigned()) {
    const std::uint64_t u = j.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(hi) || (lo > 0 && u < static_cast<std::uint64_t>(lo)))
      ctx.fail(range + ", got " + j.dump());
    return static_cast<std::int64_t>(u);
  }
  if (!j.is_number_integer()) ctx.fail(range + ", got " + describe(j));
  const std::int64_t v = j.get<std::int64_t>();
  if (v < lo || v > hi) ctx.fail(range + ", got " + std::to_string(v));
  return v;
}

int formatVersion(const Json& doc, const Ctx& ctx, const std::string& what, int oldest, int current, int missing) {
  const std::string readable = oldest == current
                                   ? "version " + std::to_string(current)
                                   : "versions " + std::to_string(oldest) + " to " + std::to_string(current);
  if (!doc.is_object()) ctx.fail("expected a JSON object at the top level, got " + describe(doc));
  const auto it = doc.find("version");
  if (it == doc.end()) {
    if (missing >= 0) return missing;
    ctx.fail("missing 'version' (this vdg reads " + what + " " + readable + ")");
  }
  const Ctx vctx = ctx.key("version");
  const bool whole = it->is_number_integer() || it->is_number_unsigned();
  if (!whole) vctx.fail("expected an integer, got " + describe(*it));
  const bool in_range = it->is_number_unsigned() ? it->get<std::uint64_t>() <= static_cast<std::uint64_t>(current)
                                                 : it->get<std::int64_t>() <= current;
  if (!in_range || it->get<std::int64_t>() < oldest)
    vctx.fail("this vdg reads " + what + " " + readable + ", got " + it->dump());
  return static_cast<int>(it->get<std::int64_t>());
}

bool boolean(const Json& j, const Ctx& ctx) {
  if (!j.is_boolean()) ctx.fail("expected true or false, got " + describe(j));
  return j.get<bool>();
}

std::string string(const Json& j, const Ctx& ctx) {
  if (!j.is_string()) ctx.fail("expected a string, got " + describe(j));
  return j.get<std::string>();
}

Eigen::VectorXd vector(const Json& j, const Ctx& ctx, long expected) {
  auto shape_error = [&]() {
    if (expected > 0)
      ctx.fail("expected " + std::to_string(expected) + (expected == 1 ? " number" : " numbers") + ", got " +
               describe(j));
    ctx.fail("expected an array of numbers, got " + describe(j));
  };
  if (!j.is_array() || j.empty()) shape_error();
  if (expected > 0 && static_cast<long>(j.size()) != expected) shape_error();
  Eigen::VectorXd v(static_cast<Eigen::Index>(j.size()));
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_number()) shape_error();
    v[static_cast<Eigen::Index>(i)] = j[i].get<double>();
    if (!std::isfinite(v[static_cast<Eigen::Index>(i)])) ctx.index(i).fail("expected a finite number");
  }
  return v;
}

Eigen::Vector3d vector3(const Json& j, const Ctx& ctx) { return vector(j, ctx, 3); }

}  // namespace vdg::io
