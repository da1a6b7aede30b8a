// Robust vector lengths and normalisation for any finite magnitude.
//
// The textbook |v| = sqrt(sum v_i^2) overflows to infinity once a component passes about 1e154
// and underflows to zero below about 1e-154, so v / |v| then silently becomes the zero vector (or
// NaN). These helpers first divide by m = max_i |v_i| (the result's largest component is exactly
// 1), take the length of that, and scale back: |v| = m |v / m|, unit(v) = (v / m) / |v / m|. Every
// finite non-zero vector, 1e-300 or 1e300 long, therefore has a correct length (when it is
// representable) and a unit direction. A zero or non-finite vector has no direction: the
// normalising functions report it (std::nullopt), they never return garbage.
//
// All functions are pure, allocation-free and never throw; they are meant for per-frame code too.
#pragma once

#include <optional>
#include <span>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vdg {

// |v| without intermediate overflow or underflow. +inf when a component is infinite or the true
// length exceeds the double range; NaN when a component is NaN; 0 for the zero vector.
double robustNorm(std::span<const double> v);
double robustNorm(const Eigen::Vector3d& v);

// v / |v|, or std::nullopt when v is zero or has a NaN or infinite component.
std::optional<Eigen::Vector3d> normalizedOrNone(const Eigen::Vector3d& v);
// q / |q| (a unit quaternion: the same rotation), or std::nullopt when q is zero or non-finite.
std::optional<Eigen::Quaterniond> normalizedOrNone(const Eigen::Quaterniond& q);

}  // namespace vdg
