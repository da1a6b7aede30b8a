// Input event files of `vdg studio` (vdg/io/studio_events.h, docs/studio-files.md). Read through
// the JSON layer of json_reader.h; written one event per line and checked by reading the text
// back, so the writer can never produce a file the reader refuses.
#include "vdg/io/studio_events.h"

#include <algorithm>
#include <iterator>

#include "json_reader.h"
#include "vdg/geom/error.h"

namespace vdg {

namespace {

using io::Ctx;
using io::Json;
using OJson = nlohmann::ordered_json;

constexpr std::string_view kKeyNames[] = {
    "A",      "B",         "C",      "D",     "E",           "F",           "G",   "H",    "I",      "J",
    "K",      "L",         "M",      "N",     "O",           "P",           "Q",   "R",    "S",      "T",
    "U",      "V",         "W",      "X",     "Y",           "Z",           "0",   "1",    "2",      "3",
    "4",      "5",         "6",      "7",     "8",           "9",           "F1",  "F2",   "F3",     "F4",
    "F5",     "F6",        "F7",     "F8",    "F9",          "F10",         "F11", "F12",  "Escape", "Enter",
    "Tab",    "Backspace", "Delete", "Space", "Left",        "Right",       "Up",  "Down", "Home",   "End",
    "PageUp", "PageDown",  "Minus",  "Equal", "LeftBracket", "RightBracket"};
// The first names are the runs A..Z, 0..9 and F1..F12; messages list them as such.
constexpr std::size_t kRunNames = 26 + 10 + 12;

constexpr std::pair<const char*, InputEventType> kTypes[] = {{"mouse_move", InputEventType::kMouseMove},
                                                             {"mouse_down", InputEventType::kMouseDown},
                                                             {"mouse_up", InputEventType::kMouseUp},
                                                             {"scroll", InputEventType::kScroll},
                                                             {"key_down", InputEventType::kKeyDown},
                                                             {"key_up", InputEventType::kKeyUp},
                                                             {"text", InputEventType::kText}};
constexpr std::pair<const char*, int> kButtons[] = {{"left", 0}, {"right", 1}, {"middle", 2}};
constexpr const char* kMods[] = {"ctrl", "shift", "alt", "super"};

bool isMouse(InputEventType t) {
  return t == InputEventType::kMouseMove || t == InputEventType::kMouseDown || t == InputEventType::kMouseUp ||
         t == InputEventType::kScroll;
}
bool isButton(InputEventType t) { return t == InputEventType::kMouseDown || t == InputEventType::kMouseUp; }
bool isKey(InputEventType t) { return t == InputEventType::kKeyDown || t == InputEventType::kKeyUp; }

std::string cut(const std::string& s) { return s.size() > 40 ? s.substr(0, 40) + "..." : s; }

std::string keyNameList() {
  std::string list = "'A'..'Z', '0'..'9', 'F1'..'F12'";
  for (std::size_t i = kRunNames; i < std::size(kKeyNames); ++i) list += ", '" + std::string(kKeyNames[i]) + "'";
  return list;
}

// ---- reading ----------------------------------------------------------------------------------

double coordinate(const Json& j, const Ctx& ctx) {
  return io::numberIn(j, ctx, -kMaxInputCoordinate, kMaxInputCoordinate);
}

void readMods(const Json& j, const Ctx& ctx, InputEvent& e) {
  if (!j.is_array()) ctx.fail("expected an array of modifier names, got " + io::describe(j));
  bool* flags[] = {&e.ctrl, &e.shift, &e.alt, &e.super};
  for (std::size_t i = 0; i < j.size(); ++i) {
    const Ctx mctx = ctx.index(i);
    const std::string name = io::string(j[i], mctx);
    const auto it = std::find_if(std::begin(kMods), std::end(kMods), [&](const char* m) { return name == m; });
    if (it == std::end(kMods))
      mctx.fail("unknown modifier '" + cut(name) + "' (expected one of 'ctrl', 'shift', 'alt', 'super')");
    bool& flag = *flags[it - std::begin(kMods)];
    if (flag) mctx.fail("modifier '" + name + "' given twice");
    flag = true;
  }
}

InputEvent readEvent(const Json& j, const Ctx& ctx) {
  if (!j.is_object()) ctx.fail("expected an object with \"frame\" and \"type\", got " + io::describe(j));
  InputEvent e;
  e.type = io::enumValue(io::required(j, "type", ctx), ctx.key("type"), kTypes);
  switch (e.type) {
    case InputEventType::kMouseMove:
      io::allowKeys(j, ctx, {"frame", "type", "x", "y", "mods"});
      break;
    case InputEventType::kMouseDown:
    case InputEventType::kMouseUp:
      io::allowKeys(j, ctx, {"frame", "type", "x", "y", "button", "mods"});
      break;
    case InputEventType::kScroll:
      io::allowKeys(j, ctx, {"frame", "type", "x", "y", "dx", "dy", "mods"});
      break;
    case InputEventType::kKeyDown:
    case InputEventType::kKeyUp:
      io::allowKeys(j, ctx, {"frame", "type", "key", "mods"});
      break;
    case InputEventType::kText:
      io::allowKeys(j, ctx, {"frame", "type", "text"});
      break;
  }
  e.frame = static_cast<int>(io::integer(io::required(j, "frame", ctx), ctx.key("frame"), 0, kMaxInputFrame));
  if (isMouse(e.type)) {
    e.x = coordinate(io::required(j, "x", ctx), ctx.key("x"));
    e.y = coordinate(io::required(j, "y", ctx), ctx.key("y"));
  }
  if (isButton(e.type) && j.contains("button")) e.button = io::enumValue(j.at("button"), ctx.key("button"), kButtons);
  if (e.type == InputEventType::kScroll) {
    if (j.contains("dx")) e.scroll_x = coordinate(j.at("dx"), ctx.key("dx"));
    if (j.contains("dy")) e.scroll_y = coordinate(j.at("dy"), ctx.key("dy"));
  }
  if (isKey(e.type)) {
    const Ctx kctx = ctx.key("key");
    e.key = io::string(io::required(j, "key", ctx), kctx);
    if (std::find(std::begin(kKeyNames), std::end(kKeyNames), e.key) == std::end(kKeyNames))
      kctx.fail("unknown key name '" + cut(e.key) + "' (expected one of " + keyNameList() + ")");
  }
  if (j.contains("mods")) readMods(j.at("mods"), ctx.key("mods"), e);
  if (e.type == InputEventType::kText) {
    const Ctx tctx = ctx.key("text");
    e.text = io::string(io::required(j, "text", ctx), tctx);
    if (e.text.empty() || e.text.size() > kMaxInputTextBytes)
      tctx.fail("expected 1 to " + std::to_string(kMaxInputTextBytes) + " bytes of text, got " +
                std::to_string(e.text.size()));
  }
  return e;
}

InputScript inputScriptFrom(const Json& doc, const std::string& source) {
  const Ctx ctx{source, ""};
  io::formatVersion(doc, ctx, "input event files", kInputScriptVersion, kInputScriptVersion,
                    /*missing=*/kInputScriptVersion);
  io::allowKeys(doc, ctx, {"version", "window", "events"});
  InputScript script;
  if (doc.contains("window")) {
    const Json& w = doc.at("window");
    const Ctx wctx = ctx.key("window");
    if (!w.is_array() || w.size() != 2) wctx.fail("expected [width, height] in pixels, got " + io::describe(w));
    std::array<int, 2> size{};
    for (std::size_t a = 0; a < 2; ++a)
      size[a] = static_cast<int>(io::integer(w[a], wctx.index(a), 1, kMaxInputWindowSide));
    script.window = size;
  }
  const Json& events = io::required(doc, "events", ctx);
  const Ctx ectx = ctx.key("events");
  if (!events.is_array()) ectx.fail("expected an array of events, got " + io::describe(events));
  if (events.size() > kMaxInputEvents)
    ectx.fail("holds " + std::to_string(events.size()) + " events, more than the limit of " +
              std::to_string(kMaxInputEvents));
  script.events.reserve(events.size());
  for (std::size_t i = 0; i < events.size(); ++i) {
    InputEvent e = readEvent(events[i], ectx.index(i));
    if (i > 0 && e.frame < script.events.back().frame)
      ectx.index(i).key("frame").fail("frames must not decrease: got " + std::to_string(e.frame) + " after " +
                                      std::to_string(script.events.back().frame));
    script.events.push_back(std::move(e));
  }
  return script;
}

// ---- writing ----------------------------------------------------------------------------------

OJson eventJson(const InputEvent& e) {
  OJson j;
  j["frame"] = e.frame;
  j["type"] = inputEventTypeName(e.type);
  if (isMouse(e.type)) {
    j["x"] = e.x;
    j["y"] = e.y;
  }
  if (isButton(e.type)) {
    // An out-of-range button is written as its number, which the read-back check refuses.
    if (e.button >= 0 && e.button < static_cast<int>(std::size(kButtons)))
      j["button"] = kButtons[e.button].first;
    else
      j["button"] = e.button;
  }
  if (e.type == InputEventType::kScroll) {
    j["dx"] = e.scroll_x;
    j["dy"] = e.scroll_y;
  }
  if (isKey(e.type)) j["key"] = e.key;
  if (e.type != InputEventType::kText && (e.ctrl || e.shift || e.alt || e.super)) {
    OJson mods = OJson::array();
    const bool flags[] = {e.ctrl, e.shift, e.alt, e.super};
    for (std::size_t m = 0; m < std::size(kMods); ++m)
      if (flags[m]) mods.push_back(kMods[m]);
    j["mods"] = std::move(mods);
  }
  if (e.type == InputEventType::kText) j["text"] = e.text;
  return j;
}

}  // namespace

std::span<const std::string_view> inputKeyNames() { return kKeyNames; }

std::string_view inputEventTypeName(InputEventType type) {
  for (const auto& [name, t] : kTypes)
    if (t == type) return name;
  return "?";
}

InputScript parseInputScript(const std::string& text, const std::string& source) {
  return inputScriptFrom(io::parseJson(text, source), source);
}

InputScript readInputScript(const std::string& path) {
  return inputScriptFrom(io::readJsonFile(path, "input event file"), path);
}

std::string formatInputScript(const InputScript& script) {
  const std::string where = "input events";
  std::string text = "{\n  \"version\": " + std::to_string(kInputScriptVersion) + ",\n";
  if (script.window)
    text +=
        "  \"window\": [" + std::to_string((*script.window)[0]) + ", " + std::to_string((*script.window)[1]) + "],\n";
  text += "  \"events\": [";
  for (std::size_t i = 0; i < script.events.size(); ++i) {
    text += i == 0 ? "\n    " : ",\n    ";
    try {
      text += eventJson(script.events[i]).dump();  // strict: invalid UTF-8 throws
    } catch (const OJson::exception&) {
      Ctx{where, "'events'[" + std::to_string(i) + "]"}.fail("holds a string that is not valid UTF-8");
    }
  }
  text += script.events.empty() ? "]\n}\n" : "\n  ]\n}\n";
  // The reader's rules are the only ones: what it refuses (a NaN, written as null; a frame out of
  // range or decreasing; an unknown key name) is refused here, naming the event.
  inputScriptFrom(io::parseJson(text, where), where);
  return text;
}

}  // namespace vdg
