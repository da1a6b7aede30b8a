// Recorded input of `vdg studio`: the events `--record EVENTS.json` writes and `--replay
// EVENTS.json` feeds to the window, frame by frame (docs/studio-files.md):
//   {"version": 1, "window": [1280, 800],
//    "events": [{"frame": 3, "type": "mouse_down", "button": "left", "x": 10, "y": 20}, ...]}
//
// Each event type has its own fields; any other key is an error (usually a typo):
//   mouse_move                 x, y, mods
//   mouse_down, mouse_up       x, y, button ("left" default, "right", "middle"), mods
//   scroll                     x, y, dx, dy (default 0), mods
//   key_down, key_up           key (a name from inputKeyNames()), mods
//   text                       text (UTF-8, 1 to kMaxInputTextBytes bytes)
// Every event has "frame" (required) and "type" (required). "mods" is a list of distinct names from
// "ctrl", "shift", "alt", "super" (default none). "version" may be left out (read as 1).
//
// Messages name the source, then the key path: "EVENTS.json: 'events'[3].'x': expected a number
// from -1000000 to 1000000, got 1e+07".
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace vdg {

// Current version of the input event file format.
inline constexpr int kInputScriptVersion = 1;
// Limits of an input event file (a file beyond them is refused with a message naming the limit).
inline constexpr std::size_t kMaxInputEvents = 1'000'000;
inline constexpr int kMaxInputFrame = 10'000'000;
inline constexpr std::size_t kMaxInputTextBytes = 4096;
inline constexpr double kMaxInputCoordinate = 1e6;   // |x|, |y|, |dx|, |dy| (window pixels, scroll steps)
inline constexpr int kMaxInputWindowSide = 1 << 16;  // "window" sides, pixels (1 to this)

enum class InputEventType { kMouseMove, kMouseDown, kMouseUp, kScroll, kKeyDown, kKeyUp, kText };

struct InputEvent {
  int frame = 0;  // frame number at which the event is delivered, 0..kMaxInputFrame, non-decreasing
  InputEventType type = InputEventType::kMouseMove;
  double x = 0, y = 0;                // window pixels, y down (mouse and scroll events; finite, |v| <= 1e6)
  int button = 0;                     // kMouseDown/kMouseUp: 0 left, 1 right, 2 middle (JSON "left"/"right"/"middle")
  double scroll_x = 0, scroll_y = 0;  // kScroll (JSON "dx"/"dy"; finite, |v| <= 1e6)
  std::string key;                    // kKeyDown/kKeyUp: a name from inputKeyNames()
  bool ctrl = false, shift = false, alt = false, super = false;  // JSON "mods": ["ctrl", ...]
  std::string text;  // kText: UTF-8 typed into the focused text field, 1..kMaxInputTextBytes bytes

  bool operator==(const InputEvent&) const = default;
};

struct InputScript {
  std::optional<std::array<int, 2>> window;  // window size the events were recorded in (pixels)
  std::vector<InputEvent> events;            // in delivery order (frames non-decreasing); may be empty

  bool operator==(const InputScript&) const = default;
};

// The key names events may use, in a fixed order: "A".."Z", "0".."9", "F1".."F12", "Escape",
// "Enter", "Tab", "Backspace", "Delete", "Space", "Left", "Right", "Up", "Down", "Home", "End",
// "PageUp", "PageDown", "Minus", "Equal", "LeftBracket", "RightBracket". Names are case-sensitive.
std::span<const std::string_view> inputKeyNames();
// The JSON name of an event type ("mouse_move", ..., "text").
std::string_view inputEventTypeName(InputEventType type);

// Parses an input event file's text. Throws vdg::Error "SOURCE: KEY PATH: PROBLEM" (one line) for
// bad JSON, nesting deeper than the JSON layer allows, an unknown version, unknown keys, a missing
// or wrong-typed field, an unknown type/key/modifier/button (the message lists the allowed ones),
// a value out of range, frames that decrease, or more than kMaxInputEvents events.
InputScript parseInputScript(const std::string& text, const std::string& source);
// Reads `path` (a regular file of at most kMaxJsonFileBytes, vdg/io/read_file.h) and parses it.
InputScript readInputScript(const std::string& path);
// The file's text: version, window (when set), then one event per line with only its type's fields
// (fields of other types are not written), doubles in their shortest exact form.
// parseInputScript(formatInputScript(s)) == s for every script whose events set only their type's
// fields (every script parseInputScript returns). Throws vdg::Error naming the event ("input
// events: 'events'[3].'x': ...") for a script the parser would refuse.
std::string formatInputScript(const InputScript& script);

}  // namespace vdg
