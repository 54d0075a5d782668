#pragma once
// HDF5 prints its error stack (a dozen lines per failure) to stderr unless told not to. Every
// Shard component that calls HDF5 -- the run writer and reader, checkpoints, the analysis reader,
// the from_file generator -- holds this guard while it works and reports failures itself, in one
// line naming the file; `shard`'s main() holds one for the whole process, so nothing escapes
// (a close at exit, a destructor). The previous handler comes back at the end of the scope, so
// another HDF5 user in the same process keeps its own setting. The setting is per thread (the
// Debian library is thread-safe); Shard calls HDF5 from one thread only.
// Include only where HDF5 is linked: this header needs <hdf5.h>.
#include <hdf5.h>

namespace shard {

class QuietHdf5Errors {
 public:
  QuietHdf5Errors() {
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }
  QuietHdf5Errors(const QuietHdf5Errors&) = delete;
  QuietHdf5Errors& operator=(const QuietHdf5Errors&) = delete;

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

}  // namespace shard
