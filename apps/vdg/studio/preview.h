// The Preview panel of `vdg studio` (Rademacher 99, Figure 6): the view-dependent model built
// from the session's keys, seen by a camera turning about it (left) and, from the same blend, by a
// fixed observer (right, vdg::render::FrameOptions::observer), with the weights of the active
// keys, the sharpness (3.2.2) and the uncovered-region mode; for an animated model (section 4) a
// timeline scrubs its frames and shows each key at its (frame, view). A static model whose keys
// carry reference drawings can show them as view-dependent textures (docs/drawing-textures.md).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "vdg/viewdep/model.h"
#include "window.h"

namespace vdg::studio::app {

class Preview {
 public:
  Preview();
  ~Preview();
  // Draws the panel's contents (inside an ImGui window the caller opened). Rebuilds the model
  // when `revision` changed; `frame` turns the camera. `window`'s context is made current again
  // after the preview's renderer (its own EGL context) has drawn.
  void draw(Window& window, const RawViewDependentModel& raw, std::uint64_t revision, int frame);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vdg::studio::app
