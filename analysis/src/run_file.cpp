#include "shard/analysis/run_file.hpp"

#include <algorithm>
#include <cstdio>
#include <numbers>

#include "column_table_h5.hpp"
#include "hdf5_handle.hpp"
#include "shard/hdf5_quiet.hpp"

namespace shard::analysis {

static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 arrays are read as [N,3] doubles");

namespace {

std::string frame_path(std::int64_t k) { return "/frames/" + frame_name(k); }

// Per-particle density from the attribute or override; throws naming what is missing.
std::vector<double> densities(const std::vector<double>& rho, const Frame& f, const std::string& where) {
  std::vector<double> out(f.id.size());
  for (std::size_t v = 0; v < out.size(); ++v) {
    double value = 0;
    if (rho.size() == 1) {
      value = rho[0];
    } else {
      const auto m = static_cast<std::size_t>(f.material[v]);
      if (f.material[v] < 0 || m >= rho.size()) {
        throw RunFileError("density " + where + " has " + std::to_string(rho.size()) +
                           " entries but particle row " + std::to_string(v) + " has material " +
                           std::to_string(f.material[v]));
      }
      value = rho[m];
    }
    if (!(value > 0)) throw RunFileError("density " + where + " is not positive");
    out[v] = value;
  }
  return out;
}

void fill_masses(hid_t frame, hid_t root, const std::string& where, std::optional<double> override,
                 Frame& f) {
  const std::size_t n = f.id.size();
  if (h5::has_link(frame, "mass")) {
    f.mass.resize(n);
    h5::read_dataset(frame, "mass", H5T_NATIVE_DOUBLE, f.mass.data(), n, where + "/mass");
    f.mass_source = "mass dataset";
    return;
  }
  std::vector<double> rho;
  std::string source;
  if (override) {
    rho = {*override};
    source = "density " + std::to_string(*override) + " kg/m^3 (given)";
  } else if (h5::has_attribute(frame, "density")) {
    rho = h5::read_double_attribute(frame, "density", where + " attribute density");
    source = "density attribute of " + where;
  } else if (h5::has_attribute(root, "density")) {
    rho = h5::read_double_attribute(root, "density", "/ attribute density");
    source = "density attribute of /";
  } else {
    throw RunFileError(where + " has no mass dataset and the file no density attribute: give the "
                       "particle density (e.g. --density 2500 for 2500 kg/m^3)");
  }
  if (rho.empty()) throw RunFileError("empty density attribute in " + where);
  const std::vector<double> per_particle = densities(rho, f, source);
  f.mass.resize(n);
  for (std::size_t v = 0; v < n; ++v) f.mass[v] = per_particle[v] * sphere_volume(f.radius[v]);
  f.mass_source = "m = rho 4/3 pi r^3, " + source;
}

}  // namespace

std::string frame_name(std::int64_t k) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%06lld", static_cast<long long>(k));
  return buffer;
}

// Every member holds a QuietHdf5Errors: HDF5's failures arrive as one RunFileError, not as its
// error stack on stderr.
RunFile::RunFile(const std::filesystem::path& path, Mode mode) : path_(path) {
  const QuietHdf5Errors quiet;
  if (!std::filesystem::exists(path))
    throw RunFileError(path.string() + ": no such run file; give the run.h5 that `shard run` wrote");
  if (std::filesystem::is_directory(path))
    throw RunFileError(path.string() + ": is a folder, not a run file; give the run.h5 inside it");
  if (H5Fis_hdf5(path.c_str()) <= 0)
    throw RunFileError(path.string() + ": not an HDF5 file, so not a run file; give the run.h5 that `shard run` wrote");
  file_ = H5Fopen(path.c_str(), mode == Mode::read ? H5F_ACC_RDONLY : H5F_ACC_RDWR, H5P_DEFAULT);
  if (file_ < 0) {
    throw RunFileError("cannot open " + path.string() +
                       (mode == Mode::read ? " for reading" : " for writing (is it read-only or open elsewhere?)"));
  }
  if (!h5::has_link(file_, "frames")) {
    H5Fclose(file_);
    throw RunFileError(path.string() + ": has no /frames group, so it is no Shard run file (a checkpoint?); give "
                       "the run.h5 that `shard run` wrote");
  }
}

RunFile::~RunFile() {
  const QuietHdf5Errors quiet;
  if (file_ >= 0) H5Fclose(file_);
}

std::vector<std::int64_t> RunFile::frames() const {
  const QuietHdf5Errors quiet;
  const h5::Handle group = h5::open_group(file_, "frames", "/frames");
  H5G_info_t info{};
  if (H5Gget_info(group.get(), &info) < 0) throw RunFileError("cannot list /frames");
  std::vector<std::int64_t> out;
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t length = H5Lget_name_by_idx(group.get(), ".", H5_INDEX_NAME, H5_ITER_INC, k,
                                              nullptr, 0, H5P_DEFAULT);
    if (length <= 0) continue;
    std::string name(static_cast<std::size_t>(length), '\0');
    H5Lget_name_by_idx(group.get(), ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(),
                       name.size() + 1, H5P_DEFAULT);
    // Only names of the documented form <k:06d> are frames.
    if (name.empty() || !std::all_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      continue;
    }
    // The writer sets step and time last: a frame without them was cut off by a crash.
    if (H5Aexists_by_name(group.get(), name.c_str(), "time", H5P_DEFAULT) <= 0) continue;
    out.push_back(std::stoll(name));
  }
  std::sort(out.begin(), out.end());
  return out;
}

Frame RunFile::read_frame(std::int64_t k, std::optional<double> density) const {
  const QuietHdf5Errors quiet;
  const std::string where = frame_path(k);
  if (!h5::has_link(file_, "frames/" + frame_name(k))) {
    throw RunFileError(path_.string() + " has no frame " + std::to_string(k) + " (" + where + ")");
  }
  const h5::Handle group = h5::open_group(file_, where, where);
  Frame f;
  f.index = k;
  if (h5::has_attribute(group.get(), "step")) f.step = h5::read_int_attribute(group.get(), "step", where + " step");
  if (h5::has_attribute(group.get(), "time")) {
    const auto t = h5::read_double_attribute(group.get(), "time", where + " time");
    if (!t.empty()) f.time = t[0];
  }
  const std::vector<hsize_t> id_shape = h5::dataset_shape(group.get(), "id", where + "/id");
  if (id_shape.size() != 1) throw RunFileError(where + "/id is not one-dimensional");
  const auto n = static_cast<std::size_t>(id_shape[0]);
  f.id.resize(n);
  f.position.resize(n);
  f.velocity.resize(n);
  f.radius.resize(n);
  f.material.assign(n, 0);
  h5::read_dataset(group.get(), "id", H5T_NATIVE_INT32, f.id.data(), n, where + "/id");
  h5::read_dataset(group.get(), "position", H5T_NATIVE_DOUBLE, f.position.data(), 3 * n, where + "/position");
  h5::read_dataset(group.get(), "velocity", H5T_NATIVE_DOUBLE, f.velocity.data(), 3 * n, where + "/velocity");
  h5::read_dataset(group.get(), "radius", H5T_NATIVE_DOUBLE, f.radius.data(), n, where + "/radius");
  if (h5::has_link(group.get(), "material")) {
    h5::read_dataset(group.get(), "material", H5T_NATIVE_INT32, f.material.data(), n, where + "/material");
  }
  if (h5::has_link(group.get(), "body")) {
    f.body.resize(n);
    h5::read_dataset(group.get(), "body", H5T_NATIVE_INT32, f.body.data(), n, where + "/body");
  }
  // bonds: int32 [M,2] row indices; an absent dataset means no surviving bond.
  if (h5::has_link(group.get(), "bonds")) {
    const std::vector<hsize_t> shape = h5::dataset_shape(group.get(), "bonds", where + "/bonds");
    if (!(shape.size() == 2 && shape[1] == 2) && !(shape.size() == 1 && shape[0] == 0)) {
      throw RunFileError(where + "/bonds is not an [M,2] array");
    }
    const std::size_t m = static_cast<std::size_t>(shape[0]);
    std::vector<Index> pairs(2 * m);
    h5::read_dataset(group.get(), "bonds", H5T_NATIVE_INT32, pairs.data(), 2 * m, where + "/bonds");
    f.bond_i.resize(m);
    f.bond_j.resize(m);
    for (std::size_t b = 0; b < m; ++b) {
      f.bond_i[b] = pairs[2 * b];
      f.bond_j[b] = pairs[2 * b + 1];
    }
  }
  fill_masses(group.get(), file_, where, density, f);  // a file id stands for its root group
  return f;
}

void RunFile::write_fragment_labels(std::int64_t k, const std::vector<Index>& labels) {
  const QuietHdf5Errors quiet;
  const std::string where = frame_path(k);
  const h5::Handle group = h5::open_group(file_, where, where);
  const std::vector<hsize_t> id_shape = h5::dataset_shape(group.get(), "id", where + "/id");
  if (id_shape.size() != 1 || id_shape[0] != labels.size()) {
    throw RunFileError("fragment labels do not match the particle count of " + where);
  }
  h5::write_dataset(group.get(), "fragment", H5T_NATIVE_INT32, {labels.size()}, labels.data(),
                    where + "/fragment");
  H5Fflush(file_, H5F_SCOPE_GLOBAL);
}

void RunFile::write_fragment_table(std::int64_t k, const std::vector<Fragment>& fragments,
                                   const SizeDistribution& fsd) {
  const QuietHdf5Errors quiet;
  if (!h5::has_link(file_, "fragments")) h5::create_group(file_, "fragments", "/fragments");
  const std::string where = "/fragments/" + frame_name(k);
  if (h5::has_link(file_, where) && H5Ldelete(file_, where.c_str(), H5P_DEFAULT) < 0) {
    throw RunFileError("cannot replace " + where);
  }
  const h5::Handle group = h5::create_group(file_, where, where);
  const std::size_t count = fragments.size();
  std::vector<std::int64_t> particles(count);
  std::vector<std::int32_t> body(count);
  std::vector<double> mass(count), volume(count), d_eq(count);
  std::vector<Vec3> centre(count), velocity(count), box_min(count), box_max(count);
  for (std::size_t r = 0; r < count; ++r) {
    const Fragment& f = fragments[r];
    particles[r] = static_cast<std::int64_t>(f.particles);
    body[r] = f.body;
    mass[r] = f.mass;
    volume[r] = f.volume;
    d_eq[r] = f.d_eq;
    centre[r] = f.centre;
    velocity[r] = f.velocity;
    box_min[r] = f.box_min;
    box_max[r] = f.box_max;
  }
  const hid_t g = group.get();
  h5::write_dataset(g, "particles", H5T_NATIVE_INT64, {count}, particles.data(), where + "/particles");
  h5::write_dataset(g, "mass", H5T_NATIVE_DOUBLE, {count}, mass.data(), where + "/mass");
  h5::write_dataset(g, "volume", H5T_NATIVE_DOUBLE, {count}, volume.data(), where + "/volume");
  h5::write_dataset(g, "d_eq", H5T_NATIVE_DOUBLE, {count}, d_eq.data(), where + "/d_eq");
  h5::write_dataset(g, "centre", H5T_NATIVE_DOUBLE, {count, 3}, centre.data(), where + "/centre");
  h5::write_dataset(g, "velocity", H5T_NATIVE_DOUBLE, {count, 3}, velocity.data(), where + "/velocity");
  h5::write_dataset(g, "box_min", H5T_NATIVE_DOUBLE, {count, 3}, box_min.data(), where + "/box_min");
  h5::write_dataset(g, "box_max", H5T_NATIVE_DOUBLE, {count, 3}, box_max.data(), where + "/box_max");
  h5::write_dataset(g, "body", H5T_NATIVE_INT32, {count}, body.data(), where + "/body");
  h5::write_int_attribute(g, "count", static_cast<std::int64_t>(count), where);
  h5::write_double_attribute(g, "x10", fsd.x10, where);
  h5::write_double_attribute(g, "x50", fsd.x50, where);
  h5::write_double_attribute(g, "x90", fsd.x90, where);
  h5::write_double_attribute(g, "fines_size", fsd.fines_size, where);
  h5::write_double_attribute(g, "fines_mass", fsd.fines_mass, where);
  H5Fflush(file_, H5F_SCOPE_GLOBAL);
}

std::vector<BodyImpactRow> RunFile::read_body_impacts() const {
  const QuietHdf5Errors quiet;
  if (!h5::has_link(file_, "body_impacts")) return {};
  const h5::Handle g = h5::open_group(file_, "body_impacts", "/body_impacts");
  const std::vector<hsize_t> shape = h5::dataset_shape(g.get(), "hit", "/body_impacts/hit");
  if (shape.size() != 1) throw RunFileError("/body_impacts/hit is not one-dimensional");
  const auto n = static_cast<std::size_t>(shape[0]);
  std::vector<std::int32_t> hit(n), wall(n);
  std::vector<double> time(n), speed(n), angle(n);
  h5::read_dataset(g.get(), "hit", H5T_NATIVE_INT32, hit.data(), n, "/body_impacts/hit");
  h5::read_dataset(g.get(), "wall", H5T_NATIVE_INT32, wall.data(), n, "/body_impacts/wall");
  h5::read_dataset(g.get(), "time", H5T_NATIVE_DOUBLE, time.data(), n, "/body_impacts/time");
  h5::read_dataset(g.get(), "speed", H5T_NATIVE_DOUBLE, speed.data(), n, "/body_impacts/speed");
  h5::read_dataset(g.get(), "angle", H5T_NATIVE_DOUBLE, angle.data(), n, "/body_impacts/angle");
  std::vector<BodyImpactRow> out(n);
  for (std::size_t b = 0; b < n; ++b) out[b] = {hit[b] != 0, time[b], speed[b], angle[b], wall[b]};
  return out;
}

void RunFile::write_table(const std::string& group, const ColumnTable& table) {
  const QuietHdf5Errors quiet;
  h5::write_table(file_, path_.string(), group, table);
}

void RunFile::write_body_table(std::int64_t k, const BodyReport& report) {
  const QuietHdf5Errors quiet;
  if (!h5::has_link(file_, "bodies")) h5::create_group(file_, "bodies", "/bodies");
  const std::string where = "/bodies/" + frame_name(k);
  if (h5::has_link(file_, where) && H5Ldelete(file_, where.c_str(), H5P_DEFAULT) < 0) {
    throw RunFileError("cannot replace " + where);
  }
  const h5::Handle group = h5::create_group(file_, where, where);
  const std::size_t count = report.bodies.size();
  std::vector<std::int32_t> body(count), broken(count);
  std::vector<std::int64_t> particles(count), fragments(count);
  std::vector<double> mass(count), largest(count), x10(count), x50(count), x90(count), fines(count);
  std::vector<std::int32_t> impacted(count);
  std::vector<double> impact_time(count), impact_speed(count), impact_angle(count);
  for (std::size_t r = 0; r < count; ++r) {
    const BodyStatistics& b = report.bodies[r];
    body[r] = b.body;
    broken[r] = b.broken ? 1 : 0;
    particles[r] = static_cast<std::int64_t>(b.particles);
    fragments[r] = static_cast<std::int64_t>(b.fragments);
    mass[r] = b.mass;
    largest[r] = b.largest_fraction;
    x10[r] = b.fsd.x10;
    x50[r] = b.fsd.x50;
    x90[r] = b.fsd.x90;
    fines[r] = b.fsd.fines_mass;
    impacted[r] = b.impacted ? 1 : 0;
    impact_time[r] = b.impact_time;
    impact_speed[r] = b.impact_speed;
    impact_angle[r] = b.impact_angle;
  }
  const hid_t g = group.get();
  h5::write_dataset(g, "body", H5T_NATIVE_INT32, {count}, body.data(), where + "/body");
  h5::write_dataset(g, "broken", H5T_NATIVE_INT32, {count}, broken.data(), where + "/broken");
  h5::write_dataset(g, "particles", H5T_NATIVE_INT64, {count}, particles.data(), where + "/particles");
  h5::write_dataset(g, "fragments", H5T_NATIVE_INT64, {count}, fragments.data(), where + "/fragments");
  h5::write_dataset(g, "mass", H5T_NATIVE_DOUBLE, {count}, mass.data(), where + "/mass");
  h5::write_dataset(g, "largest_fraction", H5T_NATIVE_DOUBLE, {count}, largest.data(), where + "/largest_fraction");
  h5::write_dataset(g, "x10", H5T_NATIVE_DOUBLE, {count}, x10.data(), where + "/x10");
  h5::write_dataset(g, "x50", H5T_NATIVE_DOUBLE, {count}, x50.data(), where + "/x50");
  h5::write_dataset(g, "x90", H5T_NATIVE_DOUBLE, {count}, x90.data(), where + "/x90");
  h5::write_dataset(g, "fines_mass", H5T_NATIVE_DOUBLE, {count}, fines.data(), where + "/fines_mass");
  h5::write_dataset(g, "impacted", H5T_NATIVE_INT32, {count}, impacted.data(), where + "/impacted");
  h5::write_dataset(g, "impact_time", H5T_NATIVE_DOUBLE, {count}, impact_time.data(), where + "/impact_time");
  h5::write_dataset(g, "impact_speed", H5T_NATIVE_DOUBLE, {count}, impact_speed.data(), where + "/impact_speed");
  h5::write_dataset(g, "impact_angle", H5T_NATIVE_DOUBLE, {count}, impact_angle.data(), where + "/impact_angle");
  h5::write_int_attribute(g, "count", static_cast<std::int64_t>(count), where);
  h5::write_int_attribute(g, "broken_count", static_cast<std::int64_t>(report.broken), where);
  h5::write_double_attribute(g, "breakage_probability", report.breakage_probability, where);
  h5::write_double_attribute(g, "intact_fraction", report.intact_fraction, where);
  h5::write_double_attribute(g, "x10", report.pooled.x10, where);
  h5::write_double_attribute(g, "x50", report.pooled.x50, where);
  h5::write_double_attribute(g, "x90", report.pooled.x90, where);
  h5::write_double_attribute(g, "fines_size", report.pooled.fines_size, where);
  h5::write_double_attribute(g, "fines_mass", report.pooled.fines_mass, where);
  H5Fflush(file_, H5F_SCOPE_GLOBAL);
}

}  // namespace shard::analysis
