#pragma once
// Writes a ColumnTable into an open HDF5 file (shared by write_hdf5_table and RunFile).
#include <hdf5.h>

#include <string>

#include "shard/analysis/column_table.hpp"

namespace shard::analysis::h5 {

// Replaces `group` (absolute, parents created) of the open file with the table; `file_name`
// names the file in messages.
void write_table(hid_t file, const std::string& file_name, const std::string& group, const ColumnTable& table);

}  // namespace shard::analysis::h5
