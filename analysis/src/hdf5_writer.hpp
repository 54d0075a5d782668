#pragma once
// RAII and the few write helpers over HDF5's C API that the standalone tables (column_table.hpp:
// sweep.h5, /breakage groups) need; run.h5 itself is read and written by shard/run_file.hpp.
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

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

// Each throws std::runtime_error with `what` (a path inside the file) when HDF5 reports failure.
Handle create_group(hid_t parent, const std::string& name, const std::string& what);
bool has_link(hid_t parent, const std::string& name);
// Creates (replacing) a dataset of the given shape and writes buffer into it.
void write_dataset(hid_t parent, const std::string& name, hid_t type, const std::vector<hsize_t>& shape,
                   const void* buffer, const std::string& what);
void write_int_attribute(hid_t object, const std::string& name, std::int64_t value, const std::string& what);

}  // namespace shard::analysis::h5
