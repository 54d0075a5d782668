#pragma once
// Signed distance to a closed triangle mesh, voxelized by OpenVDB (the seed's voxelization step).
// All OpenVDB headers stay inside signed_distance_field.cpp: this interface is all the rest of
// Shard sees, so OpenVDB's heavy templates compile once and link only into this plugin.
#include <memory>

#include "shard/geometry/inside_test.hpp"
#include "shard/geometry/stl.hpp"
#include "shard/types.hpp"

namespace shard::stl_fill {

class SignedDistanceField {
 public:
  // Unsigned distance voxelized by OpenVDB in a band of `band` [m] around the surface, signed by
  // an exact ray-parity test (so enclosed cavities stay empty); beyond the band distance()
  // returns -band inside and +band outside. `voxel` is the grid spacing [m].
  // `rule`: RayMajority for a closed mesh; WindingWhenRaysDisagree for one closed only
  // geometrically (T-junctions) or up to small cracks (mesh_repair.hpp).
  SignedDistanceField(const geometry::TriangleMesh& mesh, double voxel, double band,
                      geometry::SignRule rule = geometry::SignRule::RayMajority);
  ~SignedDistanceField();
  SignedDistanceField(const SignedDistanceField&) = delete;
  SignedDistanceField& operator=(const SignedDistanceField&) = delete;

  // Trilinear interpolation of the voxel values [m], negative inside. Not thread-safe (it keeps
  // OpenVDB's node cache between calls, which makes neighbouring queries fast).
  double distance(const Vec3& point) const;
  double voxel_size() const { return voxel_; }
  std::size_t active_voxels() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double voxel_;
};

}  // namespace shard::stl_fill
