#include "h5_io.hpp"

#include <array>
#include <cstdlib>
#include <utility>

namespace shard::h5 {

namespace {

Handle utf8_string_type() {
  Handle type = type_handle(H5Tcopy(H5T_C_S1), "copying the string type");
  check(H5Tset_size(type.get(), H5T_VARIABLE), "making a variable-length string type");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "setting UTF-8 on the string type");
  return type;
}

Handle fresh_attribute(hid_t object, const std::string& name, hid_t file_type) {
  // Attributes are rewritten whole (e.g. a frame count); HDF5 has no create-or-replace.
  if (H5Aexists(object, name.c_str()) > 0)
    check(H5Adelete(object, name.c_str()), "replacing attribute '" + name + "'");
  Handle space = space_handle(H5Screate(H5S_SCALAR), "creating a scalar dataspace");
  return attribute_handle(
      H5Acreate2(object, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
      "creating attribute '" + name + "'");
}

// Rows [first, first + rows) of `dataset`, `cols` values each (0: a 1-D dataset): its file space
// with them selected, and a memory space of their shape, for one H5Dread or H5Dwrite.
struct RowSelection {
  Handle file, memory;
};
RowSelection select_rows(hid_t dataset, std::size_t first, std::size_t rows, std::size_t cols,
                         const std::string& what) {
  Handle file = space_handle(H5Dget_space(dataset), "selecting in " + what);
  const std::array<hsize_t, 2> start{first, 0}, count{rows, cols};
  check(H5Sselect_hyperslab(file.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
        "selecting rows of " + what);
  Handle memory = space_handle(H5Screate_simple(cols == 0 ? 1 : 2, count.data(), nullptr),
                               "creating the memory space for " + what);
  return {std::move(file), std::move(memory)};
}

template <class T>
void write_scalar_attribute(hid_t object, const std::string& name, T value) {
  Handle attribute = fresh_attribute(object, name, TypeOf<T>::file());
  check(H5Awrite(attribute.get(), TypeOf<T>::memory(), &value),
        "writing attribute '" + name + "'");
}

template <class T>
T read_scalar_attribute(hid_t object, const std::string& name) {
  Handle attribute = attribute_handle(H5Aopen(object, name.c_str(), H5P_DEFAULT),
                                      "opening attribute '" + name + "'");
  T value{};
  check(H5Aread(attribute.get(), TypeOf<T>::memory(), &value),
        "reading attribute '" + name + "'");
  return value;
}

herr_t collect_attribute_name(hid_t, const char* name, const H5A_info_t*, void* client) {
  static_cast<std::vector<std::string>*>(client)->emplace_back(name);
  return 0;
}

herr_t collect_link_name(hid_t, const char* name, const H5L_info_t*, void* client) {
  static_cast<std::vector<std::string>*>(client)->emplace_back(name);
  return 0;
}

}  // namespace

void write_attribute(hid_t object, const std::string& name, const std::string& value) {
  Handle type = utf8_string_type();
  Handle attribute = fresh_attribute(object, name, type.get());
  const char* text = value.c_str();
  check(H5Awrite(attribute.get(), type.get(), &text), "writing attribute '" + name + "'");
}

void write_attribute(hid_t object, const std::string& name, double value) {
  write_scalar_attribute(object, name, value);
}
void write_attribute(hid_t object, const std::string& name, std::int64_t value) {
  write_scalar_attribute(object, name, value);
}
void write_attribute(hid_t object, const std::string& name, std::uint64_t value) {
  write_scalar_attribute(object, name, value);
}

bool has_attribute(hid_t object, const std::string& name) {
  const htri_t exists = H5Aexists(object, name.c_str());
  if (exists < 0) fail("looking for attribute '" + name + "'");
  return exists > 0;
}

std::string read_string_attribute(hid_t object, const std::string& name) {
  Handle attribute = attribute_handle(H5Aopen(object, name.c_str(), H5P_DEFAULT),
                                      "opening attribute '" + name + "'");
  Handle stored = type_handle(H5Aget_type(attribute.get()), "typing attribute '" + name + "'");
  if (H5Tget_class(stored.get()) != H5T_STRING)
    throw OutputError("attribute '" + name + "' is not a string");
  if (H5Tis_variable_str(stored.get()) > 0) {
    Handle type = utf8_string_type();
    char* text = nullptr;
    check(H5Aread(attribute.get(), type.get(), &text), "reading attribute '" + name + "'");
    std::string value = text != nullptr ? text : "";
    H5free_memory(text);
    return value;
  }
  // Fixed-length strings, as other tools write them.
  const std::size_t size = H5Tget_size(stored.get());
  std::string value(size, '\0');
  check(H5Aread(attribute.get(), stored.get(), value.data()), "reading attribute '" + name + "'");
  value.resize(value.find('\0') == std::string::npos ? size : value.find('\0'));
  return value;
}

double read_double_attribute(hid_t object, const std::string& name) {
  return read_scalar_attribute<double>(object, name);
}
std::int64_t read_int_attribute(hid_t object, const std::string& name) {
  return read_scalar_attribute<std::int64_t>(object, name);
}
std::uint64_t read_uint_attribute(hid_t object, const std::string& name) {
  return read_scalar_attribute<std::uint64_t>(object, name);
}

std::vector<double> read_double_array_attribute(hid_t object, const std::string& name) {
  Handle attribute = attribute_handle(H5Aopen(object, name.c_str(), H5P_DEFAULT),
                                      "opening attribute '" + name + "'");
  Handle space = space_handle(H5Aget_space(attribute.get()), "reading the shape of attribute '" + name + "'");
  if (H5Sget_simple_extent_ndims(space.get()) > 1)
    throw OutputError("attribute '" + name + "' has more than one dimension, expected a number or a list");
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count < 0) fail("counting the values of attribute '" + name + "'");
  std::vector<double> values(static_cast<std::size_t>(count));
  if (!values.empty())
    check(H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, values.data()), "reading attribute '" + name + "'");
  return values;
}

std::vector<std::string> attribute_names(hid_t object) {
  std::vector<std::string> names;
  hsize_t position = 0;
  if (H5Aiterate2(object, H5_INDEX_CRT_ORDER, H5_ITER_INC, &position, collect_attribute_name,
                  &names) >= 0)
    return names;
  // No creation-order index on this object (written by another tool): fall back to names.
  H5Eclear2(H5E_DEFAULT);
  names.clear();
  position = 0;
  check(H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_INC, &position, collect_attribute_name,
                    &names),
        "listing attributes");
  return names;
}

Handle create_group(hid_t parent, const std::string& name, LinkStorage storage) {
  Handle properties = plist_handle(H5Pcreate(H5P_GROUP_CREATE), "creating group properties");
  if (storage == LinkStorage::Dense)
    check(H5Pset_link_phase_change(properties.get(), 0, 0), "selecting dense link storage");
  // Keep attributes in the order they were written (plugins, quality figures, notes).
  check(H5Pset_attr_creation_order(properties.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
        "tracking attribute order");
  return group_handle(
      H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, properties.get(), H5P_DEFAULT),
      "creating group '" + name + "'");
}

Handle open_group(hid_t parent, const std::string& path) {
  return group_handle(H5Gopen2(parent, path.c_str(), H5P_DEFAULT),
                      "opening group '" + path + "'");
}

bool path_exists(hid_t parent, const std::string& path) {
  std::size_t start = path.starts_with('/') ? 1 : 0;
  while (start <= path.size()) {
    std::size_t end = path.find('/', start);
    if (end == std::string::npos) end = path.size();
    if (end == start) return false;  // empty component ("a//b" or trailing '/')
    const std::string prefix = path.substr(0, end);
    const htri_t exists = H5Lexists(parent, prefix.c_str(), H5P_DEFAULT);
    if (exists < 0) {
      H5Eclear2(H5E_DEFAULT);
      return false;
    }
    if (exists == 0) return false;
    start = end + 1;
  }
  return true;
}

std::vector<std::string> child_names(hid_t group) {
  std::vector<std::string> names;
  hsize_t position = 0;
  check(H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, &position, collect_link_name, &names),
        "listing group members");
  return names;
}

void remove_link(hid_t parent, const std::string& name) {
  if (path_exists(parent, name)) check(H5Ldelete(parent, name.c_str(), H5P_DEFAULT), "removing '" + name + "'");
}

void write_dataset(hid_t parent, const std::string& name, hid_t file_type, hid_t memory_type,
                   const void* data, std::size_t rows, std::size_t cols) {
  const std::array<hsize_t, 2> dims{rows, cols};
  Handle space = space_handle(H5Screate_simple(cols == 0 ? 1 : 2, dims.data(), nullptr),
                              "creating the dataspace of '" + name + "'");
  Handle dataset = dataset_handle(H5Dcreate2(parent, name.c_str(), file_type, space.get(),
                                             H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                                  "creating dataset '" + name + "'");
  if (rows == 0 || data == nullptr) return;
  check(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
        "writing dataset '" + name + "'");
}

void write_dataset_part(hid_t parent, const std::string& name, hid_t file_type, hid_t memory_type,
                        const void* data, std::size_t first, std::size_t rows, std::size_t total,
                        std::size_t cols, hid_t transfer) {
  const int rank = cols == 0 ? 1 : 2;
  const std::array<hsize_t, 2> dims{total, cols};
  Handle space = space_handle(H5Screate_simple(rank, dims.data(), nullptr),
                              "creating the dataspace of '" + name + "'");
  Handle dataset = dataset_handle(H5Dcreate2(parent, name.c_str(), file_type, space.get(),
                                             H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                                  "creating dataset '" + name + "'");
  // An empty dataset has no storage to write to (HDF5 fails with an address overflow); the total is
  // the same on every process, so all of them skip the write alike.
  if (total == 0) return;
  // A collective write takes every process, one without rows included (an empty selection).
  const std::array<hsize_t, 2> start{first, 0}, count{rows, cols};
  Handle memory = space_handle(H5Screate_simple(rank, count.data(), nullptr), "the rows of '" + name + "'");
  if (rows == 0 || data == nullptr) {
    check(H5Sselect_none(space.get()), "selecting no rows of '" + name + "'");
    check(H5Sselect_none(memory.get()), "selecting no rows of '" + name + "'");
  } else {
    check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
          "selecting rows of '" + name + "'");
  }
  static const std::uint64_t nothing = 0;  // a process without rows still passes a buffer
  check(H5Dwrite(dataset.get(), memory_type, memory.get(), space.get(), transfer, data ? data : &nothing),
        "writing dataset '" + name + "'");
}

void write_string_dataset(hid_t parent, const std::string& name, const std::vector<std::string>& values) {
  Handle type = utf8_string_type();
  std::vector<const char*> text(values.size());
  for (std::size_t r = 0; r < values.size(); ++r) text[r] = values[r].c_str();
  write_dataset(parent, name, type.get(), type.get(), text.data(), text.size(), 0);
}

Shape dataset_shape(hid_t parent, const std::string& path) {
  Handle dataset = dataset_handle(H5Dopen2(parent, path.c_str(), H5P_DEFAULT),
                                  "opening dataset '" + path + "'");
  Handle space = space_handle(H5Dget_space(dataset.get()), "reading the shape of '" + path + "'");
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank != 1 && rank != 2)
    throw OutputError("dataset '" + path + "' has rank " + std::to_string(rank) +
                      ", expected 1 or 2");
  std::array<hsize_t, 2> dims{0, 0};
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return {static_cast<std::size_t>(dims[0]), rank == 2 ? static_cast<std::size_t>(dims[1]) : 0};
}

void read_dataset(hid_t parent, const std::string& path, hid_t memory_type, void* out,
                  std::size_t rows, std::size_t cols) {
  if (rows == 0) return;
  Handle dataset = dataset_handle(H5Dopen2(parent, path.c_str(), H5P_DEFAULT),
                                  "opening dataset '" + path + "'");
  const RowSelection selected = select_rows(dataset.get(), 0, rows, cols, "'" + path + "'");
  check(H5Dread(dataset.get(), memory_type, selected.memory.get(), selected.file.get(), H5P_DEFAULT, out),
        "reading dataset '" + path + "'");
}

Handle create_frame_index(hid_t file, std::size_t capacity) {
  const hsize_t dims = capacity;
  Handle space = space_handle(H5Screate_simple(1, &dims, nullptr), "creating the frame index");
  Handle properties =
      plist_handle(H5Pcreate(H5P_DATASET_CREATE), "creating frame index properties");
  // Early allocation with zeros: later writes change bytes only, never the file's structure.
  check(H5Pset_layout(properties.get(), H5D_CONTIGUOUS), "laying out the frame index");
  check(H5Pset_alloc_time(properties.get(), H5D_ALLOC_TIME_EARLY), "allocating the frame index");
  const std::uint64_t zero = 0;
  check(H5Pset_fill_value(properties.get(), H5T_NATIVE_UINT64, &zero), "zeroing the frame index");
  check(H5Pset_fill_time(properties.get(), H5D_FILL_TIME_ALLOC), "zeroing the frame index");
  return dataset_handle(H5Dcreate2(file, "frame_index", H5T_STD_U64LE, space.get(), H5P_DEFAULT,
                                   properties.get(), H5P_DEFAULT),
                        "creating dataset 'frame_index'");
}

void record_frame_address(hid_t index, std::size_t k, hid_t group) {
  H5O_info_t info{};
  check(H5Oget_info2(group, &info, H5O_INFO_BASIC), "locating frame " + std::to_string(k));
  const std::uint64_t address = info.addr;
  const RowSelection entry = select_rows(index, k, 1, 0, "frame index entry " + std::to_string(k));
  check(H5Dwrite(index, H5T_NATIVE_UINT64, entry.memory.get(), entry.file.get(), H5P_DEFAULT, &address),
        "recording frame " + std::to_string(k) + " in the frame index");
}

std::vector<haddr_t> read_frame_addresses(hid_t file) {
  std::vector<haddr_t> addresses;
  if (!path_exists(file, "frame_index")) return addresses;
  const std::vector<std::uint64_t> entries = read_dataset<std::uint64_t>(file, "frame_index", 0);
  for (std::uint64_t entry : entries) {
    if (entry == 0) break;
    addresses.push_back(static_cast<haddr_t>(entry));
  }
  return addresses;
}

Column::Column(hid_t parent, const std::string& name, hid_t file_type, hid_t memory_type,
               std::size_t cols, std::size_t chunk_rows)
    : memory_type_(memory_type), cols_(cols), name_(name) {
  const int rank = cols == 0 ? 1 : 2;
  const std::array<hsize_t, 2> dims{0, cols};
  const std::array<hsize_t, 2> max_dims{H5S_UNLIMITED, cols};
  const std::array<hsize_t, 2> chunk{chunk_rows, cols};
  Handle space = space_handle(H5Screate_simple(rank, dims.data(), max_dims.data()),
                              "creating the dataspace of '" + name + "'");
  Handle properties =
      plist_handle(H5Pcreate(H5P_DATASET_CREATE), "creating properties of '" + name + "'");
  check(H5Pset_chunk(properties.get(), rank, chunk.data()), "chunking '" + name + "'");
  dataset_ = dataset_handle(H5Dcreate2(parent, name.c_str(), file_type, space.get(),
                                       H5P_DEFAULT, properties.get(), H5P_DEFAULT),
                            "creating dataset '" + name + "'");
}

void Column::append(const void* data, std::size_t rows) {
  if (rows == 0) return;
  const std::array<hsize_t, 2> new_dims{rows_ + rows, cols_};
  check(H5Dset_extent(dataset_.get(), new_dims.data()), "extending '" + name_ + "'");
  const RowSelection added = select_rows(dataset_.get(), rows_, rows, cols_, "the new rows of '" + name_ + "'");
  check(H5Dwrite(dataset_.get(), memory_type_, added.memory.get(), added.file.get(), H5P_DEFAULT, data),
        "appending to '" + name_ + "'");
  rows_ += rows;
}

}  // namespace shard::h5
