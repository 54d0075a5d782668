#include "hdf5_writer.hpp"

#include <functional>
#include <numeric>
#include <stdexcept>

namespace shard::analysis::h5 {

namespace {
[[noreturn]] void fail(const std::string& action, const std::string& what) {
  throw std::runtime_error("HDF5: cannot " + action + " " + what);
}

std::size_t element_count(const std::vector<hsize_t>& shape) {
  return std::accumulate(shape.begin(), shape.end(), std::size_t{1},
                         [](std::size_t a, hsize_t b) { return a * static_cast<std::size_t>(b); });
}
}  // namespace

Handle create_group(hid_t parent, const std::string& name, const std::string& what) {
  Handle g(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail("create group", what);
  return g;
}

bool has_link(hid_t parent, const std::string& name) { return H5Lexists(parent, name.c_str(), H5P_DEFAULT) > 0; }

void write_dataset(hid_t parent, const std::string& name, hid_t type, const std::vector<hsize_t>& shape,
                   const void* buffer, const std::string& what) {
  if (has_link(parent, name) && H5Ldelete(parent, name.c_str(), H5P_DEFAULT) < 0) fail("replace", what);
  Handle space(H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr), H5Sclose);
  Handle set(H5Dcreate2(parent, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  if (!set.valid()) fail("create dataset", what);
  if (element_count(shape) > 0 && H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer) < 0)
    fail("write", what);
}

void write_int_attribute(hid_t object, const std::string& name, std::int64_t value, const std::string& what) {
  if (H5Aexists(object, name.c_str()) > 0 && H5Adelete(object, name.c_str()) < 0) fail("replace", what);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(object, name.c_str(), H5T_NATIVE_INT64, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attr.valid() || H5Awrite(attr.get(), H5T_NATIVE_INT64, &value) < 0) fail("write attribute", what);
}

}  // namespace shard::analysis::h5
