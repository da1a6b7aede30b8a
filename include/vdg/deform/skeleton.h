// Skeleton (wire) deformation: Burtnyk and Wein's technique as Parent, Computer Animation, section
// 4.10 ("Shape Interpolation, Metamorphosis", the skeleton paragraph) describes it, extended to 3D.
//
// Parent 4.10: "The user draws a wire (sequence of connected edges) through the object. The program
// calculates dividing lines at each vertex of the wire. Dividing lines at the extreme ends of the
// wire are perpendicular to the respective end segments. Dividing lines at the interior vertices
// are bisectors of the angle made by the two adjacent segments. Each vertex of the object falls
// within one semi-infinite cell; a cell is defined by a segment of the wire and its two associated
// dividing lines. [...] The distance between the segment and the parallel line through the vertex,
// together with the relative position of the vertex on that line are the local coordinates of that
// vertex with respect to that cell. After the skeleton has been modified by the user, each vertex of
// the object is relocated using newly computed dividing lines and the relative coordinates of the
// vertex. This has been implemented in 2D and has an obvious extension to 3D."
//
// The 3D extension implemented here. A wire is a polyline of joints J_0..J_n (n >= 1 segments;
// segment i runs from J_i to J_{i+1}, length L_i, unit direction d_i).
// - Dividing planes (the lines of 2D): plane k passes through J_k with unit normal m_k:
//     m_0 = d_0, m_n = d_{n-1} (perpendicular to the end segments),
//     m_k = (d_{k-1} + d_k) / |d_{k-1} + d_k| (the bisector plane of the angle at an interior joint).
//   Every joint must bend by less than kMaxSkeletonBendDeg, so that d_i . m_i > 0 and d_i . m_{i+1} > 0.
// - Cells: cell i lies on the forward side of plane i and the backward side of plane i+1
//   ((p - J_i) . m_i >= 0 and (p - J_{i+1}) . m_{i+1} <= 0); the end planes do not bound the end
//   cells (cell 0 goes on past plane 0, cell n-1 past plane n), so every point lies in at least one
//   cell. A vertex in several cells (beyond the line where two dividing planes of a sharp bend
//   cross, on the inner side of the bend, or on a plane itself) is bound to the cell whose segment
//   is nearest (Euclidean distance to the closed segment; equal distances: the lowest index).
// - Local coordinates in cell i: the offset o = (p - J_i) - ((p - J_i) . d_i) d_i of the vertex from
//   the segment's line (the distance of Parent's text, kept as a vector so that 3D has a direction),
//   and the relative position s of p on the line through p parallel to the segment, between its
//   crossings A (plane i) and B (plane i+1): s = |A p| / |A B|, in [0, 1] between the planes. Past
//   an end plane (before plane 0 in cell 0, after plane n in cell n-1) s is replaced by the signed
//   distance beyond that plane, which is perpendicular to the segment at rest and posed alike:
//   the cells are semi-infinite there too, and the part past the end moves with the end joint.
// - Offsets after posing: o' = Q_i o, with Q_i the rotation of segment i's frame. Q_0 is the
//   minimal rotation taking the rest direction d_0 to the posed d'_0; along the wire it is
//   propagated as a parallel transport, Q_{i+1} = P'_i Q_i P_i^T, where P_i (P'_i) is the minimal
//   rotation taking d_i to d_{i+1} on the rest (posed) wire. So the twist about the wire is well
//   defined: none is added at segment 0, and each bend turns the frame by the bend alone. Joint
//   positions cannot express a roll of the wire about itself; a rotation of the whole wire about an
//   axis with a component along d_0 therefore moves a bent wire's mesh rigidly only up to a twist
//   about the segments (translations and rotations about axes perpendicular to d_0 move the mesh
//   by that very motion; any rotation of a straight wire moves it rigidly by the minimal rotation
//   of the wire's direction; tested).
// - Posed position: on the posed line J'_i + o' + t d'_i, A' and B' are its crossings with the
//   posed planes i and i+1, and p' = A' + s (B' - A') (or the end plane's crossing plus the
//   distance beyond it along d'). A vertex on the segment (o = 0) follows the segment exactly:
//   p' = J'_i + s L'_i d'_i. The rest wire as the posed wire gives back every vertex (to rounding).
// - Continuity: a point on an interior dividing plane gets the same posed position from both cells
//   (the parallel transport maps the one cell's offset to the other's), so the mesh stays
//   continuous across every dividing plane; it may jump only where the choice between several
//   cells changes, beyond crossing dividing planes (far from the wire compared with the segment
//   lengths near a sharp bend). An optional falloff (radius, power) fades the deformation out with
//   the distance from the rest wire, so vertices far from it stay put:
//   p_out = p + w (p' - p), w = falloffWeight(falloff, distance to the rest wire) (falloff.h).
//
// Builder/runtime split: bindSkeleton() computes the local coordinates once (allocating);
// SkeletonBinding::apply() relocates the bound vertices for a posed wire, allocating nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vdg/deform/falloff.h"

namespace vdg {

// Most joints a wire may have (the posing code keeps per-joint data on the stack).
inline constexpr std::size_t kMaxSkeletonJoints = 256;
// Sharpest bend at an interior joint, in degrees (the angle between the two segments' directions;
// 0 = straight). At 180 the wire folds back and the bisector plane is undefined; near it the
// dividing planes are almost parallel to the segments and positions would blow up.
inline constexpr double kMaxSkeletonBendDeg = 170.0;

// What is wrong with a wire, and at which joint.
struct SkeletonWireProblem {
  std::size_t joint = 0;  // the offending joint's index (0 for a wrong joint count)
  std::string message;    // e.g. "is the same point as joint 2" (the caller prefixes the joint)
  bool count = false;     // true: the joint count itself is wrong (message names it)
};

// The first problem of `joints` as a wire: fewer than 2 or more than kMaxSkeletonJoints joints,
// a non-finite coordinate, a joint equal to the previous one (segment length <= 1e-12 times the
// wire's largest coordinate magnitude, at least 1e-12), two consecutive joints so far apart that
// their distance overflows, or a bend of kMaxSkeletonBendDeg or more.
std::optional<SkeletonWireProblem> checkSkeletonWire(std::span<const Eigen::Vector3d> joints);

// Which part of its cell a bound vertex is in.
enum class SkeletonRegion : std::uint8_t {
  kBetween,  // between the cell's two dividing planes: `s` is the relative position
  kBefore,   // cell 0, before the start plane: `s` is the signed distance along d_0 (< 0)
  kAfter,    // last cell, after the end plane: `s` is the distance past it along d_{n-1} (> 0)
};

struct SkeletonCoords {
  std::int32_t vertex = 0;   // index into the positions
  std::int32_t segment = 0;  // the cell: segment i, from joint i to joint i+1
  SkeletonRegion region = SkeletonRegion::kBetween;
  double s = 0;                                      // relative position, or distance (see region)
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // rest offset o from the segment's line
  Eigen::Vector3d rest = Eigen::Vector3d::Zero();    // the vertex's rest position
  double weight = 1;                                 // falloff weight in [0, 1]; 1 without falloff
};

struct SkeletonBinding {
  std::vector<Eigen::Vector3d> rest_joints;      // the rest wire (valid: checkSkeletonWire)
  std::vector<Eigen::Vector3d> rest_directions;  // d_i, i = 0..n-1: unit segment directions
  std::vector<Eigen::Matrix3d> rest_transport;   // P_i, i = 0..n-2: minimal rotation d_i -> d_{i+1}
  std::vector<SkeletonCoords> coords;            // one per bound vertex, in vertex order
  std::size_t vertex_count = 0;                  // #V of the positions it was bound to

  // Relocates every bound vertex for the `posed` wire and writes it into `positions_out` (#V x 3,
  // #V = vertex_count); other vertices are not touched. Contract (checked; on a violation nothing
  // is written and it returns false): posed.size() == rest_joints.size(), the posed wire passes
  // checkSkeletonWire (finite, consecutive joints distinct, bends below kMaxSkeletonBendDeg), and
  // positions_out.size() == 3 * vertex_count. Allocates nothing.
  [[nodiscard]] bool apply(std::span<const Eigen::Vector3d> posed, std::span<float> positions_out) const;
};

// Binds the vertices of `positions` (#V x 3; all of them, or only `vertices` when it is
// non-empty: indices < #V) to the rest wire `rest`, with an optional falloff (radius > 0 in model
// units, distance measured to the rest wire; vertices with weight 0 are not bound). Throws
// vdg::Error "skeleton: joint K: ..." for a wire that checkSkeletonWire refuses, and for an index
// out of range or a bad falloff.
SkeletonBinding bindSkeleton(std::span<const Eigen::Vector3d> rest, std::span<const float> positions,
                             std::span<const std::int32_t> vertices = {},
                             const std::optional<Falloff>& falloff = std::nullopt);

// Distance from `p` to the closed segment a-b.
double distanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace vdg
