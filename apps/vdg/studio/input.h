// Input of `vdg studio`: ONE path for live and replayed mouse and keys. The window's GLFW
// callbacks (live) and an events file (--replay, vdg/io/studio_events.h) both produce
// studio::Event values with a frame number; each frame the app takes that frame's events, folds
// them into an InputState (what is held down, where the mouse is), hands that state to Dear ImGui
// (1.86: io.MousePos, io.MouseDown[], io.KeysDown[], io.KeyCtrl ..., between the backend's
// NewFrame and ImGui::NewFrame) and runs its own shortcuts and viewport gestures on the events in
// order. While replaying, live input is ignored, so a replay gives the same session whatever the
// person at the screen does.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace vdg::studio::app {

enum class EventType { kMouseMove, kMouseDown, kMouseUp, kScroll, kKeyDown, kKeyUp, kText };

// The fields of vdg::InputEvent (vdg/io/studio_events.h), kept in the app so that the window
// code does not depend on the file format.
struct Event {
  int frame = 0;
  EventType type = EventType::kMouseMove;
  double x = 0, y = 0;  // window pixels, y down
  int button = 0;       // 0 left, 1 right, 2 middle
  double scroll_x = 0, scroll_y = 0;
  std::string key;  // "A".."Z", "0".."9", "F1".."F12", "Escape", ... (keyCode())
  bool ctrl = false, shift = false, alt = false, super = false;
  std::string text;
};

struct EventScript {
  std::optional<std::array<int, 2>> window;
  std::vector<Event> events;
};

// Reads / writes an events file through vdg/io/studio_events.h. Throws vdg::Error naming the file.
EventScript readEvents(const std::string& path);
void writeEvents(const std::string& path, const EventScript& script);

// GLFW key code of a key name, or -1; and back ("" for a key without a name).
int keyCode(const std::string& name);
std::string keyName(int glfw_key);

// What is held down and where the mouse is, after the events so far.
struct InputState {
  double mouse_x = -1e6, mouse_y = -1e6;
  std::array<bool, 3> buttons{false, false, false};
  std::array<bool, 512> keys{};
  bool ctrl = false, shift = false, alt = false, super = false;
  void apply(const Event& event);
};

// Hands `state` and this frame's scroll and text events to Dear ImGui's io (call after the
// platform backend's NewFrame and before ImGui::NewFrame).
void feedImGui(const InputState& state, const std::vector<Event>& frame_events);

}  // namespace vdg::studio::app
