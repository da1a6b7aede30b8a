#include "app.h"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include "preview.h"
#include "timeline.h"
#include "vdg/geom/error.h"
#include "vdg/io/image_file.h"
#include "vdg/studio/navigation.h"
#include "vdg/studio/session.h"
#include "vdg/viewdep/intersection_check.h"
#include "viewport.h"

namespace vdg::studio::app {

namespace {

// Mouse -> camera rates.
constexpr double kOrbitDegPerPixel = 0.4;
constexpr double kRollDegPerPixel = 0.3;
constexpr double kDollyPerScroll = 0.9;  // distance factor per scroll step (up: closer)
constexpr float kPickRadiusPx = 10.0f;   // pair and vertex markers

enum class Mode { kAlign, kDeform };
enum class Gesture { kNone, kOrbit, kPan, kRoll, kStroke };

struct Rect {
  float x = 0, y = 0, w = 0, h = 0;
  bool contains(double px, double py) const { return px >= x && py >= y && px < x + w && py < y + h; }
};

ImU32 rgb(int r, int g, int b, int a = 255) { return IM_COL32(r, g, b, a); }

const char* kShortcuts[][2] = {
    {"Ctrl+Z", "undo the last stroke"},
    {"Ctrl+Shift+Z, Ctrl+Y", "redo"},
    {"Ctrl+S", "save the key being edited"},
    {"Ctrl+N", "new key (named key1, key2, ...) from the current camera"},
    {"F", "frame the model"},
    {"D", "show / hide the drawing"},
    {"W", "wireframe / shaded"},
    {"1 / 2", "Align mode / Deform mode"},
    {"C", "Align: pick 2D-3D pairs (vertex, then its place on the drawing)"},
    {"P", "Preview panel (Figure 6)"},
    {"I", "view-sphere inset (click a key to jump to its camera)"},
    {"Left / Right", "animated model: previous / next frame (the base is posed there)"},
    {"[ / ]", "animated model: previous / next frame with keys"},
    {"L / Enter", "Deform: feature lines (drag the model's line, then the drawing's) / apply them"},
    {"K", "where to key next: the inset as a heat map, the suggested view in cyan"},
    {"Escape", "cancel the stroke, the pending pair or the pending feature line"},
    {"F1", "this help"},
};

// Widgets that do nothing now are disabled, and say why when hovered: `reason` null means enabled.
void beginDisabledFor(const char* reason) { ImGui::BeginDisabled(reason != nullptr); }
void endDisabledFor(const char* reason) {
  ImGui::EndDisabled();
  if (reason != nullptr && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", reason);
}

// `text` on one line of at most `width` pixels: when longer, its middle becomes "...", so a file
// name keeps its start and its end (cut at UTF-8 character boundaries).
std::string elideMiddle(const std::string& text, float width) {
  if (ImGui::CalcTextSize(text.c_str()).x <= width) return text;
  const auto continuation = [&](std::size_t i) { return i < text.size() && (text[i] & 0xC0) == 0x80; };
  for (std::size_t keep = text.size(); keep-- > 0;) {
    std::size_t head = keep / 2, tail_start = text.size() - (keep - head);
    while (head > 0 && continuation(head)) --head;
    while (continuation(tail_start)) ++tail_start;
    const std::string s = text.substr(0, head) + "..." + text.substr(tail_start);
    if (ImGui::CalcTextSize(s.c_str()).x <= width) return s;
  }
  return "...";
}

// One line, elided in the middle to the panel's width; the whole text as its tooltip.
void oneLine(const std::string& text) {
  const std::string shown = elideMiddle(text, ImGui::GetContentRegionAvail().x);
  ImGui::TextUnformatted(shown.c_str());
  if (shown != text && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text.c_str());
}

constexpr std::size_t kMinAlignPairs = 6;  // alignCamera's minimum (vdg/deform/align.h)

}  // namespace

struct Studio::Impl {
  StudioOptions options;
  std::optional<Session> session;
  std::optional<TextureImage> drawing;
  std::vector<std::string> errors;  // shown in the window
  std::string status;
  std::vector<std::string> key_view_warnings;  // Session::keyViewWarnings() at warnings_revision
  std::uint64_t warnings_revision = ~std::uint64_t{0};
  bool failed = false;
  bool close = false;

  Mode mode = Mode::kAlign;
  ViewportStyle style;
  std::unique_ptr<ViewportRenderer> viewport;
  Texture viewport_texture;
  std::uint64_t drawn_revision = ~std::uint64_t{0};
  Camera drawn_camera;
  ViewportStyle drawn_style;
  int drawn_w = 0, drawn_h = 0;
  bool redraw = true;

  Rect area;  // the viewport's share of the window
  Rect rect;  // the letterboxed image inside it
  Gesture gesture = Gesture::kNone;
  double last_x = 0, last_y = 0;
  bool pick_pairs = false;
  std::optional<std::int32_t> pending_vertex;
  std::optional<std::int32_t> hover_vertex;
  std::int32_t weights_vertex = -1;
  std::uint64_t weights_revision = 0;
  std::vector<double> weights;
  std::optional<AlignResult> align_result;
  bool ortho_solve = false;

  bool show_help = false;
  bool show_preview = false;
  bool recovery_asked = false;
  Preview preview;
  char new_key_name[64] = "";
  bool align_hint = false;  // a drawing was opened: align first (cleared by Deform mode or a solve)
  std::uint64_t sphere_revision = ~std::uint64_t{0};

  void error(const std::string& message) {
    std::fprintf(stderr, "vdg: error: %s\n", vdg::oneLineText(message).c_str());
    errors.push_back(message);
    failed = true;
  }

  // ---- coordinates ------------------------------------------------------------------------
  Eigen::Vector2d toImage(double wx, double wy) const {
    const double s = static_cast<double>(session->image_width) / rect.w;
    return {(wx - rect.x) * s, (wy - rect.y) * s};
  }
  ImVec2 toWindow(const Eigen::Vector2d& p) const {
    const double s = rect.w / static_cast<double>(session->image_width);
    return ImVec2(static_cast<float>(rect.x + p.x() * s), static_cast<float>(rect.y + p.y() * s));
  }
  std::optional<ImVec2> projectVertex(std::span<const float> positions, std::int32_t v) const {
    const std::size_t i = static_cast<std::size_t>(v) * 3;
    if (i + 2 >= positions.size()) return std::nullopt;
    const Eigen::Vector3d p(positions[i], positions[i + 1], positions[i + 2]);
    const Projected pr = project(session->camera, session->image_width, session->image_height, p);
    if (!(pr.depth > 0)) return std::nullopt;
    return toWindow(pr.pixel);
  }

  void layout(const Window& win) {
    area = {kPanelWidth, 0.0f, std::max(1.0f, static_cast<float>(win.width()) - kPanelWidth),
            std::max(1.0f, static_cast<float>(win.height()))};
    if (!session) return;
    if (!drawing) {
      session->image_width = std::max(1, static_cast<int>(area.w));
      session->image_height = std::max(1, static_cast<int>(area.h));
    }
    const float aspect = static_cast<float>(session->image_width) / static_cast<float>(session->image_height);
    float w = area.w, h = area.w / aspect;
    if (h > area.h) {
      h = area.h;
      w = h * aspect;
    }
    rect = {area.x + std::floor((area.w - w) / 2), area.y + std::floor((area.h - h) / 2), w, h};
  }

  // ---- actions -----------------------------------------------------------------------------
  template <class F>
  void attempt(const char* what, F&& f) {
    try {
      f();
    } catch (const std::exception& e) {
      error(std::string(what) + ": " + e.what());
    }
  }

  // Fits the shape shown; an animated base's box over all its frames (its pose), so the walker
  // stays in view as the timeline moves.
  void frameModel() {
    const Bounds b = session->animated() ? session->poseBounds() : computeBounds(session->positions());
    const Eigen::Vector3d lo(b.min[0], b.min[1], b.min[2]), hi(b.max[0], b.max[1], b.max[2]);
    session->camera =
        frameBox(session->camera, lo, hi, static_cast<double>(session->image_width) / session->image_height);
  }

  std::string nextKeyName() const {
    for (int n = 1;; ++n) {
      const std::string name = "key" + std::to_string(n);
      bool used = false;
      for (const RawKey& k : session->model().keys) used = used || k.name == name;
      if (!used) return name;
    }
  }

  void newKey(const std::string& name) {
    attempt("new key", [&] {
      session->newKey(name);
      status = "new key '" + name + "': drag on the model to deform it, Ctrl+S to save";
    });
  }

  void saveKey() {
    if (session->currentKey() < 0) {
      status = "nothing to save: drag on the model in Deform mode (2) to make a key";
      return;
    }
    attempt("save", [&] {
      session->saveKey();
      const RawKey& key = session->model().keys[static_cast<std::size_t>(session->currentKey())];
      status = "saved key '" + key.name + "' to " + session->manifestPath() +
               (key.drawing_path.empty() ? "" : ", with its drawing " + key.drawing_path);
    });
  }

  void undo() {
    if (session->stroking())
      session->cancelStroke();
    else if (session->canUndo())
      session->undo();
  }
  void redo() {
    if (session->canRedo()) session->redo();
  }

  void shortcut(const Event& e) {
    if (ImGui::GetIO().WantTextInput) return;
    const std::string& k = e.key;
    if (e.ctrl) {
      if (k == "Z" && e.shift)
        redo();
      else if (k == "Z")
        undo();
      else if (k == "Y")
        redo();
      else if (k == "S")
        saveKey();
      else if (k == "N")
        newKey(nextKeyName());
      return;
    }
    if (const auto f = timelineShortcut(*session, k))
      goToFrame(*f);
    else if (k == "F1")
      show_help = !show_help;
    else if (k == "F")
      frameModel();
    else if (k == "D")
      style.show_drawing = !style.show_drawing;
    else if (k == "W")
      style.wireframe = !style.wireframe;
    else if (k == "1")
      mode = Mode::kAlign;
    else if (k == "2")
      mode = Mode::kDeform;
    else if (k == "C" && pairsDisabled())
      status = pairsDisabled();
    else if (k == "C")
      pick_pairs = !pick_pairs;
    else if (k == "P")
      show_preview = !show_preview;
    else if (k == "I" && sphereDisabled())
      status = sphereDisabled();
    else if (k == "I")
      style.sphere_inset = !style.sphere_inset;
    else if (k == "L")
      lines_tool = !lines_tool;
    else if (k == "Enter" && lines_tool && mode == Mode::kDeform)
      applyLines();
    else if (k == "K" && heatDisabled())
      status = heatDisabled();
    else if (k == "K") {  // where to key: the inset's heat map (it shows the inset)
      style.sphere_heat = !style.sphere_heat;
      style.sphere_inset = style.sphere_inset || style.sphere_heat;
    } else if (k == "Escape") {
      if (session->stroking()) session->cancelStroke();
      pending_vertex.reset();
      line_from.reset();
      model_line.reset();
      gesture = Gesture::kNone;
      show_help = false;
    }
  }

  void mouseDown(const Event& e) {
    if (!rect.contains(e.x, e.y) || ImGui::GetIO().WantCaptureMouse) return;
    last_x = e.x;
    last_y = e.y;
    const Eigen::Vector2d px = toImage(e.x, e.y);
    if (e.button == 0 && style.sphere_inset && viewport && viewport->insetAvailable()) {
      const double s = static_cast<double>(drawn_w) / rect.w;
      const int key = viewport->insetKeyAt(Eigen::Vector2d((e.x - rect.x) * s, (e.y - rect.y) * s));
      const auto inset = viewport->insetViewport();
      if (key >= 0) {
        jumpToKey(static_cast<std::size_t>(key));
        return;
      }
      const double cx = (e.x - rect.x) * s, cy = (e.y - rect.y) * s;
      if (cx >= inset.x && cy >= inset.y && cx < inset.x + inset.width && cy < inset.y + inset.height) return;
    }
    if (e.button == 0 && mode == Mode::kAlign && pick_pairs) {
      if (!pending_vertex) {
        // The pairs tie BASE vertices to the drawing (solveAlignment uses the base positions).
        pending_vertex = session->pick(px);
        if (!pending_vertex) status = "no vertex there: click on the model, then on its place in the drawing";
      } else {
        session->pairs.push_back(Session::Pair{*pending_vertex, px});
        pending_vertex.reset();
      }
      return;
    }
    if (e.button == 0 && mode == Mode::kDeform) {
      if (lines_tool) {
        line_from = line_to = px;
        return;
      }
      const std::optional<std::int32_t> v = session->pick(px);
      if (!v) return;
      if (session->currentKey() < 0) newKey(nextKeyName());
      if (session->currentKey() < 0) return;
      attempt("stroke", [&] { session->beginStroke(*v, px); });
      if (session->stroking()) gesture = Gesture::kStroke;
      return;
    }
    if (e.button == 0)
      gesture = e.shift ? Gesture::kPan : (e.ctrl ? Gesture::kRoll : Gesture::kOrbit);
    else if (e.button == 1)
      gesture = mode == Mode::kAlign ? Gesture::kPan : Gesture::kOrbit;
    else
      gesture = mode == Mode::kAlign ? Gesture::kRoll : Gesture::kPan;
  }

  void mouseMove(const Event& e) {
    if (line_from) line_to = toImage(e.x, e.y);
    const double dx = e.x - last_x, dy = e.y - last_y;
    last_x = e.x;
    last_y = e.y;
    const double s = static_cast<double>(session->image_width) / rect.w;
    switch (gesture) {
      case Gesture::kNone:
        break;
      case Gesture::kOrbit:
        session->camera = orbit(session->camera, -dx * kOrbitDegPerPixel, -dy * kOrbitDegPerPixel);
        break;
      case Gesture::kPan:
        session->camera =
            pan(session->camera, Eigen::Vector2d(dx * s, dy * s), session->image_width, session->image_height);
        break;
      case Gesture::kRoll:
        session->camera = roll(session->camera, dx * kRollDegPerPixel);
        break;
      case Gesture::kStroke:
        attempt("stroke", [&] { session->updateStroke(toImage(e.x, e.y)); });
        break;
    }
  }

  void mouseUp(const Event& e) {
    if (line_from) {
      line_to = toImage(e.x, e.y);
      lineDragEnd();
    }
    if (gesture == Gesture::kStroke) {
      attempt("stroke", [&] {
        session->updateStroke(toImage(e.x, e.y));
        session->endStroke();
      });
      warnIfThroughItself();
    }
    gesture = Gesture::kNone;
  }

  // After a stroke: the key at its own view (and, animated, its frame) is the key mesh; triangles of
  // it passing through each other where the base's (posed at that frame) do not get a warning on the
  // status line (docs/where-to-key.md).
  void warnIfThroughItself() {
    const int k = session->currentKey();
    if (k < 0) return;
    TriMesh posed = session->baseMesh();
    const std::span<const float> base = session->basePositions();
    posed.positions.assign(base.begin(), base.end());
    const auto pairs = keyIntersections(posed, session->positions());
    if (pairs.empty()) return;
    status = "warning: key '" + session->model().keys[static_cast<std::size_t>(k)].name +
             "' passes through itself at its own view (" + std::to_string(pairs.size()) +
             " triangle pairs the base does not have, e.g. " + std::to_string(pairs.front().first) + " and " +
             std::to_string(pairs.front().second) + "); Ctrl+Z undoes the stroke";
  }

  void scroll(const Event& e) {
    if (!rect.contains(e.x, e.y) || ImGui::GetIO().WantCaptureMouse) return;
    session->camera = dolly(session->camera, std::pow(kDollyPerScroll, e.scroll_y));
  }

  // Why a tool does nothing for this model (null: it works).
  const char* sphereDisabled() const {
    return session->animated() ? "the sphere inset shows a static model's key views; the Preview (P) shows this "
                                 "animated model's keys by frame and view"
                               : nullptr;
  }
  const char* heatDisabled() const {
    if (const char* why = sphereDisabled()) return why;
    return session->model().sphere.scheme == WeightScheme::Rbf
               ? "where to key maps which key triangle holds each view; this model's rbf weights weigh every key "
                 "(docs/weights.md)"
               : nullptr;
  }
  const char* pairsDisabled() const {
    return drawing ? nullptr : "no drawing to align to: open one with vdg studio MODEL --drawing IMAGE";
  }

  // The timeline: pose the base at `f` (an edited key of another frame is left, unless unsaved).
  void goToFrame(int f) {
    if (f == session->frame()) return;
    attempt("frame", [&] {
      session->setFrame(f);
      status = "frame " + std::to_string(f) + (session->currentKey() < 0 ? ": a stroke makes this frame's key" : "");
    });
  }

  void jumpToKey(std::size_t index) {
    if (session->animated()) goToFrame(session->model().keys.at(index).frame);
    const RawKey& key = session->model().keys.at(index);
    if (key.camera) {
      session->camera = *key.camera;
    } else {
      const Eigen::Vector3d c = session->model().resolvedCenter();
      const double d = (session->camera.eye - session->camera.target).norm();
      Camera cam = session->camera;
      cam.target = c;
      cam.eye = c + key.view.normalized() * d;
      session->camera = normalizedCamera(cam);
    }
    status = "camera of key '" + key.name + "'";
  }

  void handle(const std::vector<Event>& events) {
    for (const Event& e : events) {
      switch (e.type) {
        case EventType::kKeyDown:
          shortcut(e);
          break;
        case EventType::kMouseDown:
          mouseDown(e);
          break;
        case EventType::kMouseMove:
          mouseMove(e);
          break;
        case EventType::kMouseUp:
          mouseUp(e);
          break;
        case EventType::kScroll:
          scroll(e);
          break;
        case EventType::kKeyUp:
        case EventType::kText:
          break;
      }
    }
  }

  // ---- panels ------------------------------------------------------------------------------
  void errorPanel() {
    if (errors.empty()) return;
    ImGui::SetNextWindowPos(ImVec2(kPanelWidth + 20, 20), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(std::min(area.w - 40, 640.0f), 0), ImGuiCond_Always);
    ImGui::PushStyleColor(ImGuiCol_WindowBg, IM_COL32(255, 236, 232, 250));
    ImGui::Begin("Errors", nullptr, ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoMove);
    for (const std::string& m : errors) {
      ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(160, 20, 20, 255));
      ImGui::TextWrapped("%s", m.c_str());
      ImGui::PopStyleColor();
    }
    if (session && ImGui::Button("Dismiss")) errors.clear();
    ImGui::End();
    ImGui::PopStyleColor();
  }

  void helpPanel() {
    if (!show_help) return;
    ImGui::SetNextWindowPos(ImVec2(kPanelWidth + 40, 60), ImGuiCond_Appearing);
    ImGui::Begin("Help (F1)", &show_help, ImGuiWindowFlags_AlwaysAutoResize);
    if (ImGui::BeginTable("shortcuts", 2, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) {
      for (const auto& s : kShortcuts) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(s[0]);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(s[1]);
      }
      ImGui::EndTable();
    }
    ImGui::TextUnformatted(
        "Mouse: left drag orbits (Align) or deforms (Deform); right drag pans (Align) or orbits\n"
        "(Deform); middle drag rolls (Align) or pans (Deform); wheel dollies.");
    ImGui::End();
  }

  void recoveryModal() {
    if (recovery_asked || session->recoverableStrokes() == 0) return;
    if (options.recover || options.discard_recovery) {
      recovery_asked = true;
      if (options.recover)
        attempt("recover", [&] { session->recover(); });
      else
        attempt("discard recovery", [&] { session->discardRecovery(); });
      return;
    }
    ImGui::OpenPopup("Recover unsaved strokes?");
    if (ImGui::BeginPopupModal("Recover unsaved strokes?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
      ImGui::Text("The last session on this model ended with %zu unsaved stroke%s.", session->recoverableStrokes(),
                  session->recoverableStrokes() == 1 ? "" : "s");
      ImGui::TextUnformatted("Recover them (then save with Ctrl+S), or discard them?");
      if (ImGui::Button("Recover")) {
        recovery_asked = true;
        attempt("recover", [&] { session->recover(); });
        ImGui::CloseCurrentPopup();
      }
      ImGui::SameLine();
      if (ImGui::Button("Discard")) {
        recovery_asked = true;
        attempt("discard recovery", [&] { session->discardRecovery(); });
        ImGui::CloseCurrentPopup();
      }
      ImGui::EndPopup();
    }
  }

  void sidePanel(const Window& win) {
    ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(kPanelWidth, static_cast<float>(win.height())), ImGuiCond_Always);
    ImGui::Begin("vdg studio", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    if (!session) {
      ImGui::TextWrapped("No model is open (see the error).");
      ImGui::End();
      return;
    }
    oneLine(std::filesystem::path(session->modelPath()).filename().string());
    int m = static_cast<int>(mode);
    ImGui::RadioButton("Align (1)", &m, 0);
    ImGui::SameLine();
    ImGui::RadioButton("Deform (2)", &m, 1);
    mode = static_cast<Mode>(m);
    if (mode == Mode::kDeform) align_hint = false;
    if (align_hint) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.1f, 0.35f, 0.75f, 1.0f));
      ImGui::TextWrapped(
          "Align first (3.1.1): turn the camera until the model sits on the drawing, or pick pairs (C) and "
          "Solve camera; then Deform (2).");
      ImGui::PopStyleColor();
    }

    // An animated model's timeline first: the frame is what every tool edits at.
    const TimelineRequest timeline = drawTimeline(*session);
    if (timeline.frame) goToFrame(*timeline.frame);
    if (timeline.key) attempt("edit key", [&] { session->editKey(*timeline.key); });
    viewSection();
    alignSection();
    deformSection();
    keysSection();
    ImGui::Checkbox("Preview (P)", &show_preview);
    ImGui::SameLine();
    ImGui::Checkbox("Help (F1)", &show_help);
    ImGui::Separator();
    oneLine(status);
    ImGui::End();
  }

  // The panel's "View" section: drawing, wireframe, sphere, projection, framing and roll.
  void viewSection() {
    if (!(ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen))) return;
    if (drawing) {
      ImGui::Checkbox("drawing (D)", &style.show_drawing);
      ImGui::SameLine();
      ImGui::SetNextItemWidth(120);
      ImGui::SliderFloat("opacity", &style.drawing_opacity, 0.0f, 1.0f, "%.2f");
    }
    ImGui::Checkbox("wireframe (W)", &style.wireframe);
    ImGui::SameLine();
    beginDisabledFor(sphereDisabled());
    ImGui::Checkbox("sphere (I)", &style.sphere_inset);
    endDisabledFor(sphereDisabled());
    if (style.sphere_inset && !sphereDisabled()) {
      beginDisabledFor(heatDisabled());
      ImGui::Checkbox("where to key (K)", &style.sphere_heat);
      endDisabledFor(heatDisabled());
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "Colour the sphere by where a new key would help (docs/where-to-key.md); cyan: the suggestion");
      if (const auto s = style.sphere_heat && viewport ? viewport->suggestedView() : std::nullopt)
        ImGui::Text("suggested view %.3f,%.3f,%.3f", s->x(), s->y(), s->z());
    }
    Camera& c = session->camera;
    bool ortho = c.isOrtho();
    if (ImGui::Checkbox("orthographic", &ortho)) {
      const double d = (c.eye - c.target).norm();
      c.ortho_height = ortho ? 2.0 * d * std::tan(c.fov_deg * 0.5 * 3.14159265358979 / 180.0) : 0.0;
    }
    ImGui::SetNextItemWidth(160);
    if (c.isOrtho()) {
      float hgt = static_cast<float>(c.ortho_height);
      const float diag = static_cast<float>(session->baseDiagonal());
      if (ImGui::SliderFloat("height", &hgt, diag * 0.05f, diag * 10.0f, "%.3f", ImGuiSliderFlags_Logarithmic))
        c.ortho_height = hgt;
    } else {
      float fov = static_cast<float>(c.fov_deg);
      if (ImGui::SliderFloat("field of view", &fov, 5.0f, 120.0f, "%.1f deg")) c.fov_deg = fov;
    }
    if (ImGui::Button("Frame (F)")) frameModel();
    ImGui::SameLine();
    if (ImGui::Button("Roll -5")) c = roll(c, -5.0);
    ImGui::SameLine();
    if (ImGui::Button("Roll +5")) c = roll(c, 5.0);
  }

  // The "Align" section (section 3.1.1): point pairs and the camera solve.
  void alignSection() {
    if (!(mode == Mode::kAlign && ImGui::CollapsingHeader("Align (3.1.1)", ImGuiTreeNodeFlags_DefaultOpen))) return;
    beginDisabledFor(pairsDisabled());
    ImGui::Checkbox("pick pairs (C)", &pick_pairs);
    endDisabledFor(pairsDisabled());
    ImGui::TextWrapped("%zu pairs%s", session->pairs.size(),
                       pending_vertex ? "; now click the vertex's place on the drawing" : "");
    if (ImGui::Button("Remove last") && !session->pairs.empty()) session->pairs.pop_back();
    ImGui::SameLine();
    if (ImGui::Button("Clear")) session->pairs.clear();
    ImGui::Checkbox("orthographic camera", &ortho_solve);
    const std::string too_few = "needs at least " + std::to_string(kMinAlignPairs) + " pairs (" +
                                std::to_string(session->pairs.size()) + " so far)";
    const char* solve_off =
        pairsDisabled() ? pairsDisabled() : (session->pairs.size() < kMinAlignPairs ? too_few.c_str() : nullptr);
    beginDisabledFor(solve_off);
    if (ImGui::Button("Solve camera")) {
      try {
        align_result = session->solveAlignment(ortho_solve);
        session->camera = align_result->camera;
        align_hint = false;
      } catch (const std::exception& e) {
        status = std::string("solve: ") + e.what();
      }
    }
    endDisabledFor(solve_off);
    if (align_result) ImGui::Text("reprojection: rms %.2f px, max %.2f px", align_result->rms_px, align_result->max_px);
  }

  // The "Deform" section (section 3.1.2): tool, distance, falloff, undo and redo.
  void deformSection() {
    if (!(mode == Mode::kDeform && ImGui::CollapsingHeader("Deform (3.1.2)", ImGuiTreeNodeFlags_DefaultOpen))) return;
    int t = static_cast<int>(session->tool);
    ImGui::RadioButton("drag", &t, 0);
    ImGui::SameLine();
    ImGui::RadioButton("push/pull", &t, 1);
    ImGui::RadioButton("rotate", &t, 2);
    ImGui::SameLine();
    ImGui::RadioButton("scale", &t, 3);
    session->tool = static_cast<Tool>(t);
    int metric = session->metric == DistanceMetric::kGeodesic ? 1 : 0;
    ImGui::RadioButton("Euclidean", &metric, 0);
    ImGui::SameLine();
    ImGui::RadioButton("geodesic", &metric, 1);
    session->metric = metric == 1 ? DistanceMetric::kGeodesic : DistanceMetric::kEuclidean;
    float radius = static_cast<float>(session->falloff.radius);
    const float diag = static_cast<float>(session->baseDiagonal());
    ImGui::SetNextItemWidth(160);
    if (ImGui::SliderFloat("radius", &radius, diag * 0.01f, diag, "%.3f", ImGuiSliderFlags_Logarithmic))
      session->falloff.radius = radius;
    float power = static_cast<float>(session->falloff.power);
    ImGui::SetNextItemWidth(160);
    if (ImGui::SliderFloat("power", &power, 0.0f, 6.0f, "%.2f")) session->falloff.power = power;
    const char* no_undo = session->canUndo() ? nullptr : "nothing to undo: no stroke of this key in this session";
    beginDisabledFor(no_undo);
    if (ImGui::Button("Undo")) undo();
    endDisabledFor(no_undo);
    ImGui::SameLine();
    const char* no_redo = session->canRedo() ? nullptr : "nothing to redo";
    beginDisabledFor(no_redo);
    if (ImGui::Button("Redo")) redo();
    endDisabledFor(no_redo);
    linesSection();
  }

  // The "Keys" section: each key's view and edit buttons, a new key, saving the current one.
  // Key views nearly the same direction (viewdep decides), recomputed when the keys change.
  void keyViewWarnings() {
    if (warnings_revision != session->revision()) {
      key_view_warnings = session->keyViewWarnings();
      warnings_revision = session->revision();
    }
    for (const std::string& w : key_view_warnings) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.85f, 0.45f, 0.05f, 1.0f));
      ImGui::TextWrapped("warning: %s", w.c_str());
      ImGui::PopStyleColor();
    }
  }

  void keysSection() {
    if (!(ImGui::CollapsingHeader("Keys", ImGuiTreeNodeFlags_DefaultOpen))) return;
    const auto& keys = session->model().keys;
    for (std::size_t i = 0; i < keys.size(); ++i) {
      ImGui::PushID(static_cast<int>(i));
      const bool current = static_cast<int>(i) == session->currentKey();
      // An animated model's keys deform the base at their frames (section 4): the frame is shown.
      const std::string frame = session->animated() ? " f" + std::to_string(keys[i].frame) : "";
      ImGui::Text("%s %s%s%s", current ? ">" : " ", keys[i].name.c_str(), frame.c_str(),
                  current && session->dirty() ? " *" : (current && session->currentKeyIsNew() ? " (new)" : ""));
      ImGui::SameLine(190);
      if (ImGui::SmallButton("view")) jumpToKey(i);
      ImGui::SameLine();
      if (ImGui::SmallButton("edit")) attempt("edit key", [&] { session->editKey(i); });
      ImGui::PopID();
    }
    keyViewWarnings();
    ImGui::SetNextItemWidth(150);
    ImGui::InputTextWithHint("##name", nextKeyName().c_str(), new_key_name, sizeof new_key_name);
    ImGui::SameLine();
    if (ImGui::Button("New key")) {
      newKey(new_key_name[0] != '\0' ? std::string(new_key_name) : nextKeyName());
      new_key_name[0] = '\0';
    }
    const char* no_key =
        session->currentKey() < 0 ? "no key to save: a stroke in Deform mode (2) or New key makes one" : nullptr;
    beginDisabledFor(no_key);
    if (ImGui::Button("Save key (Ctrl+S)")) saveKey();
    endDisabledFor(no_key);
  }

  // ---- viewport ----------------------------------------------------------------------------
  void updateSphere() {
    if (!viewport || !style.sphere_inset) return;
    // Key views change only with the keys; a stroke's revision bump costs a rebuild, which is
    // cheap for the few keys of an editing session.
    if (sphere_revision == session->revision()) return;
    sphere_revision = session->revision();
    std::shared_ptr<const ViewDependentModel> model;
    if (!session->animated() && !session->model().keys.empty()) {
      try {
        model = std::make_shared<const ViewDependentModel>(ViewDependentModel::build(session->model()));
        if (model->hasParts()) model.reset();  // one sphere per part: the inset shows one sphere
      } catch (const std::exception&) {
        model.reset();
      }
    }
    viewport->setSphereModel(std::move(model));
  }

  void drawViewport(ImDrawList* dl) {
    const int w = std::max(1, static_cast<int>(std::lround(rect.w)));
    const int h = std::max(1, static_cast<int>(std::lround(rect.h)));
    if (!viewport) viewport = std::make_unique<ViewportRenderer>(session->baseMesh(), drawing ? &*drawing : nullptr);
    updateSphere();
    const Camera& c = session->camera;
    const bool same =
        drawn_revision == session->revision() && drawn_w == w && drawn_h == h && drawn_camera.eye == c.eye &&
        drawn_camera.target == c.target && drawn_camera.up == c.up && drawn_camera.fov_deg == c.fov_deg &&
        drawn_camera.ortho_height == c.ortho_height && drawn_style.show_drawing == style.show_drawing &&
        drawn_style.drawing_opacity == style.drawing_opacity && drawn_style.wireframe == style.wireframe &&
        drawn_style.sphere_inset == style.sphere_inset && drawn_style.sphere_heat == style.sphere_heat;
    if (!same) {
      // The renderer makes its own EGL context current; the texture belongs to the window's.
      const vdg::render::Image& image = viewport->render(w, h, c, session->positions(), style, session->baseDiagonal());
      window->makeCurrent();
      viewport_texture.upload(image);
      drawn_revision = session->revision();
      drawn_camera = c;
      drawn_style = style;
      drawn_w = w;
      drawn_h = h;
    }
    dl->AddImage(viewport_texture.id(), ImVec2(rect.x, rect.y), ImVec2(rect.x + rect.w, rect.y + rect.h));
  }
  Window* window = nullptr;

  void drawOverlays(ImDrawList* dl) {
    dl->PushClipRect(ImVec2(rect.x, rect.y), ImVec2(rect.x + rect.w, rect.y + rect.h), true);
    const std::span<const float> pos = session->positions();
    if (mode == Mode::kDeform) {
      std::optional<std::int32_t> v = hover_vertex;
      if (session->stroking()) v = stroke_vertex;
      if (v) {
        // A stroke keeps the weights of its start (the session moves the shape with those), so the
        // shape changing under the mouse does not recompute them (a geodesic solve per frame).
        if (weights_vertex != *v || (weights_revision != session->revision() && !session->stroking())) {
          weights = session->selectionWeights(*v);
          weights_vertex = *v;
          weights_revision = session->revision();
        }
        for (std::size_t i = 0; i < weights.size(); ++i) {
          if (weights[i] <= 0.0) continue;
          if (const auto p = projectVertex(pos, static_cast<std::int32_t>(i))) {
            const int a = static_cast<int>(40 + 180 * weights[i]);
            dl->AddCircleFilled(*p, 2.0f, rgb(230, 90, 20, a));
          }
        }
        if (const auto p = projectVertex(pos, *v)) {
          // The selection radius at the vertex's depth, drawn as a circle in the image plane.
          const std::size_t i = static_cast<std::size_t>(*v) * 3;
          const Eigen::Vector3d world(pos[i], pos[i + 1], pos[i + 2]);
          const CameraFrame f = cameraFrame(session->camera);
          const Projected edge = project(session->camera, session->image_width, session->image_height,
                                         world + f.right * session->falloff.radius);
          const ImVec2 e = toWindow(edge.pixel);
          const float r = std::hypot(e.x - p->x, e.y - p->y);
          dl->AddCircle(*p, r, rgb(230, 90, 20), 64, 1.5f);
          dl->AddCircleFilled(*p, 4.0f, rgb(200, 40, 20));
        }
      }
    }
    if (mode == Mode::kAlign) {
      const std::span<const float> base = session->basePositions();
      for (const Session::Pair& pair : session->pairs) {
        const ImVec2 target = toWindow(pair.pixel);
        dl->AddLine(ImVec2(target.x - 5, target.y - 5), ImVec2(target.x + 5, target.y + 5), rgb(20, 120, 40), 2.0f);
        dl->AddLine(ImVec2(target.x - 5, target.y + 5), ImVec2(target.x + 5, target.y - 5), rgb(20, 120, 40), 2.0f);
        if (const auto p = projectVertex(base, pair.vertex)) {
          dl->AddLine(*p, target, rgb(200, 40, 40), 1.0f);  // the reprojection residual
          dl->AddCircleFilled(*p, 3.5f, rgb(40, 60, 200));
        }
      }
      if (pending_vertex)
        if (const auto p = projectVertex(base, *pending_vertex))
          dl->AddCircle(*p, kPickRadiusPx, rgb(40, 60, 200), 24, 2.0f);
      if (pick_pairs && hover_vertex)
        if (const auto p = projectVertex(base, *hover_vertex)) dl->AddCircleFilled(*p, 3.0f, rgb(40, 60, 200, 160));
    }
    dl->PopClipRect();
  }
  std::int32_t stroke_vertex = -1;
  bool framed = false;

  // ---- feature lines (vdg/deform/feature_lines.h): drag the model's line, then the drawing's -----
  bool lines_tool = false, snap_lines = false;
  std::optional<Eigen::Vector2d> line_from;  // the drag in progress
  Eigen::Vector2d line_to = Eigen::Vector2d::Zero();
  std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> model_line;  // waiting for its drawing line

  void lineDragEnd() {
    const Eigen::Vector2d from = *line_from;
    line_from.reset();
    if ((line_to - from).norm() < 2.0) return;  // a click, not a line
    if (!model_line) {
      model_line = std::pair{from, line_to};
      status = "now drag the drawing's line";
      return;
    }
    session->line_pairs.push_back({model_line->first, model_line->second, from, line_to});
    model_line.reset();
    status = std::to_string(session->line_pairs.size()) + " line pair(s): Enter applies them";
  }
  void applyLines() {
    if (session->currentKey() < 0) newKey(nextKeyName());
    if (session->currentKey() < 0) return;
    attempt("feature lines", [&] { session->applyLines(snap_lines); });
  }
  void linesSection() {
    ImGui::Checkbox("feature lines (L)", &lines_tool);
    if (!lines_tool) return;
    ImGui::Checkbox("snap to silhouette", &snap_lines);
    float falloff = static_cast<float>(session->line_settings.falloff_px);
    ImGui::SetNextItemWidth(160);
    if (ImGui::SliderFloat("falloff px", &falloff, 4.0f, 512.0f, "%.0f", ImGuiSliderFlags_Logarithmic))
      session->line_settings.falloff_px = falloff;
    ImGui::BeginDisabled(session->line_pairs.empty());
    if (ImGui::Button("Apply lines (Enter)")) applyLines();
    ImGui::SameLine();
    if (ImGui::Button("Clear lines")) session->line_pairs.clear();
    ImGui::EndDisabled();
  }
  void linesOverlay(ImDrawList* dl) {
    if (!(mode == Mode::kDeform && lines_tool)) return;
    auto line = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, ImU32 colour) {
      dl->AddLine(toWindow(a), toWindow(b), colour, 2.5f);
      dl->AddCircleFilled(toWindow(a), 4.0f, colour);  // P: the line's start
    };
    for (const FeatureLinePair& pair : session->line_pairs) {
      line(pair.model_p, pair.model_q, rgb(40, 90, 220));
      line(pair.drawing_p, pair.drawing_q, rgb(220, 60, 40));
    }
    if (model_line) line(model_line->first, model_line->second, rgb(40, 90, 220));
    if (line_from) line(*line_from, line_to, model_line ? rgb(220, 60, 40) : rgb(40, 90, 220));
  }
};

Studio::Studio(const StudioOptions& options) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.options = options;
  try {
    if (!options.drawing.empty()) m.drawing = readImageFile(options.drawing, "drawing");
  } catch (const std::exception& e) {
    m.error(e.what());
  }
  try {
    m.session.emplace(Session::open(options.model));
  } catch (const std::exception& e) {
    m.error(e.what());
    return;
  }
  if (m.drawing) {
    m.session->image_width = m.drawing->width;
    m.session->image_height = m.drawing->height;
    // New keys are made in this drawing: each saves it as its reference drawing.
    m.session->setDrawing(options.drawing, std::make_shared<const TextureImage>(*m.drawing));
  }
  // Start from the front, framed; the keys' own cameras are a click away.
  Camera c;
  const Bounds b = m.session->poseBounds();
  const Eigen::Vector3d center(b.center()[0], b.center()[1], b.center()[2]);
  c.target = center;
  c.eye = center + Eigen::Vector3d(0, 0, std::max(1e-3, static_cast<double>(b.diagonal())) * 2.0);
  c.fov_deg = 35.0;
  m.session->camera = c;  // framed on the first frame, in the viewport's aspect
  if (m.drawing) {
    m.status = "drawing " + std::to_string(m.drawing->width) + "x" + std::to_string(m.drawing->height) +
               ": align the model to it first";
    m.align_hint = true;
  }
}

Studio::~Studio() = default;
bool Studio::failed() const { return impl_->failed; }
bool Studio::wantsClose() const { return impl_->close; }

void Studio::frame(Window& window, int frame, const std::vector<Event>& events) {
  Impl& m = *impl_;
  m.window = &window;
  m.layout(window);
  if (m.session && !m.framed) {
    m.framed = true;
    m.frameModel();
  }
  if (m.session) {
    for (const Event& e : events)
      if (e.type == EventType::kMouseDown && m.mode == Mode::kDeform && e.button == 0 && m.rect.contains(e.x, e.y))
        if (const auto v = m.session->pick(m.toImage(e.x, e.y))) m.stroke_vertex = *v;
    m.handle(events);
    m.recoveryModal();
    // The vertex under the mouse (Deform, and Align while picking pairs).
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    m.hover_vertex.reset();
    if (m.rect.contains(mouse.x, mouse.y) && !ImGui::GetIO().WantCaptureMouse && !m.session->stroking() &&
        (m.mode == Mode::kDeform || m.pick_pairs))
      m.hover_vertex = m.session->pick(m.toImage(mouse.x, mouse.y));
  }
  m.sidePanel(window);
  m.errorPanel();
  m.helpPanel();
  if (m.session) {
    if (m.show_preview) {
      // Anchored at the bottom left of the viewport and never taller than it: the panel fits the
      // window (1280x800 included) and its content scrolls when it cannot.
      ImGui::SetNextWindowPos(ImVec2(kPanelWidth + 20, m.area.h - 10), ImGuiCond_Appearing, ImVec2(0.0f, 1.0f));
      ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(m.area.w - 40, m.area.h - 20));
      if (ImGui::Begin("Preview (Figure 6)", &m.show_preview, ImGuiWindowFlags_AlwaysAutoResize))
        m.preview.draw(window, m.session->model(), m.session->revision(), frame);
      ImGui::End();
    }
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    dl->AddRectFilled(ImVec2(m.area.x, m.area.y), ImVec2(m.area.x + m.area.w, m.area.y + m.area.h),
                      IM_COL32(120, 120, 118, 255));
    try {
      m.drawViewport(dl);
      m.drawOverlays(dl);
      m.linesOverlay(dl);
    } catch (const std::exception& e) {
      if (m.errors.empty() || m.errors.back() != e.what()) m.error(e.what());
    }
  }
}

}  // namespace vdg::studio::app

namespace vdg::studio::app {

namespace {
double medianMs(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
}  // namespace

Studio::BenchmarkResult Studio::benchmark(int frames, int viewport_width, int viewport_height) {
  using Clock = std::chrono::steady_clock;
  Impl& m = *impl_;
  if (!m.session) throw Error("studio: --benchmark: no model is open");
  Session& s = *m.session;
  if (!m.drawing) {
    s.image_width = viewport_width;
    s.image_height = viewport_height;
  }
  const int w = viewport_width, h = viewport_height;
  if (!m.viewport) m.viewport = std::make_unique<ViewportRenderer>(s.baseMesh(), m.drawing ? &*m.drawing : nullptr);
  BenchmarkResult result{0, 0, w, h};
  std::vector<double> times;
  const Camera start = s.camera;
  (void)m.viewport->render(w, h, s.camera, s.positions(), m.style, s.baseDiagonal());  // warm-up
  for (int f = 0; f < frames; ++f) {
    s.camera = orbit(s.camera, 360.0 / frames, 0.0);
    const auto t0 = Clock::now();
    const vdg::render::Image& image = m.viewport->render(w, h, s.camera, s.positions(), m.style, s.baseDiagonal());
    if (m.window != nullptr) {  // and shown: uploaded into the window's texture
      m.window->makeCurrent();
      m.viewport_texture.upload(image);
    }
    times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  result.frame_ms = medianMs(times);
  s.camera = start;

  // A drag across the image plane from the image centre: each step is a mouse move, the stroke's
  // update and the deformed mesh drawn.
  const Eigen::Vector2d c(s.image_width / 2.0, s.image_height / 2.0);
  const std::optional<std::int32_t> v = s.pick(c);
  if (!v) throw Error("studio: --benchmark: the ray through the image centre misses the model");
  if (s.currentKey() < 0) s.newKey(m.nextKeyName());
  s.beginStroke(*v, c);
  times.clear();
  for (int f = 0; f < frames; ++f) {
    const double a = 6.283185307179586 * f / frames;
    const Eigen::Vector2d p = c + Eigen::Vector2d(40.0 * std::sin(a), 25.0 * (1.0 - std::cos(a)));
    const auto t0 = Clock::now();
    s.updateStroke(p);
    (void)m.viewport->render(w, h, s.camera, s.positions(), m.style, s.baseDiagonal());
    times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  s.cancelStroke();
  result.drag_ms = medianMs(times);
  return result;
}

}  // namespace vdg::studio::app
