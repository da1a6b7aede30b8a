#include "input.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <utility>

#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/studio_events.h"

namespace vdg::studio::app {

namespace {

struct NamedKey {
  const char* name;
  int code;
};

// The key names of vdg/io/studio_events.h and their GLFW codes ("A".."Z", "0".."9" and
// "F1".."F12" are computed in keyCode()).
constexpr NamedKey kNamedKeys[] = {
    {"Escape", GLFW_KEY_ESCAPE},
    {"Enter", GLFW_KEY_ENTER},
    {"Tab", GLFW_KEY_TAB},
    {"Backspace", GLFW_KEY_BACKSPACE},
    {"Delete", GLFW_KEY_DELETE},
    {"Space", GLFW_KEY_SPACE},
    {"Left", GLFW_KEY_LEFT},
    {"Right", GLFW_KEY_RIGHT},
    {"Up", GLFW_KEY_UP},
    {"Down", GLFW_KEY_DOWN},
    {"Home", GLFW_KEY_HOME},
    {"End", GLFW_KEY_END},
    {"PageUp", GLFW_KEY_PAGE_UP},
    {"PageDown", GLFW_KEY_PAGE_DOWN},
    {"Minus", GLFW_KEY_MINUS},
    {"Equal", GLFW_KEY_EQUAL},
    {"LeftBracket", GLFW_KEY_LEFT_BRACKET},
    {"RightBracket", GLFW_KEY_RIGHT_BRACKET},
};

EventType fromFile(InputEventType t) {
  switch (t) {
    case InputEventType::kMouseMove:
      return EventType::kMouseMove;
    case InputEventType::kMouseDown:
      return EventType::kMouseDown;
    case InputEventType::kMouseUp:
      return EventType::kMouseUp;
    case InputEventType::kScroll:
      return EventType::kScroll;
    case InputEventType::kKeyDown:
      return EventType::kKeyDown;
    case InputEventType::kKeyUp:
      return EventType::kKeyUp;
    case InputEventType::kText:
      return EventType::kText;
  }
  return EventType::kMouseMove;
}
InputEventType toFile(EventType t) {
  switch (t) {
    case EventType::kMouseMove:
      return InputEventType::kMouseMove;
    case EventType::kMouseDown:
      return InputEventType::kMouseDown;
    case EventType::kMouseUp:
      return InputEventType::kMouseUp;
    case EventType::kScroll:
      return InputEventType::kScroll;
    case EventType::kKeyDown:
      return InputEventType::kKeyDown;
    case EventType::kKeyUp:
      return InputEventType::kKeyUp;
    case EventType::kText:
      return InputEventType::kText;
  }
  return InputEventType::kMouseMove;
}

}  // namespace

EventScript readEvents(const std::string& path) {
  const InputScript file = readInputScript(path);
  EventScript script;
  script.window = file.window;
  script.events.reserve(file.events.size());
  for (const InputEvent& e : file.events)
    script.events.push_back(Event{e.frame, fromFile(e.type), e.x, e.y, e.button, e.scroll_x, e.scroll_y, e.key, e.ctrl,
                                  e.shift, e.alt, e.super, e.text});
  return script;
}

void writeEvents(const std::string& path, const EventScript& script) {
  InputScript file;
  file.window = script.window;
  for (const Event& e : script.events) {
    InputEvent f;
    f.frame = e.frame;
    f.type = toFile(e.type);
    f.x = e.x;
    f.y = e.y;
    f.button = e.button;
    f.scroll_x = e.scroll_x;
    f.scroll_y = e.scroll_y;
    f.key = e.key;
    f.ctrl = e.ctrl;
    f.shift = e.shift;
    f.alt = e.alt;
    f.super = e.super;
    f.text = e.text;
    file.events.push_back(std::move(f));
  }
  writeFileAtomically(path, formatInputScript(file));
}

int keyCode(const std::string& name) {
  if (name.size() == 1 && name[0] >= 'A' && name[0] <= 'Z') return GLFW_KEY_A + (name[0] - 'A');
  if (name.size() == 1 && name[0] >= '0' && name[0] <= '9') return GLFW_KEY_0 + (name[0] - '0');
  if (name.size() >= 2 && name.size() <= 3 && name[0] == 'F') {
    int n = 0;
    for (std::size_t i = 1; i < name.size(); ++i) {
      if (name[i] < '0' || name[i] > '9') return -1;
      n = n * 10 + (name[i] - '0');
    }
    if (n >= 1 && n <= 12) return GLFW_KEY_F1 + (n - 1);
    return -1;
  }
  for (const NamedKey& k : kNamedKeys)
    if (name == k.name) return k.code;
  return -1;
}

std::string keyName(int code) {
  if (code >= GLFW_KEY_A && code <= GLFW_KEY_Z) return std::string(1, static_cast<char>('A' + (code - GLFW_KEY_A)));
  if (code >= GLFW_KEY_0 && code <= GLFW_KEY_9) return std::string(1, static_cast<char>('0' + (code - GLFW_KEY_0)));
  if (code >= GLFW_KEY_F1 && code <= GLFW_KEY_F12) return "F" + std::to_string(code - GLFW_KEY_F1 + 1);
  for (const NamedKey& k : kNamedKeys)
    if (code == k.code) return k.name;
  return "";
}

void InputState::apply(const Event& e) {
  switch (e.type) {
    case EventType::kMouseMove:
      mouse_x = e.x;
      mouse_y = e.y;
      break;
    case EventType::kMouseDown:
    case EventType::kMouseUp:
      mouse_x = e.x;
      mouse_y = e.y;
      if (e.button >= 0 && e.button < 3) buttons[static_cast<std::size_t>(e.button)] = e.type == EventType::kMouseDown;
      break;
    case EventType::kKeyDown:
    case EventType::kKeyUp: {
      const int code = keyCode(e.key);
      if (code >= 0 && code < static_cast<int>(keys.size()))
        keys[static_cast<std::size_t>(code)] = e.type == EventType::kKeyDown;
      ctrl = e.ctrl;
      shift = e.shift;
      alt = e.alt;
      super = e.super;
      break;
    }
    case EventType::kScroll:
    case EventType::kText:
      break;
  }
}

void feedImGui(const InputState& state, const std::vector<Event>& frame_events) {
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = ImVec2(static_cast<float>(state.mouse_x), static_cast<float>(state.mouse_y));
  for (int b = 0; b < 3; ++b) io.MouseDown[b] = state.buttons[static_cast<std::size_t>(b)];
  // A press and release within one frame would be lost in a held-down state: show the press.
  for (const Event& e : frame_events)
    if (e.type == EventType::kMouseDown && e.button >= 0 && e.button < 3) io.MouseDown[e.button] = true;
  for (std::size_t k = 0; k < state.keys.size(); ++k) io.KeysDown[k] = state.keys[k];
  for (const Event& e : frame_events)
    if (e.type == EventType::kKeyDown) {
      const int code = keyCode(e.key);
      if (code >= 0 && code < 512) io.KeysDown[code] = true;
    }
  io.KeyCtrl = state.ctrl;
  io.KeyShift = state.shift;
  io.KeyAlt = state.alt;
  io.KeySuper = state.super;
  io.MouseWheel = 0.0f;
  io.MouseWheelH = 0.0f;
  for (const Event& e : frame_events) {
    if (e.type == EventType::kScroll) {
      io.MouseWheel += static_cast<float>(e.scroll_y);
      io.MouseWheelH += static_cast<float>(e.scroll_x);
    } else if (e.type == EventType::kText) {
      io.AddInputCharactersUTF8(e.text.c_str());
    }
  }
}

}  // namespace vdg::studio::app
