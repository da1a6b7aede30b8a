#include "window.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <cstdlib>
#include <cstring>
#include <utility>

#include "vdg/geom/error.h"

namespace vdg::studio::app {

namespace {

std::string glfwLastError() {
  const char* text = nullptr;
  const int code = glfwGetError(&text);
  if (code == GLFW_NO_ERROR) return "unknown error";
  return text != nullptr ? std::string(text) : "error " + std::to_string(code);
}

bool hasDisplay() {
  const char* x = std::getenv("DISPLAY");
  const char* wl = std::getenv("WAYLAND_DISPLAY");
  return (x != nullptr && *x != '\0') || (wl != nullptr && *wl != '\0');
}

Window* self(GLFWwindow* w) { return static_cast<Window*>(glfwGetWindowUserPointer(w)); }

}  // namespace

// ---- Texture ----------------------------------------------------------------------------------

Texture::~Texture() {
  if (name_ == 0) return;
  // Renderers make their own EGL contexts current: delete in the context the texture lives in.
  if (context_ != nullptr) glfwMakeContextCurrent(static_cast<GLFWwindow*>(context_));
  glDeleteTextures(1, &name_);
}

void Texture::upload(const vdg::render::Image& image) { upload(image.width, image.height, image.rgba.data()); }

void Texture::upload(int width, int height, const std::uint8_t* rgba) {
  if (name_ == 0) {
    context_ = glfwGetCurrentContext();
    glGenTextures(1, &name_);
    glBindTexture(GL_TEXTURE_2D, name_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  glBindTexture(GL_TEXTURE_2D, name_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (width != width_ || height != height_)
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  else
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  width_ = width;
  height_ = height;
}

void* Texture::id() const { return reinterpret_cast<void*>(static_cast<std::uintptr_t>(name_)); }

// ---- Window -----------------------------------------------------------------------------------

Window::Window(int width, int height, const std::string& title) {
  if (!hasDisplay())
    throw Error("studio: no display (DISPLAY is not set); vdg studio needs a window (run it under xvfb-run for tests)");
  if (glfwInit() != GLFW_TRUE) throw Error("studio: GLFW: cannot initialise (" + glfwLastError() + ")");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_EGL_CONTEXT_API);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (window_ == nullptr) {
    const std::string why = glfwLastError();
    glfwTerminate();
    throw Error("studio: GLFW: cannot open a " + std::to_string(width) + "x" + std::to_string(height) +
                " window with an OpenGL 3.3 context (" + why + ")");
  }
  glfwSetWindowUserPointer(window_, this);
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(0);
  glfwSetKeyCallback(window_, &Window::onKey);
  glfwSetCharCallback(window_, &Window::onChar);
  glfwSetMouseButtonCallback(window_, &Window::onButton);
  glfwSetCursorPosCallback(window_, &Window::onCursor);
  glfwSetScrollCallback(window_, &Window::onScroll);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // the same layout every start (replays depend on it)
  ImGui::StyleColorsLight();
  // Our own callbacks: the backend must not feed ImGui behind the event path's back.
  ImGui_ImplGlfw_InitForOpenGL(window_, false);
  ImGui_ImplOpenGL3_Init("#version 330");
  imgui_ = true;
}

Window::~Window() {
  if (imgui_) {
    glfwMakeContextCurrent(window_);
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  if (window_ != nullptr) glfwDestroyWindow(window_);
  glfwTerminate();
}

void Window::onKey(GLFWwindow* w, int key, int /*scancode*/, int action, int mods) {
  if (action == GLFW_REPEAT) action = GLFW_PRESS;
  const std::string name = keyName(key);
  if (name.empty()) return;
  Event e;
  e.frame = self(w)->frame_;
  e.type = action == GLFW_PRESS ? EventType::kKeyDown : EventType::kKeyUp;
  e.key = name;
  e.ctrl = (mods & GLFW_MOD_CONTROL) != 0;
  e.shift = (mods & GLFW_MOD_SHIFT) != 0;
  e.alt = (mods & GLFW_MOD_ALT) != 0;
  e.super = (mods & GLFW_MOD_SUPER) != 0;
  self(w)->live_.push_back(std::move(e));
}

void Window::onChar(GLFWwindow* w, unsigned c) {
  // UTF-8 of one code point.
  std::string text;
  if (c < 0x80) {
    text += static_cast<char>(c);
  } else if (c < 0x800) {
    text += static_cast<char>(0xC0 | (c >> 6));
    text += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    text += static_cast<char>(0xE0 | (c >> 12));
    text += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    text += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x110000) {
    text += static_cast<char>(0xF0 | (c >> 18));
    text += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
    text += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    text += static_cast<char>(0x80 | (c & 0x3F));
  }
  Event e;
  e.frame = self(w)->frame_;
  e.type = EventType::kText;
  e.text = text;
  self(w)->live_.push_back(std::move(e));
}

void Window::onButton(GLFWwindow* w, int button, int action, int mods) {
  if (button < 0 || button > 2) return;
  Event e;
  e.frame = self(w)->frame_;
  e.type = action == GLFW_PRESS ? EventType::kMouseDown : EventType::kMouseUp;
  glfwGetCursorPos(w, &e.x, &e.y);
  e.button = button;  // GLFW: 0 left, 1 right, 2 middle, as the events file
  e.ctrl = (mods & GLFW_MOD_CONTROL) != 0;
  e.shift = (mods & GLFW_MOD_SHIFT) != 0;
  e.alt = (mods & GLFW_MOD_ALT) != 0;
  self(w)->live_.push_back(std::move(e));
}

void Window::onCursor(GLFWwindow* w, double x, double y) {
  Event e;
  e.frame = self(w)->frame_;
  e.type = EventType::kMouseMove;
  e.x = x;
  e.y = y;
  self(w)->live_.push_back(std::move(e));
}

void Window::onScroll(GLFWwindow* w, double dx, double dy) {
  Event e;
  e.frame = self(w)->frame_;
  e.type = EventType::kScroll;
  glfwGetCursorPos(w, &e.x, &e.y);
  e.scroll_x = dx;
  e.scroll_y = dy;
  self(w)->live_.push_back(std::move(e));
}

void Window::poll(int frame) {
  frame_ = frame;
  glfwPollEvents();
}

std::vector<Event> Window::takeLiveEvents() { return std::exchange(live_, {}); }

bool Window::shouldClose() const { return glfwWindowShouldClose(window_) != 0; }
void Window::requestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

int Window::width() const {
  int w = 0, h = 0;
  glfwGetWindowSize(window_, &w, &h);
  return w;
}
int Window::height() const {
  int w = 0, h = 0;
  glfwGetWindowSize(window_, &w, &h);
  return h;
}

void Window::makeCurrent() { glfwMakeContextCurrent(window_); }

void Window::beginFrame(const InputState& state, const std::vector<Event>& events) {
  makeCurrent();
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  feedImGui(state, events);
  ImGui::NewFrame();
}

void Window::render() {
  ImGui::Render();
  makeCurrent();
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window_, &fw, &fh);
  glViewport(0, 0, fw, fh);
  glClearColor(0.86f, 0.86f, 0.84f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

vdg::render::Image Window::readFramebuffer() {
  makeCurrent();
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window_, &fw, &fh);
  vdg::render::Image image;
  image.width = fw;
  image.height = fh;
  image.rgba.assign(static_cast<std::size_t>(fw) * static_cast<std::size_t>(fh) * 4, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, fw, fh, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  // OpenGL's rows start at the bottom; images start at the top.
  const std::size_t row = static_cast<std::size_t>(fw) * 4;
  std::vector<std::uint8_t> tmp(row);
  for (int y = 0; y < fh / 2; ++y) {
    std::uint8_t* a = image.rgba.data() + static_cast<std::size_t>(y) * row;
    std::uint8_t* b = image.rgba.data() + static_cast<std::size_t>(fh - 1 - y) * row;
    std::memcpy(tmp.data(), a, row);
    std::memcpy(a, b, row);
    std::memcpy(b, tmp.data(), row);
  }
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
  return image;
}

void Window::present() { glfwSwapBuffers(window_); }

}  // namespace vdg::studio::app
