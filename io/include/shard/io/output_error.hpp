#pragma once
// The error of Shard's binary files (run.h5, checkpoints, the HDF5 layer under both): a file that
// cannot be written, opened or read as expected. what() names the file and says what to give
// instead. It lives with the file formats, below both the HDF5 layer (shard::h5) and the kernel's
// writers and readers, so the plugins that read run files (from_file) throw and catch the same
// type as the host without seeing the host's headers.
#include <stdexcept>

namespace shard {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace shard
