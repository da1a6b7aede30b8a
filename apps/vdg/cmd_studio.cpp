// vdg studio MODEL [--drawing IMG] [--replay EVENTS.json] [--record EVENTS.json]
//                  [--screenshot OUT.png] [--count N] [--size WxH] [--recover|--discard-recovery]
//                  [--benchmark]
//
// The interactive editor (Rademacher 99, section 3.1: the authoring loop against a drawing): a
// window (GLFW + Dear ImGui, apps/vdg/studio/) showing a vdg::studio::Session. Everything the
// window does is in apps/vdg/studio; this file parses the options and runs the frame loop:
//   poll input -> this frame's events (live, or --replay's at their frame numbers) -> ImGui and
//   the editor's own shortcuts and gestures -> viewport and panels -> present.
// Errors at start-up (a missing, corrupt or unreadable model or drawing) and later ones (a save
// into a read-only folder) are shown in the window and printed as one line on stderr; the exit
// status is then 1, after the frames asked for. No display: one line, exit status 1.
// Test hook: VDG_STUDIO_ABORT_AT_FRAME=N calls std::abort() at the start of frame N (crash
// recovery tests).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>

#include "cli.h"
#include "studio/app.h"
#include "studio/input.h"
#include "studio/window.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/render/image.h"

namespace vdg::cli {

namespace {

constexpr int kMaxWindowSide = 16384;
constexpr int kBenchmarkFrames = 60;

struct StudioCliOptions {
  std::string model, drawing, replay, record, screenshot, size;
  int frames = 0;  // 0: until the window is closed (with --replay: last event frame + 2)
  bool recover = false, discard_recovery = false, benchmark = false;
};

std::optional<int> abortFrame() {
  const char* v = std::getenv("VDG_STUDIO_ABORT_AT_FRAME");
  if (v == nullptr || *v == '\0') return std::nullopt;
  return std::atoi(v);
}

void run(const StudioCliOptions& opt) {
  using studio::app::Event;
  using studio::app::EventScript;
  if (opt.recover && opt.discard_recovery) throw UsageError("--recover and --discard-recovery exclude each other");
  if (opt.benchmark && (!opt.replay.empty() || !opt.record.empty()))
    throw UsageError("--benchmark takes no --replay or --record");

  std::optional<EventScript> replay;
  if (!opt.replay.empty()) replay = studio::app::readEvents(opt.replay);  // bad input: one line, exit 1

  int width = 1280, height = 800;
  if (!opt.size.empty()) {
    const ImageSize s = parseImageSize(opt.size, 'x', kMaxWindowSide, "--size");
    width = s.width;
    height = s.height;
  } else if (replay && replay->window) {
    width = (*replay->window)[0];
    height = (*replay->window)[1];
  }
  int frames = opt.frames;
  if (frames == 0 && replay) frames = (replay->events.empty() ? 0 : replay->events.back().frame) + 2;
  if (frames == 0 && opt.benchmark) frames = kBenchmarkFrames;

  studio::app::Window window(width, height, "vdg studio - " + opt.model);
  studio::app::StudioOptions so;
  so.model = opt.model;
  so.drawing = opt.drawing;
  so.recover = opt.recover;
  so.discard_recovery = opt.discard_recovery;
  studio::app::Studio studio(so);

  if (opt.benchmark) {
    const int vw = std::max(1, width - static_cast<int>(studio::app::kPanelWidth));
    const auto r = studio.benchmark(frames, vw, height);
    std::printf("viewport frame: %.2f ms median over %d frames while orbiting (%dx%d)\n", r.frame_ms, frames, r.width,
                r.height);
    std::printf("drag: %.2f ms median from mouse move to updated mesh drawn, over %d moves\n", r.drag_ms, frames);
    return;
  }

  const std::optional<int> abort_at = abortFrame();
  EventScript recorded;
  recorded.window = std::array<int, 2>{width, height};
  studio::app::InputState state;
  std::size_t next = 0;  // the next replayed event
  for (int frame = 0; frames == 0 || frame < frames; ++frame) {
    if (abort_at && frame == *abort_at) std::abort();
    window.poll(frame);
    std::vector<Event> events = window.takeLiveEvents();
    if (replay) {
      events.clear();  // live input is ignored while replaying
      while (next < replay->events.size() && replay->events[next].frame <= frame)
        events.push_back(replay->events[next++]);
    } else if (!opt.record.empty()) {
      recorded.events.insert(recorded.events.end(), events.begin(), events.end());
    }
    for (const Event& e : events) state.apply(e);
    window.beginFrame(state, events);
    studio.frame(window, frame, events);
    window.render();
    const bool last = (frames != 0 && frame + 1 == frames) || window.shouldClose();
    if (last && !opt.screenshot.empty()) render::writePng(opt.screenshot, window.readFramebuffer());
    window.present();
    if (window.shouldClose()) break;
  }
  if (!opt.record.empty()) studio::app::writeEvents(opt.record, recorded);
  if (studio.failed()) throw Exit{1};
}

}  // namespace

void addStudioCommand(CLI::App& app) {
  auto opt = std::make_shared<StudioCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "studio",
      "The interactive editor: align a model to a drawing, deform keys across the image plane, save and preview them "
      "(docs/studio.md)");
  sub->add_option("MODEL", opt->model,
                  "Model manifest (*.vdg.json), or a mesh (.obj, .gltf, .glb) to start a model from")
      ->required();
  sub->add_option("--drawing", opt->drawing, "Drawing (PNG or JPEG) shown behind the model; sets the image size");
  sub->add_option("--replay", opt->replay,
                  "Replay recorded input (events file, docs/studio-files.md), ignoring live input");
  sub->add_option("--record", opt->record, "Record the live input into an events file on exit");
  sub->add_option("--screenshot", opt->screenshot, "Write the window as a PNG after the last frame");
  sub->add_option("--count", opt->frames, "Close after N frames (default: with --replay the last event's frame + 2)")
      ->check(wholeNumber(1, 10'000'000));
  sub->add_option("--frames", opt->frames,
                  "The old spelling of --count N, read as such in this version with a deprecation note")
      ->check(wholeNumber(1, 10'000'000))
      ->each([](const std::string&) { noteDeprecated("--frames N", "--count N"); });
  sub->add_option("--size", opt->size, "Window size WxH (default 1280x800, or the replayed file's)")
      ->check(imageSize('x', kMaxWindowSide));
  sub->add_flag("--recover", opt->recover, "Re-apply the strokes autosaved by a session that crashed, without asking");
  sub->add_flag("--discard-recovery", opt->discard_recovery, "Drop the autosaved strokes of a crashed session");
  sub->add_flag("--benchmark", opt->benchmark,
                "Print the median viewport frame time while orbiting and the median mouse-move-to-mesh time of a drag");
  sub->callback([opt] {
    // What a session writes (saved keys, the recovery file of unsaved strokes) is the user's work:
    // kept when the session ends with an error or Ctrl-C (vdg/io/atomic_file.h, removeNewOutputs).
    keepNewOutputs();
    run(*opt);
  });
}

}  // namespace vdg::cli
