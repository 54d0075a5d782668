#pragma once
// RAII ownership of HDF5 identifiers and the conversion of HDF5's error stack into OutputError.
// HDF5 reports failures through negative return values plus a per-thread error stack that it
// prints to stderr by default; Shard silences the printing while it works and turns the stack
// into the exception message, so a user sees one message with context instead of a trace dump.
#include <hdf5.h>

#include <string>
#include <utility>

#include "shard/hdf5_quiet.hpp"

namespace shard::h5 {

// Owns one identifier and closes it with the matching H5?close on destruction.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept
      : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      closer_ = other.closer_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  hid_t get() const { return id_; }
  explicit operator bool() const { return id_ >= 0; }
  void reset() {
    if (id_ >= 0 && closer_ != nullptr) closer_(id_);
    id_ = H5I_INVALID_HID;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

// Turns off HDF5's automatic error printing for this scope (shard/hdf5_quiet.hpp).
using QuietErrors = QuietHdf5Errors;

// The innermost messages of the current HDF5 error stack, one line; clears the stack.
std::string take_error_stack();

// Throws OutputError("<context>: <HDF5 messages>").
[[noreturn]] void fail(const std::string& context);

// Checks an identifier-returning call: returns an owning handle or throws with context.
Handle check(hid_t id, Handle::Closer closer, const std::string& context);
// Checks a status-returning call.
void check(herr_t status, const std::string& context);

Handle file_handle(hid_t id, const std::string& context);
Handle group_handle(hid_t id, const std::string& context);
Handle dataset_handle(hid_t id, const std::string& context);
Handle space_handle(hid_t id, const std::string& context);
Handle type_handle(hid_t id, const std::string& context);
Handle plist_handle(hid_t id, const std::string& context);
Handle attribute_handle(hid_t id, const std::string& context);

}  // namespace shard::h5
