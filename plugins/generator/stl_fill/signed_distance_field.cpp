#include "signed_distance_field.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/MeshToVolume.h>

#include <cmath>

#include "shard/geometry/inside_test.hpp"
#include <stdexcept>

namespace shard::stl_fill {

struct SignedDistanceField::Impl {
  openvdb::FloatGrid::Ptr grid;
  openvdb::FloatGrid::ConstAccessor accessor;
  Vec3 origin;  // the mesh is voxelized relative to its lower corner: small float32 coordinates
  geometry::TriangleMesh mesh;
  geometry::InsideTest inside;
  Impl(openvdb::FloatGrid::Ptr g, const Vec3& o, const geometry::TriangleMesh& m, geometry::SignRule rule)
      : grid(std::move(g)), accessor(grid->getConstAccessor()), origin(o), mesh(m), inside(mesh, rule) {}
};

SignedDistanceField::SignedDistanceField(const geometry::TriangleMesh& mesh, double voxel, double band,
                                         geometry::SignRule rule)
    : voxel_(voxel) {
  if (!(voxel > 0.0) || !(band >= voxel))
    throw std::invalid_argument("SignedDistanceField: need voxel > 0 and band >= voxel");
  openvdb::initialize();  // idempotent; registers grid types
  const Vec3 origin = geometry::bounding_box(mesh).lower;
  std::vector<openvdb::Vec3s> points;
  points.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices) {
    const Vec3 local = v - origin;
    points.emplace_back(static_cast<float>(local.x()), static_cast<float>(local.y()), static_cast<float>(local.z()));
  }
  std::vector<openvdb::Vec3I> triangles;
  triangles.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces)
    triangles.emplace_back(static_cast<openvdb::Index32>(f[0]), static_cast<openvdb::Index32>(f[1]),
                           static_cast<openvdb::Index32>(f[2]));
  const auto transform = openvdb::math::Transform::createLinearTransform(voxel);
  // OpenVDB decides the sign by flooding from outside, which makes an enclosed cavity solid and
  // corrupts the values next to it. So OpenVDB provides the unsigned distance and the sign comes
  // from an exact ray-parity test (settled by the winding number where the mesh is closed only
  // geometrically and the rays disagree). Interpolating |d| is exact wherever all eight corners lie on
  // one side, i.e. deeper than ~1.7 voxels, and spheres are at least two voxels in radius.
  const auto width = static_cast<float>(std::ceil(band / voxel));
  auto grid = openvdb::tools::meshToUnsignedDistanceField<openvdb::FloatGrid>(*transform, points, triangles, {}, width);
  impl_ = std::make_unique<Impl>(std::move(grid), origin, mesh, rule);
}

SignedDistanceField::~SignedDistanceField() = default;

double SignedDistanceField::distance(const Vec3& point) const {
  const Vec3 local = point - impl_->origin;
  const openvdb::Vec3d index = impl_->grid->transform().worldToIndex(openvdb::Vec3d(local.x(), local.y(), local.z()));
  const auto value = static_cast<double>(openvdb::tools::BoxSampler::sample(impl_->accessor, index));
  return impl_->inside.inside(point) ? -value : value;
}

std::size_t SignedDistanceField::active_voxels() const { return static_cast<std::size_t>(impl_->grid->activeVoxelCount()); }

}  // namespace shard::stl_fill
