// Point pairs for camera alignment (`vdg align --points PAIRS.json`, Rademacher 99, 3.1.1): each
// pair ties a pixel of a drawing to a 3D point of the base mesh, given by vertex number or as a
// point in model space:
//   {"pairs": [{"vertex": 12, "pixel": [310, 92]}, {"point": [0, 1.5, 0.2], "pixel": [256, 40]}]}
// A bare array of pairs is accepted too. Read with the limits of vdg/io/read_file.h and the JSON
// nesting limit of every vdg format.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vdg {

struct PointPair {
  std::optional<std::int64_t> vertex;               // a vertex number (0-based), or
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // a model-space point when there is no vertex
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // drawing pixel (x right, y down), finite
};

// Parses the pairs; `where` names the text in messages. Vertex numbers are checked against
// `vertex_count` (the base mesh's), so an out-of-range or overflowing number is an error naming
// the pair: "PAIRS.json: 'pairs'[3].'vertex': expected an integer from 0 to 2929, got 99999".
// Throws vdg::Error for bad JSON, unknown fields, or a pair without exactly one of vertex/point.
std::vector<PointPair> parsePointPairs(const std::string& text, const std::string& where, std::size_t vertex_count);
std::vector<PointPair> readPointPairs(const std::string& path, std::size_t vertex_count);

}  // namespace vdg
