// Authoring a key of a view-dependent model one deformation step at a time (Rademacher 99,
// section 3.1: a key deformation is made in its key camera): the rules for a new key, the camera a
// key is edited through, one step of edit operations, and replaying or undoing a key's edit log.
//
// Everything here works on data in memory (RawViewDependentModel, EditLog, TriMesh), so an editor
// or a script uses the same rules as `vdg deform`; reading and writing the files is vdg/io's
// (vdg/io/edit_script.h, vdg/io/file_transaction.h). Every function that changes its arguments
// leaves them unchanged when it throws.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vdg/deform/edits.h"
#include "vdg/viewdep/model.h"

namespace vdg {

// Key names are used as file names (NAME.obj, NAME.edits.json), so they follow one safe rule:
// 1 to 64 characters, each an ASCII letter, digit, '_', '-' or '.', the first not a '.'.
inline constexpr std::size_t kMaxKeyNameLength = 64;
inline constexpr const char* kKeyNameRule = "1 to 64 letters, digits, '_', '-' or '.', not starting with '.'";
bool isValidKeyName(std::string_view name);
// Throws vdg::Error "key name '../x': not allowed (use 1 to 64 letters, ...)"; bytes outside
// printable ASCII are shown as \xHH.
void checkKeyName(std::string_view name);

// A new key's mesh path, as the manifest stores it: relative to the manifest's folder and inside
// it (no leading '/', no '..' leaving it), valid UTF-8 without control characters, ending in
// ".obj" (any letter case). Throws vdg::Error "--mesh PATH: ..." naming the rule broken.
void checkKeyMeshPath(std::string_view mesh_path);

// The base as a key at `frame` deforms it (Rademacher 99, section 4.1: a key of an animated model
// is drawn over the base posed at its frame): the base's triangles with base_frames[frame]'s
// positions for an animated model, the base itself for a static one. Throws vdg::Error "frame F is
// outside the base animation's frames 0..N-1" (a static model has only frame 0).
TriMesh posedBase(const RawViewDependentModel& model, int frame);

// What a new key starts from: the base shape (posed at `frame` for an animated base), with a camera
// or a view (exactly one).
struct NewKey {
  std::string name;
  std::string mesh_path;  // empty: NAME.obj
  std::optional<Camera> camera;
  std::optional<Eigen::Vector3d> view;  // model space, towards the eye; need not be unit
  int frame = 0;                        // the base animation's frame; 0 for a static model
};
// Appends the key to `model` (its mesh a copy of posedBase(model, key.frame), its view resolved)
// and returns its index. Throws vdg::Error for a name breaking the rule or already used, a bad mesh
// path or one another key uses, neither or both of camera and view, a frame out of range, and a
// (frame, view) another key already has (section 4.2: one key per view and frame).
std::size_t addKey(RawViewDependentModel& model, const NewKey& key);

// The camera a key is edited through: its own camera, or for a key known only by its view a
// parallel camera looking at the model's centre along the view (Y up, Z when the view is
// vertical; cameraFromView) from twice the diagonal of the base posed at the key's frame.
Camera keyEditCamera(const RawViewDependentModel& model, const RawKey& key);

// The log a key's first logged step starts: origin "base" when the key's shape is the base's at
// its frame (posedBase), else `snapshot_name` (the caller saves the key's current shape under that
// name, beside the log). A log's origin "base" always means the base posed at the key's frame.
EditLog startEditLog(const RawViewDependentModel& model, const RawKey& key, const std::string& snapshot_name);

// One step: applies `ops` in order to key `key_index` in its edit camera, validates the model and
// appends the step (camera, image size, ops) to `log`. Returns one report per op. Throws vdg::Error
// (naming `source`, the op and the field) for an invalid op or a model that no longer validates.
std::vector<EditReport> deformKey(RawViewDependentModel& model, std::size_t key_index, EditLog& log,
                                  std::span<const EditOp> ops, const std::optional<std::array<int, 2>>& image_size,
                                  const std::string& source);

// The key's positions (#V x 3) rebuilt by replaying every entry of `log` from `origin` (the base,
// or the origin snapshot). `source` names the log in messages ("k.edits.json: 'entries'[1]...").
std::vector<float> replayEditLog(const TriMesh& origin, const EditLog& log, const std::string& source);

// Drops the last entry of `log` and returns the positions the remaining entries rebuild from
// `origin`. Throws vdg::Error naming `source` when the log has no entry.
std::vector<float> undoLastStep(const TriMesh& origin, EditLog& log, const std::string& source);

}  // namespace vdg
