// The names a model's settings take in vdg's files, one table each, shared by the manifest
// (manifest.cpp) and the glTF extras (gltf_export.cpp) readers. The writers use the matching
// uncoveredName (vdg/viewdep/view_sphere.h) and offsetSpaceName (vdg/viewdep/model.h).
#pragma once

#include <utility>

#include "vdg/viewdep/model.h"
#include "vdg/viewdep/view_sphere.h"

namespace vdg::io {

// "uncovered": what a view outside the key views' hull shows (docs/manifest.md).
inline constexpr std::pair<const char*, Uncovered> kUncoveredNames[] = {
    {"base", Uncovered::Base}, {"cosine", Uncovered::Cosine}, {"cosine2", Uncovered::Cosine2}};

// "weights": {"scheme": ...}: how a view's weights follow from its hull triangle.
inline constexpr std::pair<const char*, WeightScheme> kWeightSchemeNames[] = {
    {"linear", WeightScheme::Linear}, {"smooth", WeightScheme::Smooth}, {"rbf", WeightScheme::Rbf}};

// "weights": {"space": ...}: where keys are located (vdg/viewdep/key_space.h).
inline constexpr std::pair<const char*, WeightSpace> kWeightSpaceNames[] = {{"directions", WeightSpace::Directions},
                                                                            {"positions", WeightSpace::Positions}};
// "weights": {"kernel": ...}: the rbf scheme's radial kernel (view_sphere.h, "Weight schemes").
inline constexpr std::pair<const char*, RbfKernel> kRbfKernelNames[] = {
    {"gaussian", RbfKernel::Gaussian},
    {"inverse-multiquadric", RbfKernel::InverseMultiquadric},
    {"wendland", RbfKernel::Wendland}};

// "offsets": the space a key's offsets from the base are held in (Rademacher 99, section 4).
inline constexpr std::pair<const char*, OffsetSpace> kOffsetSpaceNames[] = {{"world", OffsetSpace::kWorld},
                                                                            {"skinned", OffsetSpace::kSkinned}};

}  // namespace vdg::io
