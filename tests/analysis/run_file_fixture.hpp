#pragma once
// Writes a small run.h5 in the layout of docs/reference/output-format.md with HDF5's C API directly (not
// through shard::RunWriter), so the reader is checked against the documented layout.
#include <hdf5.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace shard::analysis::test {

struct FrameSpec {
  std::int64_t k = 0, step = 0;
  double time = 0;
  std::vector<std::int32_t> id;
  std::vector<double> position, velocity;  // N*3
  std::vector<double> radius;
  std::vector<std::int32_t> material;
  std::vector<std::int32_t> bonds;  // M*2 row indices
  std::vector<double> mass;         // written only if not empty
  bool complete = true;             // false: no step/time attributes (a frame cut off by a crash)
};

inline void put_dataset(hid_t group, const char* name, hid_t type, std::vector<hsize_t> shape,
                        const void* data) {
  const hid_t space = H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr);
  const hid_t set = H5Dcreate2(group, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  bool empty = false;
  for (hsize_t d : shape) empty = empty || d == 0;
  if (!empty) H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  H5Dclose(set);
  H5Sclose(space);
}

inline void put_attribute(hid_t object, const char* name, hid_t type, const void* value) {
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attr, type, value);
  H5Aclose(attr);
  H5Sclose(space);
}

// density <= 0: no density attribute.
inline void write_run_file(const std::filesystem::path& path, const std::vector<FrameSpec>& frames,
                           double density) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (density > 0) put_attribute(file, "density", H5T_NATIVE_DOUBLE, &density);
  const hid_t all = H5Gcreate2(file, "frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  for (const FrameSpec& f : frames) {
    char name[16];
    std::snprintf(name, sizeof name, "%06lld", static_cast<long long>(f.k));
    const hid_t g = H5Gcreate2(all, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (f.complete) {
      put_attribute(g, "step", H5T_NATIVE_INT64, &f.step);
      put_attribute(g, "time", H5T_NATIVE_DOUBLE, &f.time);
    }
    const hsize_t n = f.id.size();
    put_dataset(g, "id", H5T_NATIVE_INT32, {n}, f.id.data());
    put_dataset(g, "position", H5T_NATIVE_DOUBLE, {n, 3}, f.position.data());
    put_dataset(g, "velocity", H5T_NATIVE_DOUBLE, {n, 3}, f.velocity.data());
    const std::vector<double> omega(3 * n, 0.0);
    put_dataset(g, "omega", H5T_NATIVE_DOUBLE, {n, 3}, omega.data());
    put_dataset(g, "radius", H5T_NATIVE_DOUBLE, {n}, f.radius.data());
    put_dataset(g, "material", H5T_NATIVE_INT32, {n}, f.material.data());
    put_dataset(g, "bonds", H5T_NATIVE_INT32, {f.bonds.size() / 2, 2}, f.bonds.data());
    if (!f.mass.empty()) put_dataset(g, "mass", H5T_NATIVE_DOUBLE, {n}, f.mass.data());
    H5Gclose(g);
  }
  H5Gclose(all);
  H5Fclose(file);
}

// A bar of 6 spheres (ids 100..105, radius 1 mm, 2 mm apart along x) stored in reversed row
// order; in frame k=0 all 5 bonds hold, in frame k=2 the bond between ids 102 and 103 is gone.
inline std::vector<FrameSpec> breaking_bar() {
  std::vector<FrameSpec> frames(2);
  for (int f = 0; f < 2; ++f) {
    FrameSpec& s = frames[static_cast<std::size_t>(f)];
    s.k = 2 * f;
    s.step = 1000 * f;
    s.time = 1e-4 * f;
    for (int row = 0; row < 6; ++row) {
      const int id = 105 - row;
      s.id.push_back(id);
      s.position.insert(s.position.end(), {2e-3 * (id - 100), 0.0, 0.0});
      s.velocity.insert(s.velocity.end(), {0.0, id >= 103 && f == 1 ? 1.0 : 0.0, 0.0});
      s.radius.push_back(1e-3);
      s.material.push_back(0);
    }
    // Row r holds id 105 - r: bond (id, id+1) joins rows (105-id, 104-id).
    for (int id = 100; id < 105; ++id) {
      if (f == 1 && id == 102) continue;
      s.bonds.insert(s.bonds.end(), {105 - id, 104 - id});
    }
  }
  return frames;
}

}  // namespace shard::analysis::test
