#include "preview.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "vdg/geom/error.h"
#include "vdg/render/model_renderer.h"
#include "vdg/viewdep/animated_model.h"

namespace vdg::studio::app {

namespace {
constexpr double kTurnDegPerFrame = 1.5;  // the rotating camera's azimuth step
constexpr int kPanelSide = 256;           // pixels of each half of the preview
constexpr float kWeightLines = 4.2f;      // lines of the weight list shown (more scroll)
}  // namespace

struct Preview::Impl {
  std::uint64_t built_revision = ~std::uint64_t{0};
  float sharpness = 0.0f;  // 0: the model's own
  int uncovered = -1;      // -1: the model's own, else Uncovered
  int anim_frame = 0;
  bool settings_changed = false;
  // The keys' reference drawings over the model (vdg/render/drawing_textures.h), ink filled: a
  // static model with a key's "drawing" only.
  bool drawing_textures = false;
  int drawing_mode = 1;  // render::DrawingMode: as drawn, fill ink, flat
  std::optional<ViewDependentModel> model;
  std::optional<AnimatedViewDependentModel> animated;
  std::unique_ptr<vdg::render::ModelRenderer> renderer;
  vdg::render::Image image;
  Texture texture;
  std::string problem;
  ViewWeights weights;
  std::vector<std::string> key_names;

  std::shared_ptr<const vdg::render::DrawingTextures> drawings(const RawViewDependentModel& raw) const;

  void rebuild(const RawViewDependentModel& raw) {
    renderer.reset();
    model.reset();
    animated.reset();
    problem.clear();
    key_names.clear();
    if (raw.keys.empty()) {
      problem = "no keys yet: save a key to preview the view-dependent model";
      return;
    }
    try {
      RawViewDependentModel copy = raw;
      if (uncovered >= 0) copy.sphere.uncovered = static_cast<Uncovered>(uncovered);
      for (const RawKey& k : copy.keys) key_names.push_back(k.name);
      vdg::render::FrameOptions options;
      options.width = kPanelSide;
      options.height = kPanelSide;
      options.samples = 4;
      options.observer = true;
      options.sharpness = sharpness;
      if (copy.animated()) {
        animated = AnimatedViewDependentModel::build(copy);
        renderer = std::make_unique<vdg::render::ModelRenderer>(*animated, options);
        anim_frame = std::clamp(anim_frame, 0, animated->frameCount() - 1);
        renderer->setFrame(anim_frame);
      } else {
        model = ViewDependentModel::build(copy);
        if (drawing_textures) options.drawings = drawings(copy);
        renderer = std::make_unique<vdg::render::ModelRenderer>(*model, options);
      }
    } catch (const std::exception& e) {
      renderer.reset();
      problem = e.what();
    }
  }
};

// The drawings of the keys of the built model (matched by name), prepared in drawing_mode; null
// when no key has one.
std::shared_ptr<const vdg::render::DrawingTextures> Preview::Impl::drawings(const RawViewDependentModel& raw) const {
  std::vector<std::shared_ptr<const TextureImage>> images(model->keyCount());
  bool any = false;
  for (std::size_t k = 0; k < model->keyCount(); ++k)
    for (const RawKey& key : raw.keys)
      if (key.name == model->keyName(k) && key.drawing) {
        images[k] = key.drawing;
        any = true;
      }
  if (!any) return nullptr;
  vdg::render::DrawingStyle style;
  style.mode = static_cast<vdg::render::DrawingMode>(drawing_mode);
  return std::make_shared<const vdg::render::DrawingTextures>(
      vdg::render::DrawingTextures::build(*model, images, style));
}

Preview::Preview() : impl_(std::make_unique<Impl>()) {}
Preview::~Preview() = default;

void Preview::draw(Window& window, const RawViewDependentModel& raw, std::uint64_t revision, int frame) {
  Impl& m = *impl_;
  if (revision != m.built_revision || m.settings_changed) {
    m.settings_changed = false;
    m.built_revision = revision;
    m.rebuild(raw);
  }
  ImGui::SetNextItemWidth(160);
  if (ImGui::SliderFloat("sharpness", &m.sharpness, 0.0f, 10.0f, m.sharpness <= 0.0f ? "model's own" : "%.2f"))
    m.settings_changed = true;
  ImGui::SameLine();
  const char* modes[] = {"model's own", "base", "cosine", "cosine2"};
  int mode = m.uncovered + 1;
  ImGui::SetNextItemWidth(120);
  if (ImGui::Combo("uncovered", &mode, modes, 4)) {
    m.uncovered = mode - 1;
    m.settings_changed = true;
  }
  const bool has_drawings = std::any_of(raw.keys.begin(), raw.keys.end(), [](const RawKey& k) { return k.drawing; });
  if (has_drawings && !raw.animated()) {
    if (ImGui::Checkbox("drawing textures", &m.drawing_textures)) m.settings_changed = true;
    ImGui::SameLine();
    const char* drawing_modes[] = {"as drawn", "fill ink", "flat"};
    ImGui::SetNextItemWidth(120);
    if (ImGui::Combo("drawings", &m.drawing_mode, drawing_modes, 3)) m.settings_changed = true;
  }
  if (!m.renderer) {
    ImGui::TextWrapped("%s", m.problem.c_str());
    return;
  }
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 1.0;
  if (m.model) {
    center = m.model->center();
    radius = m.model->extentRadius();
  } else if (m.animated) {
    center = m.animated->center();
    radius = m.animated->extentRadius();
    const int frames = m.animated->frameCount();
    ImGui::SetNextItemWidth(2 * kPanelSide - 80);
    if (ImGui::SliderInt("frame", &m.anim_frame, 0, frames - 1)) m.renderer->setFrame(m.anim_frame);
    // The keys at (frame, view): x = frame, y = the view's azimuth about +Y.
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    const float w = 2.0f * kPanelSide, h = 60.0f;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(origin, ImVec2(origin.x + w, origin.y + h), IM_COL32(235, 235, 230, 255));
    const float cursor_x =
        origin.x + w * static_cast<float>(m.anim_frame) / static_cast<float>(std::max(1, frames - 1));
    dl->AddLine(ImVec2(cursor_x, origin.y), ImVec2(cursor_x, origin.y + h), IM_COL32(40, 90, 200, 255), 2.0f);
    for (const RawKey& k : raw.keys) {
      const double az = std::atan2(k.view.x(), k.view.z()) * 180.0 / std::numbers::pi;
      const float x = origin.x + w * static_cast<float>(k.frame) / static_cast<float>(std::max(1, frames - 1));
      const float y = origin.y + h * static_cast<float>((180.0 - az) / 360.0);
      dl->AddCircleFilled(ImVec2(x, y), 4.0f, IM_COL32(200, 40, 40, 255));
      if (ImGui::IsMouseHoveringRect(ImVec2(x - 5, y - 5), ImVec2(x + 5, y + 5)))
        ImGui::SetTooltip("%s: frame %d, azimuth %.0f deg", k.name.c_str(), k.frame, az);
    }
    ImGui::Dummy(ImVec2(w, h));
  }
  const Camera turning = vdg::render::orbitCamera(center, vdg::render::fitDistance(radius, 35.0, 1.0),
                                                  kTurnDegPerFrame * frame, 15.0, 35.0);
  try {
    m.weights = m.renderer->render(turning, m.image);
    window.makeCurrent();
    m.texture.upload(m.image);
  } catch (const std::exception& e) {
    m.problem = e.what();
    m.renderer.reset();
    return;
  }
  ImGui::Image(m.texture.id(), ImVec2(static_cast<float>(m.image.width), static_cast<float>(m.image.height)));
  ImGui::TextUnformatted("left: turning camera; right: fixed observer (Figure 6)");
  // The weights in a list of its own height that scrolls, so the panel keeps its size in a small
  // window (1280x800) whatever the list holds.
  ImGui::BeginChild("weights", ImVec2(2.0f * kPanelSide, kWeightLines * ImGui::GetTextLineHeightWithSpacing()), false);
  for (int i = 0; i < 3; ++i) {
    const int k = m.weights.key[static_cast<std::size_t>(i)];
    if (k < 0) continue;
    const std::string name = m.model ? m.model->keyName(static_cast<std::size_t>(k)) : "view " + std::to_string(k);
    ImGui::Text("key %-16s weight %.3f", name.c_str(), m.weights.weight[static_cast<std::size_t>(i)]);
  }
  ImGui::Text("base                 weight %.3f", m.weights.base);
  ImGui::EndChild();
}

}  // namespace vdg::studio::app
