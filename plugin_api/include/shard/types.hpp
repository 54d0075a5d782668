#pragma once
// Basic numeric types shared by the kernel and every plugin. SI units throughout.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

namespace shard {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;
using Mat3 = Eigen::Matrix3d;
// 32-bit indices: halves the memory traffic of pair lists; 2^31 particles is beyond one node.
using Index = std::int32_t;

}  // namespace shard
