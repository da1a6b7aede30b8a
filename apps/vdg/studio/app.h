// The editor of `vdg studio`: a Session (vdg/studio/session.h) shown in a window, the authoring
// loop of Rademacher 99, section 3.1, against a drawing. Align mode turns the camera (orbit, pan,
// dolly, roll, field of view or orthographic height) or picks 2D-3D correspondences and solves
// for the camera (3.1.1); Deform mode drags, pushes/pulls, rotates and scales the key mesh across
// the image plane (3.1.2); keys are saved, re-edited from their own camera, previewed (Figure 6).
//
// The app turns studio::app::Event values (input.h; live or replayed, one path) into Session
// calls. Coordinates: window pixels (mouse, y down) -> image pixels of the drawing (or of the
// viewport when there is none) through the letterboxed viewport rectangle.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "input.h"
#include "window.h"

namespace vdg::studio::app {

struct StudioOptions {
  std::string model;
  std::string drawing;
  bool recover = false;           // --recover: re-apply autosaved strokes without asking
  bool discard_recovery = false;  // --discard-recovery: drop them without asking
};

// Width of the tool panel on the left of the window, in window pixels; the viewport takes the rest.
inline constexpr float kPanelWidth = 300.0f;

class Studio {
 public:
  // Opens the model and the drawing; a failure is kept as an error shown in the window (and
  // printed once to stderr), never thrown: the window still opens and says what is wrong.
  explicit Studio(const StudioOptions& options);
  ~Studio();

  // One frame between Window::beginFrame and Window::render: handles `events` (this frame's, in
  // order), draws the panels and the viewport. `frame` numbers frames from 0.
  void frame(Window& window, int frame, const std::vector<Event>& events);
  // True when something failed during the session (start-up, saving, recovery): exit status 1.
  bool failed() const;
  bool wantsClose() const;

  // --benchmark: median milliseconds of a viewport frame while orbiting, and of a drag step (mouse
  // move -> stroke update -> mesh drawn) over `frames` steps. Throws vdg::Error without a model.
  struct BenchmarkResult {
    double frame_ms = 0, drag_ms = 0;
    int width = 0, height = 0;
  };
  BenchmarkResult benchmark(int frames, int viewport_width, int viewport_height);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vdg::studio::app
