// Session — the editing document of `vdg studio`, the authoring loop of Rademacher 99, section 3.1:
// a base model, a camera turned (or solved from 2D-3D correspondences, 3.1.1) until the model sits
// on a drawing, and strokes dragged across the image plane (3.1.2) that become a key deformation
// with its key viewpoint. No window and no OpenGL here: the editor's window (apps/vdg/studio) shows
// a Session and turns mouse and keys into its calls; tests drive it directly.
//
// Every stroke is one entry of the key's edit log (vdg/deform/edits.h: the camera it was made in,
// the image size, its operations), so a key saved here replays and undoes with `vdg deform`, and a
// drag here gives the same key mesh as the same DragOp through `vdg deform` (tested).
//
// Files: saveKey() writes the key mesh, its edit log and the manifest as one step
// (vdg/io/file_transaction.h, the journal and folder lock `vdg deform` uses), so a failure changes
// nothing. After every stroke, undo and redo the unsaved strokes are autosaved, atomically, to
// recoveryPath(); a crash or a kill loses at most the stroke in progress, and the next open of the
// same model offers them back (recoverableStrokes(), recover(), discardRecovery()).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vdg/deform/align.h"
#include "vdg/deform/edits.h"
#include "vdg/deform/feature_lines.h"
#include "vdg/geom/camera.h"
#include "vdg/geom/material.h"
#include "vdg/geom/tri_mesh.h"
#include "vdg/viewdep/model.h"

namespace vdg::studio {

struct OpenOptions {
  // For an OBJ or glTF model: the manifest keys are saved to; empty: STEM.vdg.json beside it. When
  // that file already exists open() refuses (open the manifest itself instead), so an existing
  // manifest is never replaced by a new one.
  std::string manifest_out;
};

// What a mouse stroke does (3.1.2): drag across the image plane (depth kept), push/pull along the
// view (vertical mouse motion), rotate about the view axis through the picked vertex (horizontal
// motion), scale in the image plane about it (horizontal motion).
enum class Tool { kDrag, kPushPull, kRotate, kScale };
const char* toolName(Tool tool);

// Mouse motion -> tool amounts (image pixels).
inline constexpr double kPushPullPerPixel = 0.005;  // x the base's bounding-box diagonal, per pixel
inline constexpr double kRotateDegPerPixel = 0.5;
inline constexpr double kScalePerPixel = 0.005;  // factor = exp(pixels x this)
// Undo depth: strokes kept with their shapes (older ones stay in the log but cannot be undone here).
inline constexpr std::size_t kMaxUndo = 256;

class Session {
 public:
  // Opens a manifest (*.json), or an OBJ / glTF (*.obj, *.gltf, *.glb) as the base of a new model.
  // Throws vdg::Error naming the file for anything that cannot be read or validated.
  static Session open(const std::string& path, const OpenOptions& options = {});
  ~Session();
  Session(Session&&) noexcept;
  Session& operator=(Session&&) noexcept;

  const RawViewDependentModel& model() const;  // the keys as saved, plus the key being edited
  const std::string& modelPath() const;        // the file opened
  const std::string& manifestPath() const;     // the manifest saveKey() writes
  bool animated() const;                       // animated base (Rademacher 99, section 4)
  const TriMesh& baseMesh() const;
  // The base's positions at frame() (#V x 3): what alignment pairs and a new key start from.
  std::span<const float> basePositions() const;
  double baseDiagonal() const;  // of the base's bounding box at frame 0 (> 0)
  // What framing fits: the base's box for a static model; for an animated one the box around the
  // base at every frame and, when it has keys, the model's extent() (every view's pose), grown to be symmetric about
  // the model's centre, so that a camera framing it looks at the centre and a key made from it has the view it was seen
  // from.
  const Bounds& poseBounds() const;

  // Timeline (section 4: keys at (frame, view)). The frame the base is posed at and new keys are
  // made at: always 0 for a static model. setFrame poses the base at `frame` (0 <= frame <
  // frameCount(), else vdg::Error); when the current key belongs to another frame it is left (the
  // base is shown; an unsaved new key is dropped), refused (vdg::Error) while it has unsaved
  // strokes or a stroke is in progress. editKey() moves to the key's frame.
  int frame() const;
  int frameCount() const;
  void setFrame(int frame);
  // The frames that have keys, ascending, each once.
  std::vector<int> keyFrames() const;

  // The key being edited (an index into model().keys), or -1: the base is shown, nothing to edit.
  int currentKey() const;
  bool currentKeyIsNew() const;  // made in this session and never saved
  // The shape shown: the current key's positions with its strokes (#V x 3), or the base's.
  std::span<const float> positions() const;
  // Changes whenever positions(), the keys or the current key change (for the window's caches).
  std::uint64_t revision() const;

  // The viewport camera, and the image it maps to: a drawing's size in pixels, or the viewport's.
  Camera camera;
  int image_width = 1024, image_height = 768;

  Tool tool = Tool::kDrag;
  DistanceMetric metric = DistanceMetric::kEuclidean;
  Falloff falloff;  // open() sets radius = 0.15 x baseDiagonal(), power 2 (the paper's falloff)

  // The vertex of the first front-facing triangle hit by the ray through `pixel` (image pixels, y
  // down) that is nearest to the hit point, or nothing when the ray misses the shape shown.
  std::optional<std::int32_t> pick(const Eigen::Vector2d& pixel) const;
  // One line per pair of keys whose views are nearly the same direction (viewdep's
  // nearlySameViewPairs: a near-degenerate hull triangle, the weights flip between them), at most
  // a few listed and the rest counted; empty when the key views are well apart.
  std::vector<std::string> keyViewWarnings() const;
  // Falloff weights (#V, in [0, 1]) of a stroke picked at `vertex` with the current settings.
  std::vector<double> selectionWeights(std::int32_t vertex) const;

  // Keys. newKey: a key `name` (checkKeyName) starting from the base posed at frame(), its camera
  // the current one, mesh NAME.obj, its frame frame() (the manifest's (frame, view) key of an
  // animated model); throws vdg::Error for a bad or used name, or a (frame, view) another key
  // has when saved. editKey: makes key `index` current (its shape, its saved edit log), moves to
  // its frame and sets the camera to its edit camera (the timeline's jump to a key). Either
  // refuses (vdg::Error) while the current key has unsaved strokes.
  void newKey(const std::string& name);
  void editKey(std::size_t index);
  bool dirty() const;  // the current key has strokes not saved
  // Writes the current key (mesh, edit log; the manifest when the key is new) as one transaction.
  // Throws vdg::Error naming the file, having changed nothing (on disk and in the session).
  void saveKey();
  // Sets the current key's camera to `camera` (a new key only; a saved key keeps its camera), and
  // gives it the session's drawing (setDrawing), if any.
  void setKeyCamera(const Camera& camera);
  // The drawing the viewport shows (`vdg studio --drawing`; `path` as given, relative to the working
  // directory or absolute): a new key takes it as its reference drawing together with its camera,
  // at its first stroke (the manifest's "drawing", version 5, written relative to the manifest's
  // folder, so `vdg render --drawing-textures` projects it from that camera). Keys made before,
  // and saved keys, keep theirs. An empty path: no drawing.
  void setDrawing(const std::string& path, std::shared_ptr<const TextureImage> image);

  // Strokes with the current tool, in image pixels. begin picks nothing: give the picked vertex.
  void beginStroke(std::int32_t vertex, const Eigen::Vector2d& pixel);
  void updateStroke(const Eigen::Vector2d& pixel);  // the shape follows the mouse
  void endStroke();                                 // commits one log entry; no-op if nothing moved
  void cancelStroke();                              // restores the shape before the stroke
  bool stroking() const;
  // One stroke of explicit operations in the current camera (throws vdg::Error for an invalid op,
  // changing nothing).
  void applyOps(std::span<const EditOp> ops);
  // The ops of stroke i of this session's unsaved-and-saved history (for tests and the log panel).
  std::size_t strokeCount() const;
  bool canUndo() const;
  bool canRedo() const;
  void undo();
  void redo();

  // Feature lines drawn over the drawing (vdg/deform/feature_lines.h), in image pixels: each pair
  // is the model's line, then the drawing's. applyLines() makes them one "lines" stroke in the
  // current camera (in the edit log, undoable) and clears them; with `snap_silhouette` the model
  // sides are first snapped to the silhouette of the shape shown. Throws vdg::Error (changing
  // nothing) when there is no pair, no key, or a pair the op refuses.
  std::vector<FeatureLinePair> line_pairs;
  FeatureLineSettings line_settings;
  void applyLines(bool snap_silhouette = false);

  // Alignment (3.1.1): pairs of a base vertex and the drawing pixel where it belongs.
  struct Pair {
    std::int32_t vertex = 0;
    Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  };
  std::vector<Pair> pairs;
  // alignCamera on the pairs (the base posed at frame()) in image_width x image_height; throws vdg::Error.
  AlignResult solveAlignment(bool ortho) const;

  // Crash recovery. The file lives in a ".vdg-studio" folder beside the manifest.
  const std::string& recoveryPath() const;
  // Unsaved strokes found in a recovery file of this model when it was opened (0: none): its
  // strokes less those a save in the lost session already wrote to the key's edit log.
  std::size_t recoverableStrokes() const;
  // Re-applies them (making their key current; a new key is re-created) and keeps the file;
  // throws vdg::Error if the file no longer fits the model. discardRecovery removes the file.
  void recover();
  void discardRecovery();

 private:
  Session();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vdg::studio
