#include "hdf5_handle.hpp"

#include <functional>
#include <numeric>

namespace shard::analysis::h5 {

namespace {
[[noreturn]] void fail(const std::string& action, const std::string& what) {
  throw RunFileError("HDF5: cannot " + action + " " + what);
}

std::size_t element_count(const std::vector<hsize_t>& shape) {
  return std::accumulate(shape.begin(), shape.end(), std::size_t{1},
                         [](std::size_t a, hsize_t b) { return a * static_cast<std::size_t>(b); });
}

std::vector<hsize_t> shape_of(hid_t space) {
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) return {};
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return dims;
}
}  // namespace

Handle open_group(hid_t parent, const std::string& name, const std::string& what) {
  if (!has_link(parent, name)) fail("find group", what);
  Handle g(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail("open group", what);
  return g;
}

Handle create_group(hid_t parent, const std::string& name, const std::string& what) {
  Handle g(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail("create group", what);
  return g;
}

bool has_link(hid_t parent, const std::string& name) {
  return H5Lexists(parent, name.c_str(), H5P_DEFAULT) > 0;
}

bool has_attribute(hid_t object, const std::string& name) {
  return H5Aexists(object, name.c_str()) > 0;
}

std::vector<hsize_t> dataset_shape(hid_t parent, const std::string& name, const std::string& what) {
  if (!has_link(parent, name)) fail("find dataset", what);
  Handle set(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!set.valid()) fail("open dataset", what);
  Handle space(H5Dget_space(set.get()), H5Sclose);
  if (!space.valid()) fail("read the shape of", what);
  return shape_of(space.get());
}

void read_dataset(hid_t parent, const std::string& name, hid_t mem_type, void* buffer,
                  std::size_t expected_elements, const std::string& what) {
  if (!has_link(parent, name)) fail("find dataset", what);
  Handle set(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!set.valid()) fail("open dataset", what);
  Handle space(H5Dget_space(set.get()), H5Sclose);
  const std::size_t count = element_count(shape_of(space.get()));
  if (count != expected_elements) {
    throw RunFileError("HDF5: " + what + " holds " + std::to_string(count) + " values, expected " +
                       std::to_string(expected_elements));
  }
  if (count == 0) return;
  if (H5Dread(set.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer) < 0) fail("read", what);
}

std::vector<double> read_double_attribute(hid_t object, const std::string& name,
                                          const std::string& what) {
  Handle attr(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!attr.valid()) fail("open attribute", what);
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  std::vector<double> values(element_count(shape_of(space.get())));
  if (!values.empty() && H5Aread(attr.get(), H5T_NATIVE_DOUBLE, values.data()) < 0) {
    fail("read attribute", what);
  }
  return values;
}

std::int64_t read_int_attribute(hid_t object, const std::string& name, const std::string& what) {
  Handle attr(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!attr.valid()) fail("open attribute", what);
  std::int64_t value = 0;
  if (H5Aread(attr.get(), H5T_NATIVE_INT64, &value) < 0) fail("read attribute", what);
  return value;
}

void write_dataset(hid_t parent, const std::string& name, hid_t type,
                   const std::vector<hsize_t>& shape, const void* buffer, const std::string& what) {
  if (has_link(parent, name) && H5Ldelete(parent, name.c_str(), H5P_DEFAULT) < 0) {
    fail("replace", what);
  }
  Handle space(H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr), H5Sclose);
  Handle set(H5Dcreate2(parent, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                        H5P_DEFAULT),
             H5Dclose);
  if (!set.valid()) fail("create dataset", what);
  if (element_count(shape) > 0 &&
      H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer) < 0) {
    fail("write", what);
  }
}

namespace {
void write_scalar_attribute(hid_t object, const std::string& name, hid_t type, const void* value,
                            const std::string& what) {
  if (has_attribute(object, name) && H5Adelete(object, name.c_str()) < 0) fail("replace", what);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(object, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose);
  if (!attr.valid() || H5Awrite(attr.get(), type, value) < 0) fail("write attribute", what);
}
}  // namespace

void write_double_attribute(hid_t object, const std::string& name, double value,
                            const std::string& what) {
  write_scalar_attribute(object, name, H5T_NATIVE_DOUBLE, &value, what);
}

void write_int_attribute(hid_t object, const std::string& name, std::int64_t value,
                         const std::string& what) {
  write_scalar_attribute(object, name, H5T_NATIVE_INT64, &value, what);
}

}  // namespace shard::analysis::h5
