// Input event files of vdg studio (vdg/io/studio_events.h): every event type and field, the round
// trip format -> parse on hand-written and random scripts, and one test per refusal comparing the
// whole message (it must name the key path).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <string>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/io/studio_events.h"

namespace vdg {
namespace {

using testing::errorOf;

const char* kAllTypes = R"({
  "version": 1,
  "window": [1280, 800],
  "events": [
    {"frame": 0, "type": "mouse_move", "x": 10.5, "y": -3},
    {"frame": 3, "type": "mouse_down", "button": "right", "x": 10, "y": 20, "mods": ["shift", "ctrl"]},
    {"frame": 3, "type": "mouse_up", "x": 11, "y": 21},
    {"frame": 4, "type": "scroll", "x": 1, "y": 2, "dx": -0.5, "dy": 2},
    {"frame": 5, "type": "key_down", "key": "F12", "mods": ["super", "alt"]},
    {"frame": 5, "type": "key_up", "key": "LeftBracket"},
    {"frame": 9, "type": "text", "text": "k\u00e9y \u2713"}
  ]})";

TEST(StudioEvents, ReadsEveryEventType) {
  const InputScript s = parseInputScript(kAllTypes, "EV.json");
  ASSERT_TRUE(s.window.has_value());
  EXPECT_EQ(*s.window, (std::array<int, 2>{1280, 800}));
  ASSERT_EQ(s.events.size(), 7u);
  EXPECT_EQ(s.events[0].type, InputEventType::kMouseMove);
  EXPECT_EQ(s.events[0].x, 10.5);
  EXPECT_EQ(s.events[0].y, -3.0);
  EXPECT_EQ(s.events[1].type, InputEventType::kMouseDown);
  EXPECT_EQ(s.events[1].frame, 3);
  EXPECT_EQ(s.events[1].button, 1);
  EXPECT_TRUE(s.events[1].ctrl && s.events[1].shift);
  EXPECT_FALSE(s.events[1].alt || s.events[1].super);
  EXPECT_EQ(s.events[2].type, InputEventType::kMouseUp);
  EXPECT_EQ(s.events[2].button, 0);  // left by default
  EXPECT_EQ(s.events[3].type, InputEventType::kScroll);
  EXPECT_EQ(s.events[3].scroll_x, -0.5);
  EXPECT_EQ(s.events[3].scroll_y, 2.0);
  EXPECT_EQ(s.events[4].type, InputEventType::kKeyDown);
  EXPECT_EQ(s.events[4].key, "F12");
  EXPECT_TRUE(s.events[4].alt && s.events[4].super);
  EXPECT_EQ(s.events[5].type, InputEventType::kKeyUp);
  EXPECT_EQ(s.events[5].key, "LeftBracket");
  EXPECT_EQ(s.events[6].type, InputEventType::kText);
  EXPECT_EQ(s.events[6].text, "k\xc3\xa9y \xe2\x9c\x93");
}

TEST(StudioEvents, OptionalFieldsAndEmptyLists) {
  const InputScript s = parseInputScript(R"({"events": []})", "EV.json");  // version 1 when left out
  EXPECT_FALSE(s.window.has_value());
  EXPECT_TRUE(s.events.empty());
  const InputScript scroll = parseInputScript(R"({"events": [{"frame": 2, "type": "scroll", "x": 0, "y": 0}]})", "e");
  EXPECT_EQ(scroll.events.at(0).scroll_x, 0.0);
  EXPECT_EQ(scroll.events.at(0).scroll_y, 0.0);
  const InputScript no_mods =
      parseInputScript(R"({"events": [{"frame": 0, "type": "key_up", "key": "A", "mods": []}]})", "e");
  EXPECT_EQ(no_mods.events.at(0), (InputEvent{.frame = 0, .type = InputEventType::kKeyUp, .key = "A"}));
  // The empty script round-trips too, with and without a window.
  for (const InputScript& empty : {InputScript{}, InputScript{std::array<int, 2>{1, 1}, {}}})
    EXPECT_EQ(parseInputScript(formatInputScript(empty), "f"), empty);
}

TEST(StudioEvents, EveryKeyNameIsAcceptedAndDistinct) {
  const auto names = inputKeyNames();
  EXPECT_EQ(names.size(), 26u + 10u + 12u + 18u);
  EXPECT_EQ(std::set<std::string_view>(names.begin(), names.end()).size(), names.size());
  EXPECT_EQ(names.front(), "A");
  EXPECT_EQ(names.back(), "RightBracket");
  for (const std::string_view name : names) {
    const std::string text = R"({"events": [{"frame": 1, "type": "key_down", "key": ")" + std::string(name) + "\"}]}";
    EXPECT_EQ(parseInputScript(text, "e").events.at(0).key, name);
  }
}

TEST(StudioEvents, HandWrittenFileRoundTrips) {
  const InputScript s = parseInputScript(kAllTypes, "EV.json");
  const std::string text = formatInputScript(s);
  EXPECT_EQ(parseInputScript(text, "again"), s);
  EXPECT_EQ(formatInputScript(parseInputScript(text, "again")), text);  // a fixed point
  // One event per line, its type's fields only.
  EXPECT_NE(text.find("\n    {\"frame\":0,\"type\":\"mouse_move\",\"x\":10.5,\"y\":-3.0},\n"), std::string::npos)
      << text;
  EXPECT_NE(text.find("{\"frame\":5,\"type\":\"key_down\",\"key\":\"F12\",\"mods\":[\"alt\",\"super\"]}"),
            std::string::npos)
      << text;
}

// A random event of a random type, with only its type's fields set.
InputEvent randomEvent(std::mt19937_64& rng, int frame) {
  std::uniform_int_distribution<int> type_of(0, 6), bit(0, 1), button_of(0, 2);
  std::uniform_real_distribution<double> coordinate(-kMaxInputCoordinate, kMaxInputCoordinate);
  std::uniform_int_distribution<std::size_t> key_of(0, inputKeyNames().size() - 1);
  // Values whose decimal form is long or odd: shortest round trip must still give them back.
  const double awkward[] = {0.1,
                            1.0 / 3.0,
                            -0.0,
                            5e-324,
                            1e-300,
                            2.2250738585072014e-308,
                            kMaxInputCoordinate,
                            -kMaxInputCoordinate,
                            123456.78901234567,
                            std::nextafter(1.0, 2.0)};
  auto value = [&] { return bit(rng) ? coordinate(rng) : awkward[key_of(rng) % std::size(awkward)]; };
  InputEvent e;
  e.frame = frame;
  e.type = static_cast<InputEventType>(type_of(rng));
  switch (e.type) {
    case InputEventType::kScroll:
      e.scroll_x = value();
      e.scroll_y = value();
      [[fallthrough]];
    case InputEventType::kMouseMove:
      e.x = value();
      e.y = value();
      break;
    case InputEventType::kMouseDown:
    case InputEventType::kMouseUp:
      e.x = value();
      e.y = value();
      e.button = button_of(rng);
      break;
    case InputEventType::kKeyDown:
    case InputEventType::kKeyUp:
      e.key = std::string(inputKeyNames()[key_of(rng)]);
      break;
    case InputEventType::kText: {
      // Printable ASCII, control characters (escaped in JSON), a NUL, and multi-byte UTF-8.
      const std::string pieces[] = {
          "a", "Z", " ", "\"", "\\", "\n", "\t", std::string(1, '\0'), "\xc3\xa9", "\xe2\x9c\x93", "\xf0\x9f\x99\x82"};
      const int n = 1 + static_cast<int>(key_of(rng) % 12);
      for (int i = 0; i < n; ++i) e.text += pieces[key_of(rng) % std::size(pieces)];
      break;
    }
  }
  if (e.type != InputEventType::kText) {
    e.ctrl = bit(rng);
    e.shift = bit(rng);
    e.alt = bit(rng);
    e.super = bit(rng);
  }
  return e;
}

TEST(StudioEvents, RandomScriptsRoundTripExactly) {
  constexpr int kScripts = 40;
  constexpr int kEventsPerScript = 120;
  std::mt19937_64 rng(1313);
  std::uniform_int_distribution<int> step(0, 3), side(1, kMaxInputWindowSide);
  for (int n = 0; n < kScripts; ++n) {
    InputScript s;
    if (n % 3 != 0) s.window = std::array<int, 2>{side(rng), side(rng)};
    int frame = n == 1 ? kMaxInputFrame - 2 * kEventsPerScript : 0;
    for (int i = 0; i < kEventsPerScript; ++i) s.events.push_back(randomEvent(rng, frame += step(rng)));
    const std::string text = formatInputScript(s);
    const InputScript back = parseInputScript(text, "random");
    ASSERT_EQ(back, s) << text;
    // -0.0 == 0.0: check the sign bits survive too.
    for (std::size_t i = 0; i < s.events.size(); ++i)
      ASSERT_EQ(std::signbit(back.events[i].x), std::signbit(s.events[i].x)) << i;
  }
}

TEST(StudioEvents, ReadsFiles) {
  testing::TempDir dir;
  const InputScript s = parseInputScript(kAllTypes, "EV.json");
  testing::writeText(dir.file("ev.json"), formatInputScript(s));
  EXPECT_EQ(readInputScript(dir.file("ev.json")), s);
  EXPECT_EQ(errorOf([&] { readInputScript(dir.file("missing.json")); }).rfind(dir.file("missing.json") + ": ", 0), 0u);
  testing::writeText(dir.file("bad.json"), R"({"events": [{"frame": 0, "type": "text"}]})");
  EXPECT_EQ(errorOf([&] { readInputScript(dir.file("bad.json")); }),
            dir.file("bad.json") + ": 'events'[0]: missing key 'text'");
}

// Each refusal names the source and the key path of the offending value.
TEST(StudioEvents, EveryRefusalNamesItsKeyPath) {
  struct Case {
    std::string events;  // the "events" array, or a whole document when it starts with '{'
    std::string message;
  };
  const std::string keys =
      "'A'..'Z', '0'..'9', 'F1'..'F12', 'Escape', 'Enter', 'Tab', 'Backspace', 'Delete', 'Space', 'Left', "
      "'Right', 'Up', 'Down', 'Home', 'End', 'PageUp', 'PageDown', 'Minus', 'Equal', 'LeftBracket', "
      "'RightBracket'";
  const std::string ok = R"({"frame": 0, "type": "mouse_move", "x": 0, "y": 0})";
  const Case cases[] = {
      {R"({"version": 2, "events": []})", "EV.json: 'version': this vdg reads input event files version 1, got 2"},
      {R"([])", "EV.json: expected a JSON object at the top level, got an array of 0 items"},
      {R"({"version": 1})", "EV.json: missing key 'events'"},
      {R"({"events": [], "speed": 2})", "EV.json: unknown key 'speed' (expected one of 'version', 'window', 'events')"},
      {R"({"events": {}})", "EV.json: 'events': expected an array of events, got an object"},
      {R"({"window": [0, 800], "events": []})", "EV.json: 'window'[0]: expected an integer from 1 to 65536, got 0"},
      {R"({"window": [800], "events": []})",
       "EV.json: 'window': expected [width, height] in pixels, got an array of 1 item"},
      {R"({"window": [800, 600.5], "events": []})",
       "EV.json: 'window'[1]: expected an integer from 1 to 65536, got the number 600.5"},
      {"[" + ok + ", 7]", "EV.json: 'events'[1]: expected an object with \"frame\" and \"type\", got the number 7"},
      {R"([{"frame": 0, "x": 1, "y": 2}])", "EV.json: 'events'[0]: missing key 'type'"},
      {R"([{"frame": 0, "type": "mouse_drag", "x": 1, "y": 2}])",
       "EV.json: 'events'[0].'type': unknown value 'mouse_drag' (expected one of 'mouse_move', 'mouse_down', "
       "'mouse_up', 'scroll', 'key_down', 'key_up', 'text')"},
      {R"([{"type": "mouse_move", "x": 1, "y": 2}])", "EV.json: 'events'[0]: missing key 'frame'"},
      {R"([{"frame": -1, "type": "mouse_move", "x": 1, "y": 2}])",
       "EV.json: 'events'[0].'frame': expected an integer from 0 to 10000000, got -1"},
      {R"([{"frame": 10000001, "type": "mouse_move", "x": 1, "y": 2}])",
       "EV.json: 'events'[0].'frame': expected an integer from 0 to 10000000, got 10000001"},
      {R"([{"frame": 1.5, "type": "mouse_move", "x": 1, "y": 2}])",
       "EV.json: 'events'[0].'frame': expected an integer from 0 to 10000000, got the number 1.5"},
      {R"([{"frame": 5, "type": "key_down", "key": "A"}, {"frame": 5, "type": "key_up", "key": "A"},
           {"frame": 4, "type": "key_down", "key": "B"}])",
       "EV.json: 'events'[2].'frame': frames must not decrease: got 4 after 5"},
      {R"([{"frame": 0, "type": "mouse_move", "y": 2}])", "EV.json: 'events'[0]: missing key 'x'"},
      {R"([{"frame": 0, "type": "mouse_down", "x": 2}])", "EV.json: 'events'[0]: missing key 'y'"},
      {R"([{"frame": 0, "type": "scroll", "dy": 2}])", "EV.json: 'events'[0]: missing key 'x'"},
      {R"([{"frame": 0, "type": "mouse_move", "x": "10", "y": 2}])",
       "EV.json: 'events'[0].'x': expected a number, got the string \"10\""},
      {"[" + ok + ", " + ok + ", " + ok + R"(, {"frame": 0, "type": "mouse_move", "x": 1e7, "y": 2}])",
       "EV.json: 'events'[3].'x': expected a number from -1000000 to 1000000, got 10000000"},
      {R"([{"frame": 0, "type": "mouse_up", "x": 0, "y": -1000000.5}])",
       "EV.json: 'events'[0].'y': expected a number from -1000000 to 1000000, got -1000000.5"},
      {R"([{"frame": 0, "type": "scroll", "x": 0, "y": 0, "dx": 2e6}])",
       "EV.json: 'events'[0].'dx': expected a number from -1000000 to 1000000, got 2000000"},
      {R"([{"frame": 0, "type": "scroll", "x": 0, "y": 0, "dy": null}])",
       "EV.json: 'events'[0].'dy': expected a number, got null"},
      {R"([{"frame": 0, "type": "mouse_move", "x": 0, "y": 0, "button": "left"}])",
       "EV.json: 'events'[0]: unknown key 'button' (expected one of 'frame', 'type', 'x', 'y', 'mods')"},
      {R"([{"frame": 0, "type": "mouse_down", "x": 0, "y": 0, "button": "back"}])",
       "EV.json: 'events'[0].'button': unknown value 'back' (expected one of 'left', 'right', 'middle')"},
      {R"([{"frame": 0, "type": "mouse_down", "x": 0, "y": 0, "button": 1}])",
       "EV.json: 'events'[0].'button': expected a string, got the number 1"},
      {R"([{"frame": 0, "type": "key_down", "key": "A", "x": 3}])",
       "EV.json: 'events'[0]: unknown key 'x' (expected one of 'frame', 'type', 'key', 'mods')"},
      {R"([{"frame": 0, "type": "key_down"}])", "EV.json: 'events'[0]: missing key 'key'"},
      {R"([{"frame": 0, "type": "key_up", "key": "a"}])",
       "EV.json: 'events'[0].'key': unknown key name 'a' (expected one of " + keys + ")"},
      {R"([{"frame": 0, "type": "key_up", "key": ""}])",
       "EV.json: 'events'[0].'key': unknown key name '' (expected one of " + keys + ")"},
      {R"([{"frame": 0, "type": "key_down", "key": "A", "mods": "ctrl"}])",
       "EV.json: 'events'[0].'mods': expected an array of modifier names, got the string \"ctrl\""},
      {R"([{"frame": 0, "type": "key_down", "key": "A", "mods": ["ctrl", "meta"]}])",
       "EV.json: 'events'[0].'mods'[1]: unknown modifier 'meta' (expected one of 'ctrl', 'shift', 'alt', 'super')"},
      {R"([{"frame": 0, "type": "key_down", "key": "A", "mods": ["alt", "alt"]}])",
       "EV.json: 'events'[0].'mods'[1]: modifier 'alt' given twice"},
      {R"([{"frame": 0, "type": "key_down", "key": "A", "mods": [true]}])",
       "EV.json: 'events'[0].'mods'[0]: expected a string, got true"},
      {R"([{"frame": 0, "type": "text"}])", "EV.json: 'events'[0]: missing key 'text'"},
      {R"([{"frame": 0, "type": "text", "text": ""}])",
       "EV.json: 'events'[0].'text': expected 1 to 4096 bytes of text, got 0"},
      {R"([{"frame": 0, "type": "text", "text": ")" + std::string(kMaxInputTextBytes + 1, 'x') + "\"}]",
       "EV.json: 'events'[0].'text': expected 1 to 4096 bytes of text, got 4097"},
      {R"([{"frame": 0, "type": "text", "text": "a", "mods": ["ctrl"]}])",
       "EV.json: 'events'[0]: unknown key 'mods' (expected one of 'frame', 'type', 'text')"},
  };
  for (const Case& c : cases) {
    const std::string text = c.events.starts_with("{") ? c.events : R"({"version": 1, "events": )" + c.events + "}";
    EXPECT_EQ(errorOf([&] { parseInputScript(text, "EV.json"); }), c.message) << text;
  }
  // The longest text and the last frame are accepted.
  const std::string longest =
      R"({"events": [{"frame": 10000000, "type": "text", "text": ")" + std::string(kMaxInputTextBytes, 'x') + "\"}]}";
  EXPECT_EQ(parseInputScript(longest, "e").events.at(0).text.size(), kMaxInputTextBytes);
}

TEST(StudioEvents, RefusesTooManyEventsBeforeReadingThem) {
  std::string text = R"({"events": [)";
  for (std::size_t i = 0; i <= kMaxInputEvents; ++i) text += i == 0 ? "0" : ",0";
  text += "]}";
  EXPECT_EQ(errorOf([&] { parseInputScript(text, "EV.json"); }),
            "EV.json: 'events': holds 1000001 events, more than the limit of 1000000");
}

TEST(StudioEvents, RefusesBadJsonAndDeepNesting) {
  EXPECT_EQ(errorOf([&] { parseInputScript(R"({"events": [)", "EV.json"); }).rfind("EV.json: not valid JSON at ", 0),
            0u);
  const std::string deep = R"({"events": )" + std::string(100, '[') + std::string(100, ']') + "}";
  EXPECT_EQ(errorOf([&] { parseInputScript(deep, "EV.json"); }).rfind("EV.json: JSON nested deeper than 64 levels", 0),
            0u);
}

// The writer refuses what the reader would refuse, naming the event.
TEST(StudioEvents, FormatRefusesScriptsItCouldNotReadBack) {
  auto refusal = [](InputEvent e, std::optional<InputEvent> before = std::nullopt) {
    InputScript s;
    if (before) s.events.push_back(*before);
    s.events.push_back(std::move(e));
    return errorOf([&] { formatInputScript(s); });
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(refusal({.x = nan}), "input events: 'events'[0].'x': expected a number, got null");
  EXPECT_EQ(refusal({.type = InputEventType::kScroll, .scroll_y = std::numeric_limits<double>::infinity()}),
            "input events: 'events'[0].'dy': expected a number, got null");
  EXPECT_EQ(refusal({.y = 1e7}),
            "input events: 'events'[0].'y': expected a number from -1000000 to 1000000, got 10000000");
  EXPECT_EQ(refusal({.frame = 2}, InputEvent{.frame = 3}),
            "input events: 'events'[1].'frame': frames must not decrease: got 2 after 3");
  EXPECT_EQ(refusal({.frame = -1}),
            "input events: 'events'[0].'frame': expected an integer from 0 to 10000000, got -1");
  EXPECT_EQ(refusal({.type = InputEventType::kMouseDown, .button = 3}),
            "input events: 'events'[0].'button': expected a string, got the number 3");
  EXPECT_EQ(refusal({.type = InputEventType::kKeyDown, .key = "Ctrl"})
                .rfind("input events: 'events'[0].'key': unknown key name 'Ctrl' (expected one of 'A'..'Z'", 0),
            0u);
  EXPECT_EQ(refusal({.type = InputEventType::kText, .text = ""}),
            "input events: 'events'[0].'text': expected 1 to 4096 bytes of text, got 0");
  EXPECT_EQ(refusal({.type = InputEventType::kText, .text = "ab\xff"}),
            "input events: 'events'[0]: holds a string that is not valid UTF-8");
  InputScript window;
  window.window = std::array<int, 2>{0, 10};
  EXPECT_EQ(errorOf([&] { formatInputScript(window); }),
            "input events: 'window'[0]: expected an integer from 1 to 65536, got 0");
}

}  // namespace
}  // namespace vdg
