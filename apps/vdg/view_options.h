// Options shared by the subcommands that evaluate a model at one view (weights, eval).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cli.h"
#include "vdg/geom/normalize.h"
#include "vdg/viewdep/model.h"

namespace vdg::cli {

struct ViewOptions {
  std::string view_text;
  std::string eye_text;
  double sharpness = 0.0;               // 0: the model's own
  std::vector<std::string> part_views;  // --part-view NAME=X,Y,Z, repeatable

  void add(CLI::App& sub) {
    auto* view = sub.add_option("--view", view_text, "View direction X,Y,Z from the model centre towards the eye");
    auto* eye = sub.add_option("--eye", eye_text, "Eye position X,Y,Z in model space (view = eye - centre)");
    view->excludes(eye);
    sub.add_option("--sharpness", sharpness, "Sharpness alpha of the blend (default: the model's)")
        ->check(positiveNumber());
    sub.add_option("--part-view", part_views,
                   "NAME=X,Y,Z: drive model part NAME by this view direction instead of its own (repeatable)");
  }

  // The driving view of every part of a model with parts (ViewDependentModel::partViews) for the
  // main view `view`, with --part-view's overrides; usage errors name an unknown part, a model
  // without parts, or a malformed value.
  std::vector<Eigen::Vector3d> resolveParts(const ViewDependentModel& model, const Eigen::Vector3d& view) const {
    if (!part_views.empty() && !model.hasParts())
      throw UsageError("--part-view: the model has no parts (manifest 'parts'; docs/weights.md)");
    std::vector<Eigen::Vector3d> views(model.partCount());
    (void)model.partViews(view, views);  // the size is partCount()
    for (const std::string& text : part_views) {
      const std::size_t eq = text.find('=');
      if (eq == std::string::npos) throw UsageError("--part-view: expected NAME=X,Y,Z, got " + quotedText(text));
      const std::string name = text.substr(0, eq);
      std::size_t p = 0;
      while (p < model.partCount() && model.partName(p) != name) ++p;
      if (p == model.partCount()) {
        std::string names;
        for (std::size_t q = 0; q < model.partCount(); ++q) names += (q ? ", " : "") + model.partName(q);
        throw UsageError("--part-view: the model has no part " + quotedText(name) + " (its parts: " + names + ")");
      }
      views[p] = parseDirection(text.substr(eq + 1), "--part-view " + name);
    }
    return views;
  }

  // The view direction; throws UsageError unless exactly one of --view / --eye was given.
  Eigen::Vector3d resolve(const ViewDependentModel& model) const { return resolve(model.center()); }
  // The eye of a model weighed by eye positions ("weights": {"space": "positions"}): --eye only
  // (a direction has no distance); throws UsageError for --view or neither.
  Eigen::Vector3d resolveEye() const {
    if (eye_text.empty())
      throw UsageError(
          "--eye X,Y,Z: the model weighs eye positions ('positions' space), so a --view direction "
          "does not say where the camera is");
    const Eigen::Vector3d eye = parseVec3(eye_text, "--eye");
    if (!eye.allFinite()) throw UsageError("--eye: expected finite numbers, got " + quotedText(eye_text));
    return eye;
  }
  // The same for a model whose views are measured from `center` (an animated model's).
  Eigen::Vector3d resolve(const Eigen::Vector3d& center) const {
    if (view_text.empty() == eye_text.empty()) throw UsageError("give exactly one of --view X,Y,Z or --eye X,Y,Z");
    if (!view_text.empty()) {
      return parseDirection(view_text, "--view");
    }
    // view = normalize(eye - centre), as ViewDependentModel::viewFromEye, without overflow for a
    // far eye (1e300).
    const Eigen::Vector3d d = parseVec3(eye_text, "--eye") - center;
    if (!d.allFinite()) throw UsageError("--eye: too far from the model centre, got " + quotedText(eye_text));
    const std::optional<Eigen::Vector3d> unit = normalizedOrNone(d);
    if (!unit) throw UsageError("--eye: the eye is at the model centre, so there is no view direction");
    return *unit;
  }
};

}  // namespace vdg::cli
