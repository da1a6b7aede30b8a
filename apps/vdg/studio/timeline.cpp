// The studio's timeline (see timeline.h).
#include "timeline.h"

#include <imgui.h>

#include <algorithm>
#include <string>
#include <vector>

namespace vdg::studio::app {
namespace {

constexpr float kStripHeight = 22.0f;
constexpr float kMarkHalfWidth = 4.0f;

// The strip: the frames 0..N-1 left to right, a mark at each frame with keys (filled when it is the
// frame shown), the frame shown as a line. Returns the frame of a mark clicked.
std::optional<int> keyStrip(const Session& session) {
  const int frames = session.frameCount();
  const std::vector<int> keyed = session.keyFrames();
  const float width = ImGui::GetContentRegionAvail().x;
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##strip", ImVec2(width, kStripHeight));
  const bool clicked = ImGui::IsItemClicked();
  const float mouse_x = ImGui::GetIO().MousePos.x;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const auto xOf = [&](int f) {
    return origin.x + kMarkHalfWidth +
           (width - 2 * kMarkHalfWidth) * static_cast<float>(f) / static_cast<float>(std::max(1, frames - 1));
  };
  dl->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + kStripHeight), IM_COL32(60, 60, 64, 255));
  const float now = xOf(session.frame());
  dl->AddLine(ImVec2(now, origin.y), ImVec2(now, origin.y + kStripHeight), IM_COL32(250, 200, 60, 255), 2.0f);
  std::optional<int> hit;
  for (const int f : keyed) {
    const float x = xOf(f);
    const ImVec2 a(x - kMarkHalfWidth, origin.y + 4), b(x + kMarkHalfWidth, origin.y + kStripHeight - 4);
    if (f == session.frame())
      dl->AddRectFilled(a, b, IM_COL32(90, 200, 250, 255));
    else
      dl->AddRect(a, b, IM_COL32(90, 200, 250, 255), 0.0f, 0, 2.0f);
    if (clicked && mouse_x >= a.x - 2 && mouse_x <= b.x + 2) hit = f;
    if (ImGui::IsItemHovered() && mouse_x >= a.x - 2 && mouse_x <= b.x + 2) ImGui::SetTooltip("keys at frame %d", f);
  }
  return hit;
}

}  // namespace

TimelineRequest drawTimeline(const Session& session) {
  TimelineRequest request;
  if (!session.animated() || !ImGui::CollapsingHeader("Timeline (section 4)", ImGuiTreeNodeFlags_DefaultOpen))
    return request;
  int frame = session.frame();
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x - 60);
  if (ImGui::SliderInt("frame", &frame, 0, session.frameCount() - 1)) request.frame = frame;
  if (const auto f = keyStrip(session)) request.frame = *f;
  // The keys of the frame shown, each a jump to its (frame, view).
  const auto& keys = session.model().keys;
  bool any = false;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (keys[i].frame != session.frame()) continue;
    any = true;
    ImGui::PushID(static_cast<int>(i));
    const bool current = static_cast<int>(i) == session.currentKey();
    if (ImGui::SmallButton((std::string(current ? "> " : "") + keys[i].name).c_str())) request.key = i;
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("edit key '%s' at frame %d from its view", keys[i].name.c_str(), keys[i].frame);
    ImGui::SameLine();
    ImGui::PopID();
  }
  if (any)
    ImGui::NewLine();
  else
    ImGui::TextDisabled("no key at frame %d: a stroke makes one", session.frame());
  ImGui::TextDisabled("Left/Right: frame, [ ]: key frames");
  return request;
}

std::optional<int> timelineShortcut(const Session& session, const std::string& key) {
  if (!session.animated()) return std::nullopt;
  const int f = session.frame(), n = session.frameCount();
  if (key == "Left") return std::max(0, f - 1);
  if (key == "Right") return std::min(n - 1, f + 1);
  const std::vector<int> keyed = session.keyFrames();
  if (keyed.empty() || (key != "LeftBracket" && key != "RightBracket")) return std::nullopt;
  if (key == "RightBracket") {
    const auto next = std::upper_bound(keyed.begin(), keyed.end(), f);
    return next == keyed.end() ? keyed.front() : *next;
  }
  const auto prev = std::lower_bound(keyed.begin(), keyed.end(), f);
  return prev == keyed.begin() ? keyed.back() : *(prev - 1);
}

}  // namespace vdg::studio::app
