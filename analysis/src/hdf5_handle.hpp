#pragma once
// Private RAII and read/write helpers over HDF5's C API.
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "shard/analysis/run_file.hpp"

namespace shard::analysis::h5 {

// Owns one HDF5 identifier and closes it with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, -1)), close_(o.close_) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, -1);
      close_ = o.close_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  void reset() {
    if (id_ >= 0 && close_ != nullptr) close_(id_);
    id_ = -1;
  }
  hid_t id_ = -1;
  Closer close_ = nullptr;
};

// Each throws RunFileError with `what` (a path inside the file) when HDF5 reports failure.
Handle open_group(hid_t parent, const std::string& name, const std::string& what);
Handle create_group(hid_t parent, const std::string& name, const std::string& what);
bool has_link(hid_t parent, const std::string& name);
bool has_attribute(hid_t object, const std::string& name);

// A dataset's dimensions.
std::vector<hsize_t> dataset_shape(hid_t parent, const std::string& name, const std::string& what);

// Reads a whole dataset converted to the memory type; checks the element count.
void read_dataset(hid_t parent, const std::string& name, hid_t mem_type, void* buffer,
                  std::size_t expected_elements, const std::string& what);
std::vector<double> read_double_attribute(hid_t object, const std::string& name,
                                          const std::string& what);
std::int64_t read_int_attribute(hid_t object, const std::string& name, const std::string& what);

// Creates (replacing) a dataset of the given shape and writes buffer into it.
void write_dataset(hid_t parent, const std::string& name, hid_t type, const std::vector<hsize_t>& shape,
                   const void* buffer, const std::string& what);
void write_double_attribute(hid_t object, const std::string& name, double value, const std::string& what);
void write_int_attribute(hid_t object, const std::string& name, std::int64_t value, const std::string& what);

}  // namespace shard::analysis::h5
