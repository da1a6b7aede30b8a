// The studio's timeline for an animated model (Rademacher 99, section 4: keys at (frame, view)):
// a frame slider that poses the base, a strip marking the frames that have keys (click one to go
// there), and the keys of the frame shown with a button that jumps to each (its frame and view).
// It draws and reports what the artist asked for; the app makes the Session calls.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "vdg/studio/session.h"

namespace vdg::studio::app {

struct TimelineRequest {
  std::optional<int> frame;        // go to this frame (Session::setFrame)
  std::optional<std::size_t> key;  // edit this key: its frame and view (Session::editKey)
};

// Draws the "Timeline" section into the current ImGui window (nothing for a static model).
TimelineRequest drawTimeline(const Session& session);

// Keyboard: Left/Right step one frame, LeftBracket/RightBracket jump to the previous/next frame
// that has keys (wrapping round). Nothing for another key or a static model.
std::optional<int> timelineShortcut(const Session& session, const std::string& key);

}  // namespace vdg::studio::app
