// The window of `vdg studio`: GLFW (its OpenGL 3.3 core context made through EGL, so that it and
// the vdg::render::Renderer contexts live in one EGL display) and Dear ImGui with its GLFW and
// OpenGL 3 backends. Live input goes to a queue of studio::app::Event (input.h), never straight
// to ImGui: the app feeds ImGui from that queue or from a replayed script, one path for both.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "input.h"
#include "vdg/render/image.h"

struct GLFWwindow;

namespace vdg::studio::app {

// An RGBA8 texture of the window's context, for ImGui::Image and draw lists.
class Texture {
 public:
  Texture() = default;
  ~Texture();
  Texture(const Texture&) = delete;
  Texture& operator=(const Texture&) = delete;
  // Uploads `image` (top row first); the window's context must be current (the first upload
  // ties the texture to it).
  void upload(const vdg::render::Image& image);
  void upload(int width, int height, const std::uint8_t* rgba);
  void* id() const;  // for ImGui (ImTextureID)
  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return name_ == 0; }

 private:
  unsigned name_ = 0;
  void* context_ = nullptr;  // the GLFWwindow whose context holds the texture
  int width_ = 0, height_ = 0;
};

class Window {
 public:
  // Opens a width x height window titled `title` and sets up ImGui. Throws vdg::Error with one
  // line: "studio: no display ..." without DISPLAY/WAYLAND_DISPLAY, "studio: GLFW: ..." when GLFW
  // cannot make the window or its context.
  Window(int width, int height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  // Polls GLFW; live input lands in the queue (taken by takeLiveEvents) stamped with `frame`.
  void poll(int frame);
  std::vector<Event> takeLiveEvents();
  bool shouldClose() const;
  void requestClose();
  int width() const;  // window size in screen coordinates (= mouse coordinates)
  int height() const;

  // Starts an ImGui frame: backends' NewFrame, then `state` and `events` fed to ImGui, then
  // ImGui::NewFrame.
  void beginFrame(const InputState& state, const std::vector<Event>& events);
  // Makes the window's context current, clears, renders ImGui's draw data.
  void render();
  // The framebuffer as it is now (after render(), before present()), top row first.
  vdg::render::Image readFramebuffer();
  void present();
  void makeCurrent();

 private:
  GLFWwindow* window_ = nullptr;
  int frame_ = 0;
  std::vector<Event> live_;
  bool imgui_ = false;
  static void onKey(GLFWwindow* w, int key, int scancode, int action, int mods);
  static void onChar(GLFWwindow* w, unsigned codepoint);
  static void onButton(GLFWwindow* w, int button, int action, int mods);
  static void onCursor(GLFWwindow* w, double x, double y);
  static void onScroll(GLFWwindow* w, double dx, double dy);
};

}  // namespace vdg::studio::app
