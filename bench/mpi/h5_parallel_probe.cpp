// A probe for the parallel-HDF5 frame writer that is not built yet (docs/explanation/scaling.md, "Where it
// stops scaling"): does the parallel HDF5 library of the MPI build accept the serial RunWriter's
// file settings (the 1.8 object format, attribute creation order, metadata evictions off until a
// flush) under the MPI-IO driver, a variable-length string attribute written alike by every rank,
// and a collective hyperslab write of each rank's rows at the exclusive prefix sum of the counts?
// Rank 0 reads the file back with the default driver and checks every row holds its writer's rank.
//   mpirun -np N build/mpi/bench/mpi/h5_parallel_probe [DIR]     exit code 0: all of it works
#include <hdf5.h>
#include <mpi.h>

#include <cstdio>
#include <string>
#include <vector>

#include "shard/mpi/init.hpp"

namespace {

bool ok(herr_t status, const char* what, int rank, bool& all) {
  if (status < 0) {
    std::printf("rank %d: FAIL: %s\n", rank, what);
    all = false;
  }
  return status >= 0;
}

}  // namespace

int main(int argc, char** argv) {
  shard::mpi::init_funneled(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const std::string path = std::string(argc > 1 ? argv[1] : ".") + "/h5_parallel_probe.h5";
  bool all = true;

  const hid_t access = H5Pcreate(H5P_FILE_ACCESS);
  ok(H5Pset_fapl_mpio(access, MPI_COMM_WORLD, MPI_INFO_NULL), "MPI-IO driver", rank, all);
  ok(H5Pset_libver_bounds(access, H5F_LIBVER_V18, H5F_LIBVER_LATEST), "1.8 object format", rank, all);
  H5AC_cache_config_t config{};
  config.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  ok(H5Pget_mdc_config(access, &config), "reading the metadata cache settings", rank, all);
  config.evictions_enabled = false;
  config.incr_mode = H5C_incr__off;
  config.flash_incr_mode = H5C_flash_incr__off;
  config.decr_mode = H5C_decr__off;
  ok(H5Pset_mdc_config(access, &config), "metadata evictions off", rank, all);
  const hid_t creation = H5Pcreate(H5P_FILE_CREATE);
  ok(H5Pset_attr_creation_order(creation, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), "attribute order", rank, all);
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, creation, access);
  if (file < 0) {
    std::printf("rank %d: FAIL: creating %s\n", rank, path.c_str());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }

  const hid_t text = H5Tcopy(H5T_C_S1);
  H5Tset_size(text, H5T_VARIABLE);
  H5Tset_cset(text, H5T_CSET_UTF8);
  const hid_t scalar = H5Screate(H5S_SCALAR);
  const hid_t attribute = H5Acreate2(file, "scene", text, scalar, H5P_DEFAULT, H5P_DEFAULT);
  const char* scene = "[simulation]\nduration = 1\n";
  ok(H5Awrite(attribute, text, &scene), "a variable-length string attribute", rank, all);
  H5Aclose(attribute);

  // Rank r owns 10 (r + 1) rows; its first row is the sum of the counts before it.
  const long long mine = 10LL * (rank + 1);
  long long before = 0, total = 0;
  MPI_Exscan(&mine, &before, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0) before = 0;  // MPI_Exscan leaves rank 0's result undefined
  MPI_Allreduce(&mine, &total, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  const hid_t group = H5Gcreate2(file, "frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[2] = {static_cast<hsize_t>(total), 3};
  const hid_t space = H5Screate_simple(2, dims, nullptr);
  const hid_t data = H5Dcreate2(group, "position", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t start[2] = {static_cast<hsize_t>(before), 0}, count[2] = {static_cast<hsize_t>(mine), 3};
  H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr);
  const hid_t memory = H5Screate_simple(2, count, nullptr);
  const std::vector<double> rows(static_cast<std::size_t>(3 * mine), static_cast<double>(rank));
  const hid_t transfer = H5Pcreate(H5P_DATASET_XFER);
  ok(H5Pset_dxpl_mpio(transfer, H5FD_MPIO_COLLECTIVE), "collective transfer", rank, all);
  ok(H5Dwrite(data, H5T_NATIVE_DOUBLE, memory, space, transfer, rows.data()), "the collective hyperslab write", rank, all);
  ok(H5Fflush(file, H5F_SCOPE_GLOBAL), "the collective flush", rank, all);
  for (hid_t id : {transfer, access, creation}) H5Pclose(id);
  H5Sclose(memory);
  H5Sclose(space);
  H5Dclose(data);
  H5Gclose(group);
  H5Sclose(scalar);
  H5Tclose(text);
  ok(H5Fclose(file), "closing", rank, all);

  if (rank == 0) {
    const hid_t back = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    std::vector<double> read(static_cast<std::size_t>(3 * total), -1.0);
    const hid_t position = H5Dopen2(back, "frames/position", H5P_DEFAULT);
    ok(H5Dread(position, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, read.data()), "reading back", rank, all);
    H5Dclose(position);
    H5Fclose(back);
    long long row = 0;
    for (int r = 0; r < size; ++r)
      for (long long k = 0; k < 10LL * (r + 1); ++k, ++row)
        for (int a = 0; a < 3; ++a)
          if (read[static_cast<std::size_t>(3 * row + a)] != r) all = false;
    std::printf("%s: %d ranks wrote %lld rows of %s collectively with the serial writer's file settings\n",
                all ? "ok  " : "FAIL", size, total, path.c_str());
  }
  int mine_ok = all ? 1 : 0, every = 0;
  MPI_Allreduce(&mine_ok, &every, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
  MPI_Finalize();
  return every ? 0 : 1;
}
