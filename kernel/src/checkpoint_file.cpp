// Checkpoint files (layout in docs/how-to/restart-a-run.md, "The checkpoint file"): one small HDF5 file beside the run
// file, replaced atomically. Kept apart from run.h5 on purpose: the run file's crash safety rests
// on flushing only at frames and never rewriting an object (output/run_writer.cpp), while a
// checkpoint is rewritten every time.
#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <system_error>

#include "h5_io.hpp"
#include "shard/checkpoint.hpp"

namespace shard {
namespace {

constexpr const char* kFormat = "shard checkpoint";
constexpr std::int64_t kFormatVersion = 1;

// Which rows of the whole file a dataset's rows are, when several processes write it at once.
enum class Table { particles, bonds, contacts, shared };

// How this process writes the file: the whole of it (no share), or its share of the particles,
// bonds and contacts, the shared tables by one process only.
struct Layout {
  const CheckpointShare* share = nullptr;
  hid_t transfer = H5P_DEFAULT;
};

// `rows` rows of `cols` (0: a 1-D dataset); `per_row`: values per row of the table (a flat array of
// `per_row` values per bond or contact).
template <class T>
void put_rows(hid_t group, const std::string& name, const T* data, std::size_t rows, std::size_t cols,
              const Layout& l, Table table, std::size_t per_row = 1) {
  if (!l.share) {
    h5::write_dataset(group, name, data, rows, cols);
    return;
  }
  if (table == Table::shared) {
    h5::write_dataset_part(group, name, data, 0, l.share->writes_shared ? rows : 0, rows, cols, l.transfer);
    return;
  }
  const CheckpointRows& r = table == Table::particles ? l.share->particles
                            : table == Table::bonds   ? l.share->bonds
                                                      : l.share->contacts;
  h5::write_dataset_part(group, name, data, r.first * per_row, rows, r.total * per_row, cols, l.transfer);
}

template <class T>
void put(hid_t group, const std::string& name, const std::vector<T>& v, const Layout& l, Table t, std::size_t per_row = 1) {
  put_rows(group, name, v.data(), v.size(), 0, l, t, per_row);
}
void put(hid_t group, const std::string& name, const std::vector<Vec3>& v, const Layout& l, Table t) {
  put_rows(group, name, v.empty() ? nullptr : v.front().data(), v.size(), 3, l, t);
}
void put(hid_t group, const std::string& name, const std::vector<Quat>& v, const Layout& l, Table t) {
  put_rows(group, name, v.empty() ? nullptr : v.front().coeffs().data(), v.size(), 4, l, t);
}

template <class T>
std::vector<T> get(hid_t group, const std::string& name) {
  return h5::read_dataset<T>(group, name, 0);
}
std::vector<Vec3> get_vec3(hid_t group, const std::string& name) {
  const std::vector<double> flat = h5::read_dataset<double>(group, name, 3);
  std::vector<Vec3> out(flat.size() / 3);
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = Vec3(flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]);
  return out;
}
std::vector<Quat> get_quat(hid_t group, const std::string& name) {
  const std::vector<double> flat = h5::read_dataset<double>(group, name, 4);
  std::vector<Quat> out(flat.size() / 4);
  // Eigen stores (x, y, z, w); the constructor takes (w, x, y, z).
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = Quat(flat[4 * k + 3], flat[4 * k], flat[4 * k + 1], flat[4 * k + 2]);
  return out;
}

constexpr std::size_t kStressColumns = 7;
std::vector<double> stress_table(const std::vector<BondStress>& s) {
  std::vector<double> t;
  t.reserve(s.size() * kStressColumns);
  for (const auto& x : s) t.insert(t.end(), {x.sigma_axial, x.tau, x.sigma_vm, x.tension, x.bending, x.shear, x.torsion});
  return t;
}
std::vector<std::uint8_t> mode_column(const std::vector<BondStress>& s) {
  std::vector<std::uint8_t> m;
  m.reserve(s.size());
  for (const auto& x : s) m.push_back(static_cast<std::uint8_t>(x.dominant));
  return m;
}
std::vector<BondStress> read_stress(hid_t group, const std::string& table, const std::string& mode) {
  const std::vector<double> t = h5::read_dataset<double>(group, table, kStressColumns);
  const std::vector<std::uint8_t> m = get<std::uint8_t>(group, mode);
  if (m.size() * kStressColumns != t.size()) throw CheckpointError("'" + table + "' and '" + mode + "' differ in length");
  std::vector<BondStress> out(m.size());
  for (std::size_t k = 0; k < m.size(); ++k) {
    const double* r = t.data() + k * kStressColumns;
    out[k] = {r[0], r[1], r[2], r[3], r[4], r[5], r[6], static_cast<BondFailureMode>(m[k])};
  }
  return out;
}

void write_particles(hid_t file, const Particles& p, const Layout& l) {
  h5::Handle g = h5::create_group(file, "particles");
  put(g.get(), "position", p.position, l, Table::particles);
  put(g.get(), "velocity", p.velocity, l, Table::particles);
  put(g.get(), "orientation", p.orientation, l, Table::particles);
  put(g.get(), "omega", p.omega, l, Table::particles);
  put(g.get(), "force", p.force, l, Table::particles);
  put(g.get(), "torque", p.torque, l, Table::particles);
  put(g.get(), "radius", p.radius, l, Table::particles);
  put(g.get(), "mass", p.mass, l, Table::particles);
  put(g.get(), "inertia", p.inertia, l, Table::particles);
  put(g.get(), "material", p.material, l, Table::particles);
  put(g.get(), "flags", p.flags, l, Table::particles);
  put(g.get(), "id", p.id, l, Table::particles);
  put(g.get(), "body", p.body, l, Table::particles);
}

Particles read_particles(hid_t file) {
  h5::Handle g = h5::open_group(file, "particles");
  Particles p;
  p.position = get_vec3(g.get(), "position");
  p.velocity = get_vec3(g.get(), "velocity");
  p.orientation = get_quat(g.get(), "orientation");
  p.omega = get_vec3(g.get(), "omega");
  p.force = get_vec3(g.get(), "force");
  p.torque = get_vec3(g.get(), "torque");
  p.radius = get<double>(g.get(), "radius");
  p.mass = get<double>(g.get(), "mass");
  p.inertia = get<double>(g.get(), "inertia");
  p.material = get<std::int32_t>(g.get(), "material");
  p.flags = get<std::uint8_t>(g.get(), "flags");
  p.id = get<Index>(g.get(), "id");
  // Checkpoints written before bodies existed hold one body: every particle in body 0.
  p.body = h5::path_exists(g.get(), "body") ? get<std::int32_t>(g.get(), "body") : std::vector<std::int32_t>(p.id.size(), 0);
  return p;
}

void write_bonds(hid_t file, const Bonds& b, const Layout& l) {
  h5::Handle g = h5::create_group(file, "bonds");
  h5::write_attribute(g.get(), "stride", static_cast<std::int64_t>(b.stride));
  const Table t = Table::bonds;
  put(g.get(), "i", b.i, l, t);
  put(g.get(), "j", b.j, l, t);
  put(g.get(), "state", b.state, l, t, b.stride);
  if (b.keeps_loads) {
    put(g.get(), "force", b.force, l, t);
    put(g.get(), "torque_i", b.torque_i, l, t);
    put(g.get(), "torque_j", b.torque_j, l, t);
    put(g.get(), "energy", b.energy, l, t);
  }
  put(g.get(), "broken", b.broken, l, t);
  put_rows(g.get(), "stress", stress_table(b.stress).data(), b.stress.size(), kStressColumns, l, t);
  put(g.get(), "mode", mode_column(b.stress), l, t);
}

Bonds read_bonds(hid_t file) {
  h5::Handle g = h5::open_group(file, "bonds");
  Bonds b;
  b.stride = static_cast<std::size_t>(h5::read_int_attribute(g.get(), "stride"));
  b.i = get<Index>(g.get(), "i");
  b.j = get<Index>(g.get(), "j");
  b.state = get<double>(g.get(), "state");
  b.keeps_loads = h5::path_exists(g.get(), "force");
  if (b.keeps_loads) {
    b.force = get_vec3(g.get(), "force");
    b.torque_i = get_vec3(g.get(), "torque_i");
    b.torque_j = get_vec3(g.get(), "torque_j");
    b.energy = get<double>(g.get(), "energy");
  }
  b.broken = get<std::uint8_t>(g.get(), "broken");
  b.stress = read_stress(g.get(), "stress", "mode");
  return b;
}

void write_events(hid_t file, const std::vector<BondBreakEvent>& events, const Layout& l) {
  h5::Handle g = h5::create_group(file, "events");
  std::vector<double> time;
  std::vector<std::int64_t> step;
  std::vector<Index> id_i, id_j;
  std::vector<Vec3> midpoint;
  std::vector<BondStress> stress;
  for (const auto& e : events) {
    time.push_back(e.time);
    step.push_back(e.step);
    id_i.push_back(e.id_i);
    id_j.push_back(e.id_j);
    midpoint.push_back(e.midpoint);
    stress.push_back(e.stress);
  }
  const Table t = Table::shared;
  put(g.get(), "time", time, l, t);
  put(g.get(), "step", step, l, t);
  put(g.get(), "id_i", id_i, l, t);
  put(g.get(), "id_j", id_j, l, t);
  put(g.get(), "midpoint", midpoint, l, t);
  put_rows(g.get(), "stress", stress_table(stress).data(), stress.size(), kStressColumns, l, t);
  put(g.get(), "mode", mode_column(stress), l, t);
}

std::vector<BondBreakEvent> read_events(hid_t file) {
  h5::Handle g = h5::open_group(file, "events");
  const auto time = get<double>(g.get(), "time");
  const auto step = get<std::int64_t>(g.get(), "step");
  const auto id_i = get<Index>(g.get(), "id_i");
  const auto id_j = get<Index>(g.get(), "id_j");
  const auto midpoint = get_vec3(g.get(), "midpoint");
  const auto stress = read_stress(g.get(), "stress", "mode");
  const std::size_t n = time.size();
  if (step.size() != n || id_i.size() != n || id_j.size() != n || midpoint.size() != n || stress.size() != n)
    throw CheckpointError("the break log's columns differ in length");
  std::vector<BondBreakEvent> events(n);
  for (std::size_t k = 0; k < n; ++k) events[k] = {time[k], step[k], id_i[k], id_j[k], midpoint[k], stress[k]};
  return events;
}

void write_walls(hid_t file, const std::vector<WallState>& walls, const Layout& l) {
  h5::Handle g = h5::create_group(file, "walls");
  std::vector<Vec3> velocity, displacement, force, torque;
  std::vector<double> contact_work, stored_energy;
  std::vector<std::int64_t> impacts;
  std::vector<Vec3> point;
  for (const auto& w : walls) {
    point.push_back(w.point);
    velocity.push_back(w.velocity);
    displacement.push_back(w.displacement);
    force.push_back(w.force);
    torque.push_back(w.torque);
    contact_work.push_back(w.contact_work);
    stored_energy.push_back(w.stored_energy);
    impacts.push_back(w.impacts);
  }
  put(g.get(), "velocity", velocity, l, Table::shared);
  put(g.get(), "displacement", displacement, l, Table::shared);
  put(g.get(), "force", force, l, Table::shared);
  put(g.get(), "torque", torque, l, Table::shared);
  put(g.get(), "contact_work", contact_work, l, Table::shared);
  put(g.get(), "stored_energy", stored_energy, l, Table::shared);
  put(g.get(), "impacts", impacts, l, Table::shared);
  put(g.get(), "point", point, l, Table::shared);
}

// A column that checkpoints written before it existed lack: `fallback` for each of n rows.
template <class T>
std::vector<T> get_or(hid_t group, const std::string& name, std::size_t n, T fallback) {
  if (!h5::path_exists(group, name)) return std::vector<T>(n, fallback);
  return get<T>(group, name);
}

std::vector<WallState> read_walls(hid_t file) {
  h5::Handle g = h5::open_group(file, "walls");
  const auto velocity = get_vec3(g.get(), "velocity");
  const auto displacement = get_vec3(g.get(), "displacement");
  const auto force = get_vec3(g.get(), "force");
  const auto torque = get_vec3(g.get(), "torque");
  const std::size_t n = velocity.size();
  // Checkpoints before the wear indicator was kept: nothing recorded yet.
  const auto contact_work = get_or<double>(g.get(), "contact_work", n, 0.0);
  const auto stored_energy = get_or<double>(g.get(), "stored_energy", n, 0.0);
  const auto impacts = get_or<std::int64_t>(g.get(), "impacts", n, 0);
  // Checkpoints before walls could be seated after settling: the scene's point (WallState::point).
  const auto point = h5::path_exists(g.get(), "point") ? get_vec3(g.get(), "point") : std::vector<Vec3>(n, WallState{}.point);
  if (point.size() != n || displacement.size() != n || force.size() != n || torque.size() != n || contact_work.size() != n ||
      stored_energy.size() != n || impacts.size() != n)
    throw CheckpointError("the wall columns differ in length");
  std::vector<WallState> walls(n);
  for (std::size_t k = 0; k < n; ++k)
    walls[k] = {velocity[k], displacement[k], force[k], torque[k], contact_work[k], stored_energy[k], impacts[k], point[k]};
  return walls;
}

void write_neighbours(hid_t file, const NeighbourState& s, const Layout& l) {
  h5::Handle g = h5::create_group(file, "neighbours");
  h5::write_attribute(g.get(), "skin", s.skin);
  h5::write_attribute(g.get(), "history_stride", static_cast<std::int64_t>(s.history_stride));
  h5::write_attribute(g.get(), "rebuilds", s.rebuilds);
  // A share's contacts are touching pairs without build positions (the importer rebuilds the
  // list): those are empty on every process, written as shared.
  put(g.get(), "first", s.first, l, Table::contacts);
  put(g.get(), "second", s.second, l, Table::contacts);
  put(g.get(), "history", s.history, l, Table::contacts, s.history_stride);
  put(g.get(), "position_at_build", s.position_at_build, l, Table::shared);
  put(g.get(), "wall_displacement_at_build", s.wall_displacement_at_build, l, Table::shared);
  put(g.get(), "wall_angle_at_build", s.wall_angle_at_build, l, Table::shared);
  put(g.get(), "wall_reach", s.wall_reach, l, Table::shared);
  put(g.get(), "touching", s.touching, l, Table::contacts);
}

NeighbourState read_neighbours(hid_t file) {
  h5::Handle g = h5::open_group(file, "neighbours");
  NeighbourState s;
  s.skin = h5::read_double_attribute(g.get(), "skin");
  s.history_stride = static_cast<std::size_t>(h5::read_int_attribute(g.get(), "history_stride"));
  s.rebuilds = h5::read_int_attribute(g.get(), "rebuilds");
  s.first = get<Index>(g.get(), "first");
  s.second = get<Index>(g.get(), "second");
  s.history = get<double>(g.get(), "history");
  s.position_at_build = get_vec3(g.get(), "position_at_build");
  s.wall_displacement_at_build = get_vec3(g.get(), "wall_displacement_at_build");
  // Absent from checkpoints written before walls could spin (NeighbourList::restore fills them).
  if (h5::path_exists(g.get(), "wall_angle_at_build")) {
    s.wall_angle_at_build = get<double>(g.get(), "wall_angle_at_build");
    s.wall_reach = get<double>(g.get(), "wall_reach");
  }
  if (h5::path_exists(g.get(), "touching")) s.touching = get<std::uint8_t>(g.get(), "touching");
  return s;
}

void write_run(hid_t file, const Checkpoint& c, const Layout& l) {
  h5::Handle g = h5::create_group(file, "run");
  for (const auto& [name, value] : c.numbers) h5::write_attribute(g.get(), name, value);
  for (const auto& [name, values] : c.arrays) put(g.get(), name, values, l, Table::shared);
}

void read_run(hid_t file, Checkpoint& c) {
  h5::Handle g = h5::open_group(file, "run");
  for (const auto& name : h5::attribute_names(g.get())) c.numbers.emplace_back(name, h5::read_double_attribute(g.get(), name));
  for (const auto& name : h5::child_names(g.get())) c.arrays.emplace_back(name, get<double>(g.get(), name));
}

void write_file(const std::filesystem::path& path, const Checkpoint& c, const Layout& l,
                const std::function<void(std::int64_t)>& configure_access) {
  const SimulationState& s = c.simulation;
  h5::Handle creation = h5::plist_handle(H5Pcreate(H5P_FILE_CREATE), "creating file creation list");
  h5::check(H5Pset_attr_creation_order(creation.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
            "tracking attribute order");
  h5::Handle access = h5::plist_handle(H5Pcreate(H5P_FILE_ACCESS), "creating file access list");
  if (configure_access) configure_access(access.get());
  h5::Handle file = h5::file_handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, creation.get(), access.get()),
                                    "creating the checkpoint '" + path.string() + "'");
  const hid_t f = file.get();
  h5::write_attribute(f, "format", std::string(kFormat));
  h5::write_attribute(f, "format_version", kFormatVersion);
  h5::write_attribute(f, "step", s.step);
  h5::write_attribute(f, "time", s.time);
  h5::write_attribute(f, "dt", s.dt);
  h5::write_attribute(f, "bonds_broken", s.bonds_broken);
  h5::write_attribute(f, "events_taken", static_cast<std::int64_t>(s.events_taken));
  h5::write_attribute(f, "contacts", static_cast<std::int64_t>(s.contacts));
  h5::write_attribute(f, "contact_energy", s.contact_energy);
  h5::write_attribute(f, "bond_energy", s.bond_energy);
  write_particles(f, s.particles, l);
  write_bonds(f, s.bonds, l);
  write_events(f, s.events, l);
  write_walls(f, s.walls, l);
  write_neighbours(f, s.neighbours, l);
  write_run(f, c, l);
  // Everything reaches the file here, so a full disk is reported here; closing writes nothing more.
  h5::check(H5Fflush(f, H5F_SCOPE_GLOBAL), "flushing the checkpoint");
}

CheckpointError not_written(const std::filesystem::path& path, const std::exception& e) {
  return CheckpointError(fmt::format("cannot write the checkpoint '{}': {}. The previous checkpoint (if any) is "
                                     "kept; free disk space or choose a writable output folder",
                                     path.string(), e.what()));
}

// HDF5 has written and closed the file; the data may still sit in the page cache. fsync makes
// the rename below publish a file whose bytes are on the disk.
void sync_to_disk(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int error = errno;
    if (fd >= 0) ::close(fd);
    throw CheckpointError(fmt::format("cannot flush '{}' to disk: {}", path.string(), std::strerror(error)));
  }
  ::close(fd);
}

}  // namespace

double Checkpoint::number(const std::string& name) const {
  for (const auto& [n, v] : numbers)
    if (n == name) return v;
  throw CheckpointError("the checkpoint has no value '" + name + "'; it was written by another version of shard");
}

const std::vector<double>& Checkpoint::array(const std::string& name) const {
  for (const auto& [n, v] : arrays)
    if (n == name) return v;
  throw CheckpointError("the checkpoint has no array '" + name + "'; it was written by another version of shard");
}

std::filesystem::path checkpoint_path_for(const std::filesystem::path& run_file) {
  std::filesystem::path p = run_file;
  p.replace_extension(".checkpoint.h5");
  return p;
}

std::filesystem::path checkpoint_temporary_for(const std::filesystem::path& path) {
  std::filesystem::path temporary = path;
  temporary += ".tmp";
  return temporary;
}

void write_checkpoint(const std::filesystem::path& path, const Checkpoint& checkpoint) {
  const std::filesystem::path temporary = checkpoint_temporary_for(path);
  try {
    const h5::QuietErrors quiet;
    write_file(temporary, checkpoint, Layout{}, {});
  } catch (const std::exception& e) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw not_written(path, e);
  }
  publish_checkpoint(temporary, path);
}

void write_checkpoint_share(const std::filesystem::path& temporary, const CheckpointShare& share) {
  if (!share.checkpoint) throw std::invalid_argument("write_checkpoint_share: no checkpoint given");
  try {
    const h5::QuietErrors quiet;
    h5::Handle transfer = h5::plist_handle(H5Pcreate(H5P_DATASET_XFER), "creating a transfer list");
    if (share.configure_transfer) share.configure_transfer(transfer.get());
    write_file(temporary, *share.checkpoint, Layout{&share, transfer.get()}, share.configure);
  } catch (const std::exception& e) {
    throw not_written(temporary, e);
  }
}

void publish_checkpoint(const std::filesystem::path& temporary, const std::filesystem::path& path) {
  try {
    sync_to_disk(temporary);
  } catch (const std::exception& e) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw not_written(path, e);
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error)
    throw CheckpointError(fmt::format("cannot move the checkpoint into place as '{}': {}", path.string(), error.message()));
}

Checkpoint read_checkpoint(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    throw CheckpointError(fmt::format("no checkpoint '{}': a run writes it beside its run file at every frame and on "
                                      "SIGINT; restart a run that wrote at least one frame",
                                      path.string()));
  try {
    const h5::QuietErrors quiet;
    h5::Handle file = h5::file_handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "opening");
    const hid_t f = file.get();
    if (!h5::has_attribute(f, "format") || h5::read_string_attribute(f, "format") != kFormat)
      throw CheckpointError("not a shard checkpoint");
    const std::int64_t version = h5::read_int_attribute(f, "format_version");
    if (version != kFormatVersion)
      throw CheckpointError(fmt::format("format version {} (this shard reads {})", version, kFormatVersion));
    Checkpoint c;
    SimulationState& s = c.simulation;
    s.step = h5::read_int_attribute(f, "step");
    s.time = h5::read_double_attribute(f, "time");
    s.dt = h5::read_double_attribute(f, "dt");
    s.bonds_broken = h5::read_int_attribute(f, "bonds_broken");
    s.events_taken = static_cast<std::size_t>(h5::read_int_attribute(f, "events_taken"));
    s.contacts = static_cast<std::size_t>(h5::read_int_attribute(f, "contacts"));
    s.contact_energy = h5::read_double_attribute(f, "contact_energy");
    s.particles = read_particles(f);
    s.bonds = read_bonds(f);
    // Checkpoints before the attribute kept every bond's energy instead.
    if (h5::has_attribute(f, "bond_energy")) {
      s.bond_energy = h5::read_double_attribute(f, "bond_energy");
    } else {
      for (double e : s.bonds.energy) s.bond_energy += e;
    }
    s.events = read_events(f);
    s.walls = read_walls(f);
    s.neighbours = read_neighbours(f);
    read_run(f, c);
    return c;
  } catch (const std::exception& e) {
    throw CheckpointError(fmt::format("cannot read the checkpoint '{}': {}", path.string(), e.what()));
  }
}

}  // namespace shard
