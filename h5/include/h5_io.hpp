#pragma once
// Typed reading and writing of attributes and datasets on top of h5_handle.hpp. Storage types
// are fixed little-endian so a file reads the same on every machine; memory types are native.
#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "h5_handle.hpp"
#include "shard/io/output_error.hpp"

namespace shard::h5 {

template <class T>
struct TypeOf;
template <>
struct TypeOf<double> {
  static hid_t memory() { return H5T_NATIVE_DOUBLE; }
  static hid_t file() { return H5T_IEEE_F64LE; }
};
template <>
struct TypeOf<std::int32_t> {
  static hid_t memory() { return H5T_NATIVE_INT32; }
  static hid_t file() { return H5T_STD_I32LE; }
};
template <>
struct TypeOf<std::int64_t> {
  static hid_t memory() { return H5T_NATIVE_INT64; }
  static hid_t file() { return H5T_STD_I64LE; }
};
template <>
struct TypeOf<std::uint64_t> {
  static hid_t memory() { return H5T_NATIVE_UINT64; }
  static hid_t file() { return H5T_STD_U64LE; }
};
template <>
struct TypeOf<std::uint8_t> {
  static hid_t memory() { return H5T_NATIVE_UINT8; }
  static hid_t file() { return H5T_STD_U8LE; }
};

// --- attributes ---------------------------------------------------------------------------
// Strings are variable-length UTF-8 (h5py and ParaView read them as text).
void write_attribute(hid_t object, const std::string& name, const std::string& value);
void write_attribute(hid_t object, const std::string& name, double value);
void write_attribute(hid_t object, const std::string& name, std::int64_t value);
void write_attribute(hid_t object, const std::string& name, std::uint64_t value);

bool has_attribute(hid_t object, const std::string& name);
std::string read_string_attribute(hid_t object, const std::string& name);
double read_double_attribute(hid_t object, const std::string& name);
std::int64_t read_int_attribute(hid_t object, const std::string& name);
std::uint64_t read_uint_attribute(hid_t object, const std::string& name);
// A scalar or one-dimensional numeric attribute, converted to double.
std::vector<double> read_double_array_attribute(hid_t object, const std::string& name);
// Names in creation order when tracked, else in name order.
std::vector<std::string> attribute_names(hid_t object);

// --- groups and links ---------------------------------------------------------------------
// Compact: links live in the group's object header (small groups). Dense: in a fractal heap
// indexed by a B-tree from the first link, so adding a link never rewrites or grows the header;
// used for /frames, which gains a link per frame.
enum class LinkStorage { Compact, Dense };
Handle create_group(hid_t parent, const std::string& name,
                    LinkStorage storage = LinkStorage::Compact);
Handle open_group(hid_t parent, const std::string& path);
// True when every component of `path` exists (H5Lexists on each prefix, as HDF5 requires).
bool path_exists(hid_t parent, const std::string& path);
std::vector<std::string> child_names(hid_t group);
// Removes the link `name` below parent when there is one (a dataset or group to be replaced).
void remove_link(hid_t parent, const std::string& name);

// --- fixed-size datasets ------------------------------------------------------------------
// A [rows] dataset when cols == 0, else [rows, cols]; contiguous storage.
void write_dataset(hid_t parent, const std::string& name, hid_t file_type, hid_t memory_type,
                   const void* data, std::size_t rows, std::size_t cols);

// A [total] ([total, cols]) dataset of which this process writes rows [first, first + rows): every
// process sharing the file calls it (a process without rows too) with the same name and total.
// `transfer` is the dataset-transfer property list (collective I/O for MPI-IO).
void write_dataset_part(hid_t parent, const std::string& name, hid_t file_type, hid_t memory_type,
                        const void* data, std::size_t first, std::size_t rows, std::size_t total,
                        std::size_t cols, hid_t transfer);

template <class T>
void write_dataset_part(hid_t parent, const std::string& name, const T* data, std::size_t first,
                        std::size_t rows, std::size_t total, std::size_t cols, hid_t transfer) {
  write_dataset_part(parent, name, TypeOf<T>::file(), TypeOf<T>::memory(), data, first, rows, total,
                     cols, transfer);
}

// One row per string, variable-length UTF-8 like the string attributes.
void write_string_dataset(hid_t parent, const std::string& name, const std::vector<std::string>& values);

template <class T>
void write_dataset(hid_t parent, const std::string& name, const T* data, std::size_t rows,
                   std::size_t cols = 0) {
  write_dataset(parent, name, TypeOf<T>::file(), TypeOf<T>::memory(), data, rows, cols);
}

struct Shape {
  std::size_t rows = 0;
  std::size_t cols = 0;  // 0 for a 1-D dataset
};

Shape dataset_shape(hid_t parent, const std::string& path);
// Reads the first `rows` rows (all when rows is npos) into out (resized), converting to T.
void read_dataset(hid_t parent, const std::string& path, hid_t memory_type, void* out,
                  std::size_t rows, std::size_t cols);

template <class T>
std::vector<T> read_dataset(hid_t parent, const std::string& path, std::size_t expect_cols,
                            std::size_t rows = static_cast<std::size_t>(-1)) {
  const Shape shape = dataset_shape(parent, path);
  if (shape.cols != expect_cols)
    throw OutputError("dataset '" + path + "' has " + std::to_string(shape.cols) +
                      " columns, expected " + std::to_string(expect_cols));
  if (rows > shape.rows) rows = shape.rows;
  std::vector<T> out(rows * (expect_cols == 0 ? 1 : expect_cols));
  read_dataset(parent, path, TypeOf<T>::memory(), out.data(), rows, shape.cols);
  return out;
}

// --- the frame index -----------------------------------------------------------------------
// /frame_index: uint64 [capacity], contiguous and allocated at creation, 0 = no frame. Entry k
// is the object address of /frames/<k:06d>.
Handle create_frame_index(hid_t file, std::size_t capacity);
void record_frame_address(hid_t index, std::size_t k, hid_t group);
// Object addresses of the recorded frames, up to the first empty entry.
std::vector<haddr_t> read_frame_addresses(hid_t file);

// --- extensible datasets ------------------------------------------------------------------
// A chunked dataset with an unlimited first dimension, grown by append().
class Column {
 public:
  Column() = default;
  Column(hid_t parent, const std::string& name, hid_t file_type, hid_t memory_type,
         std::size_t cols, std::size_t chunk_rows);
  // Appends `rows` rows of `cols` (1 for 1-D) values each.
  void append(const void* data, std::size_t rows);
  std::size_t rows() const { return rows_; }

 private:
  Handle dataset_;
  hid_t memory_type_ = H5I_INVALID_HID;
  std::size_t cols_ = 0;
  std::size_t rows_ = 0;
  std::string name_;
};

template <class T>
Column make_column(hid_t parent, const std::string& name, std::size_t cols,
                   std::size_t chunk_rows) {
  return Column(parent, name, TypeOf<T>::file(), TypeOf<T>::memory(), cols, chunk_rows);
}

}  // namespace shard::h5
