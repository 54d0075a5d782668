#include "shard/run_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <numbers>
#include <type_traits>

#include "h5_io.hpp"
#include "run_layout.hpp"

namespace shard {

namespace {

using h5::frame_path;
constexpr std::size_t kAll = std::numeric_limits<std::size_t>::max();

const std::vector<std::string>& scalar_series_names() {
  static const std::vector<std::string> names{"step",         "time",        "kinetic_energy",
                                              "bond_energy",  "contact_energy",
                                              "bonds_intact", "bonds_broken", "contacts"};
  return names;
}

const std::vector<std::string>& event_column_names() {
  static const std::vector<std::string> names{
      "time",    "step",    "id_i",    "id_j",  "midpoint", "sigma_vm", "sigma_axial",
      "tau",     "tension", "bending", "shear", "torsion",  "mode"};
  return names;
}

constexpr std::array<const char*, 3> kWallQuantities{"force", "torque", "displacement"};
// Scalar wall columns; run files written before them lack them.
constexpr std::array<const char*, 2> kWallCounters{"impact_energy", "impacts"};

std::vector<Vec3> read_vec3(hid_t file, const std::string& path, std::size_t rows = kAll) {
  const h5::Shape shape = h5::dataset_shape(file, path);
  if (shape.cols != 3) throw OutputError("dataset '" + path + "' is not an [n,3] array");
  rows = std::min(rows, shape.rows);
  std::vector<Vec3> out(rows);
  if (rows > 0) h5::read_dataset(file, path, H5T_NATIVE_DOUBLE, out.front().data(), rows, 3);
  return out;
}

bool is_frame_name(const std::string& name) {
  if (name.empty() || name.size() > 18) return false;
  if (!std::all_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; })) return false;
  return frame_name(std::stoull(name)) == name;
}

// Per-particle masses rho 4/3 pi r^3 (rho: one value, or one per material id).
std::vector<double> masses_from_density(const std::vector<double>& rho, const FrameData& f, const std::string& source) {
  if (rho.empty()) throw OutputError("the density " + source + " holds no value");
  std::vector<double> mass(f.radius.size());
  for (std::size_t v = 0; v < mass.size(); ++v) {
    double value = rho[0];
    if (rho.size() > 1) {
      const std::int32_t m = f.material[v];
      if (m < 0 || static_cast<std::size_t>(m) >= rho.size())
        throw OutputError(fmt::format("the density {} has {} entries but particle row {} has material {}", source,
                                      rho.size(), v, m));
      value = rho[static_cast<std::size_t>(m)];
    }
    if (!(value > 0)) throw OutputError("the density " + source + " is not positive");
    const double r = f.radius[v];
    mass[v] = value * (4.0 / 3.0 * std::numbers::pi * r * r * r);
  }
  return mass;
}

}  // namespace

struct RunFile::Impl {
  std::filesystem::path path;
  RunFile::Mode mode = RunFile::Mode::read;
  h5::Handle file;
  std::vector<std::size_t> frames;  // numbers of the complete frames, ascending
  std::size_t series_rows = 0;
  std::size_t event_rows = 0;
  std::vector<std::string> walls;
  std::vector<haddr_t> addresses;  // of frames [0, addresses.size())
  std::string series_error, event_error;

  hid_t id() const { return file.get(); }

  std::size_t rows_of(const std::string& dataset) const {
    return h5::dataset_shape(id(), dataset).rows;
  }

  // A frame counts once its group opens and holds every attribute and dataset.
  static bool frame_complete(hid_t group) { return h5::frame_complete(group); }

  bool named_frame_complete(std::size_t k) const {
    try {
      return frame_complete(h5::open_group(id(), frame_path(k)).get());
    } catch (const OutputError&) {
      return false;
    }
  }

  h5::Handle open_frame(std::size_t k) const {
    if (k < addresses.size())
      return h5::check(H5Oopen_by_addr(id(), addresses[k]), H5Oclose,
                       fmt::format("opening frame {} by address", k));
    return h5::open_group(id(), frame_path(k));
  }

  // `shard run` writes frames 0, 1, 2, ... in order, so in its files the frames beyond the index
  // are probed by name up to the first absent or incomplete one. Iterating /frames instead
  // (H5Literate) crashed libhdf5 1.10.8 on a group whose dense link storage a SIGKILL had torn: it
  // freed a garbage pointer while releasing the link table (test_output_crash, 2 runs in 10).
  void scan_written_frames_beyond(std::size_t indexed) {
    for (std::size_t k = indexed; h5::path_exists(id(), frame_path(k)) && named_frame_complete(k); ++k)
      frames.push_back(k);
  }

  // Files written by other tools in the documented layout may number their frames with gaps; they
  // were not torn by a kill of `shard run`, so listing the group is safe.
  void scan_listed_frames() {
    for (const std::string& name : h5::child_names(h5::open_group(id(), "frames").get())) {
      if (!is_frame_name(name)) continue;
      const std::size_t k = std::stoull(name);
      if (named_frame_complete(k)) frames.push_back(k);
    }
  }

  // Frames through /frame_index (written so that a kill cannot tear it), then by name through
  // /frames for any beyond the index's capacity or in files without one.
  void scan_frames() {
    try {
      addresses = h5::read_frame_addresses(id());
    } catch (const OutputError&) {
      addresses.clear();
    }
    std::size_t indexed = 0;
    for (; indexed < addresses.size(); ++indexed) {
      try {
        if (!frame_complete(open_frame(indexed).get())) break;
      } catch (const OutputError&) {
        break;
      }
    }
    addresses.resize(indexed);
    for (std::size_t k = 0; k < indexed; ++k) frames.push_back(k);
    try {
      if (h5::path_exists(id(), "frame_index"))
        scan_written_frames_beyond(indexed);
      else
        scan_listed_frames();
    } catch (const OutputError&) {
      // A torn link index ends the frames found by name; those found by address remain.
    }
    std::sort(frames.begin(), frames.end());
  }

  // Why frame k is not readable, for the error message.
  std::string absent_frame(std::size_t k) const {
    std::string listed = "it holds no complete frame yet";
    if (frames.size() == 1) listed = fmt::format("its one complete frame is {}", frames.front());
    if (frames.size() > 1) listed = fmt::format("its complete frames are {} to {}", frames.front(), frames.back());
    if (h5::path_exists(id(), frame_path(k))) {
      std::string missing;
      try {
        missing = h5::frame_missing_part(h5::open_group(id(), frame_path(k)).get());
      } catch (const OutputError& error) {
        missing = error.what();
      }
      return fmt::format("frame {} of '{}' is incomplete (it lacks {}): the run was killed while writing it, or "
                         "the file was not written by `shard run`; {}",
                         k, path.string(), missing, listed);
    }
    return fmt::format("'{}' has no frame {} (/{}); {}", path.string(), k, frame_path(k), listed);
  }

  void require_writable() const {
    if (mode != RunFile::Mode::read_write)
      throw OutputError(fmt::format("'{}' was opened for reading; open it with RunFile::Mode::read_write to "
                                    "store analysis results",
                                    path.string()));
  }

  // Columns are written one after another; a killed run may hold a block in some and not in
  // others, so every reader sees the rows they all hold. A torn column makes the series
  // unreadable (the error is kept for read_series) without hiding the frames.
  void scan_series() {
    try {
      if (h5::path_exists(id(), "series/walls"))
        walls = h5::child_names(h5::open_group(id(), "series/walls").get());
      series_rows = kAll;
      for (const std::string& name : scalar_series_names())
        series_rows = std::min(series_rows, rows_of("series/" + name));
      for (const std::string& wall : walls) {
        for (const char* quantity : kWallQuantities)
          series_rows = std::min(series_rows, rows_of("series/walls/" + wall + "/" + quantity));
        for (const char* quantity : kWallCounters)
          if (h5::path_exists(id(), "series/walls/" + wall + "/" + quantity))
            series_rows = std::min(series_rows, rows_of("series/walls/" + wall + "/" + quantity));
      }
    } catch (const OutputError& error) {
      series_rows = 0;
      series_error = error.what();
    }
    try {
      event_rows = kAll;
      for (const std::string& name : event_column_names())
        event_rows = std::min(event_rows, rows_of("events/bond_breaks/" + name));
    } catch (const OutputError& error) {
      event_rows = 0;
      event_error = error.what();
    }
  }

  // A scalar series column, cut to the rows every column holds.
  template <class T>
  std::vector<T> series(const std::string& name) const {
    const auto& names = scalar_series_names();
    if (std::find(names.begin(), names.end(), name) == names.end())
      throw OutputError(fmt::format("no series '{}' in a run file; the series are: {}", name, fmt::join(names, ", ")));
    require_series();
    const h5::QuietErrors quiet;
    return h5::read_dataset<T>(id(), "series/" + name, 0, series_rows);
  }

  void require_series() const {
    if (!series_error.empty())
      throw OutputError("the series of '" + path.string() + "' are damaged: " + series_error);
  }
};

std::string frame_name(std::size_t k) { return fmt::format("{:06d}", k); }

RunFile::RunFile(const std::filesystem::path& path, Mode mode) {
  const h5::QuietErrors quiet;
  impl_ = std::make_unique<Impl>();
  impl_->path = path;
  impl_->mode = mode;
  impl_->file = h5::open_run_file(path, mode == Mode::read_write ? h5::RunAccess::read_write : h5::RunAccess::read);
  impl_->scan_frames();
  impl_->scan_series();
}

RunFile::~RunFile() = default;
RunFile::RunFile(RunFile&&) noexcept = default;
RunFile& RunFile::operator=(RunFile&&) noexcept = default;

const std::filesystem::path& RunFile::path() const { return impl_->path; }

namespace {

RunMetadata read_metadata(hid_t f) {
  RunMetadata meta;
  meta.shard_version = h5::read_string_attribute(f, "shard_version");
  meta.git_revision = h5::read_string_attribute(f, "git_revision");
  meta.scene_file = h5::read_string_attribute(f, "scene_file");
  meta.scene_text = h5::read_string_attribute(f, "scene");
  meta.seed = h5::read_uint_attribute(f, "seed");
  h5::Handle plugins = h5::open_group(f, "plugins");
  for (const std::string& name : h5::attribute_names(plugins.get()))
    meta.plugins.emplace_back(name, h5::read_string_attribute(plugins.get(), name));
  h5::Handle generator = h5::open_group(f, "generator");
  for (const std::string& name : h5::attribute_names(generator.get()))
    meta.generator_quality.emplace_back(name, h5::read_double_attribute(generator.get(), name));
  h5::Handle notes = h5::open_group(f, "notes");
  for (const std::string& name : h5::attribute_names(notes.get()))
    meta.notes.emplace_back(name, h5::read_string_attribute(notes.get(), name));
  return meta;
}

}  // namespace

RunMetadata RunFile::metadata() const {
  const h5::QuietErrors quiet;
  try {
    return read_metadata(impl_->id());
  } catch (const OutputError& error) {
    throw OutputError(fmt::format("'{}' lacks metadata that `shard run` writes ({}): give the run.h5 that `shard "
                                  "run` wrote",
                                  impl_->path.string(), error.what()));
  }
}

int RunFile::format_version() const {
  const h5::QuietErrors quiet;
  return static_cast<int>(h5::run_format_version(impl_->id()));
}

int RunFile::abi_version() const {
  const h5::QuietErrors quiet;
  if (!h5::has_attribute(impl_->id(), "abi_version"))
    throw OutputError(fmt::format("'{}' has no abi_version attribute: it was not written by `shard run`",
                                  impl_->path.string()));
  return static_cast<int>(h5::read_int_attribute(impl_->id(), "abi_version"));
}

const std::vector<std::size_t>& RunFile::frames() const { return impl_->frames; }

std::size_t RunFile::frame_count() const { return impl_->frames.size(); }

namespace {

void read_masses(hid_t frame, hid_t root, std::size_t k, std::optional<double> density, FrameData& f) {
  if (h5::path_exists(frame, "mass")) {
    f.mass = h5::read_dataset<double>(frame, "mass", 0);
    f.mass_source = "mass dataset";
    return;
  }
  std::vector<double> rho;
  std::string source;
  if (density) {
    rho = {*density};
    source = fmt::format("{} kg/m^3 (given)", *density);
  } else if (h5::has_attribute(frame, "density")) {
    rho = h5::read_double_array_attribute(frame, "density");
    source = fmt::format("attribute of /{}", frame_path(k));
  } else if (h5::has_attribute(root, "density")) {
    rho = h5::read_double_array_attribute(root, "density");
    source = "attribute of /";
  } else {
    throw OutputError(fmt::format("/{} has no mass dataset and the file no density attribute: give the particle "
                                  "density (e.g. --density 2500 for 2500 kg/m^3)",
                                  frame_path(k)));
  }
  f.mass = masses_from_density(rho, f, source);
  f.mass_source = "m = rho 4/3 pi r^3, density " + source;
}

}  // namespace

FrameData RunFile::read_frame(std::size_t k, std::optional<double> density) const {
  const h5::QuietErrors quiet;
  if (!std::binary_search(impl_->frames.begin(), impl_->frames.end(), k)) throw OutputError(impl_->absent_frame(k));
  FrameData frame;
  try {
    h5::Handle group = impl_->open_frame(k);
    const hid_t g = group.get();
    frame.step = h5::read_int_attribute(g, "step");
    frame.time = h5::read_double_attribute(g, "time");
    frame.id = h5::read_dataset<Index>(g, "id", 0);
    const std::size_t n = frame.id.size();
    frame.position = read_vec3(g, "position");
    frame.velocity = read_vec3(g, "velocity");
    frame.omega = read_vec3(g, "omega");
    frame.radius = h5::read_dataset<double>(g, "radius", 0);
    frame.material = h5::read_dataset<std::int32_t>(g, "material", 0);
    // Run files written before bodies existed hold one body.
    frame.body = h5::path_exists(g, "body") ? h5::read_dataset<std::int32_t>(g, "body", 0)
                                            : std::vector<std::int32_t>(n, 0);
    for (std::size_t size : {frame.position.size(), frame.velocity.size(), frame.omega.size(),
                             frame.radius.size(), frame.material.size(), frame.body.size()})
      if (size != n) throw OutputError("its particle arrays have different lengths");
    read_masses(g, impl_->id(), k, density, frame);
    if (frame.mass.size() != n) throw OutputError("its mass dataset has another length than its id dataset");
    const std::vector<Index> pairs = h5::read_dataset<Index>(g, "bonds", 2);
    frame.bond_i.resize(pairs.size() / 2);
    frame.bond_j.resize(pairs.size() / 2);
    for (std::size_t b = 0; b < frame.bond_i.size(); ++b) {
      frame.bond_i[b] = pairs[2 * b];
      frame.bond_j[b] = pairs[2 * b + 1];
    }
    if (h5::path_exists(g, "fragment")) frame.fragment = h5::read_dataset<Index>(g, "fragment", 0);
  } catch (const OutputError& error) {
    throw OutputError(fmt::format("frame {} of '{}': {}", k, impl_->path.string(), error.what()));
  }
  return frame;
}

std::size_t RunFile::series_rows() const { return impl_->series_rows; }

std::vector<double> RunFile::read_series(const std::string& name) const { return impl_->series<double>(name); }

std::vector<std::int64_t> RunFile::read_integer_series(const std::string& name) const {
  return impl_->series<std::int64_t>(name);
}

std::vector<std::string> RunFile::wall_names() const { return impl_->walls; }

std::vector<Vec3> RunFile::read_wall_series(const std::string& wall,
                                            const std::string& quantity) const {
  if (std::find(impl_->walls.begin(), impl_->walls.end(), wall) == impl_->walls.end())
    throw OutputError(fmt::format("no wall '{}' in '{}'; its walls are: {}", wall,
                                  impl_->path.string(), fmt::join(impl_->walls, ", ")));
  if (std::find(kWallQuantities.begin(), kWallQuantities.end(), quantity) ==
      kWallQuantities.end())
    throw OutputError(fmt::format("no wall quantity '{}'; use force, torque or displacement",
                                  quantity));
  impl_->require_series();
  const h5::QuietErrors quiet;
  return read_vec3(impl_->id(), "series/walls/" + wall + "/" + quantity, impl_->series_rows);
}

namespace {

template <class T>
std::vector<T> read_wall_counter(const RunFile& run, hid_t file, const std::vector<std::string>& walls,
                                 const std::string& wall, const std::string& quantity, std::size_t rows) {
  if (std::find(walls.begin(), walls.end(), wall) == walls.end())
    throw OutputError(fmt::format("no wall '{}' in '{}'; its walls are: {}", wall, run.path().string(),
                                  fmt::join(walls, ", ")));
  const std::string path = "series/walls/" + wall + "/" + quantity;
  if (!h5::path_exists(file, path))
    throw OutputError(fmt::format("'{}' has no {} for wall '{}': it was written before walls recorded it; run "
                                  "the scene again",
                                  run.path().string(), quantity, wall));
  const h5::QuietErrors quiet;
  return h5::read_dataset<T>(file, path, 0, rows);
}

}  // namespace

std::vector<double> RunFile::read_wall_impact_energy(const std::string& wall) const {
  impl_->require_series();
  return read_wall_counter<double>(*this, impl_->id(), impl_->walls, wall, "impact_energy", impl_->series_rows);
}

std::vector<std::int64_t> RunFile::read_wall_impacts(const std::string& wall) const {
  impl_->require_series();
  return read_wall_counter<std::int64_t>(*this, impl_->id(), impl_->walls, wall, "impacts", impl_->series_rows);
}

std::vector<BondBreakEvent> RunFile::read_break_events() const {
  if (!impl_->event_error.empty())
    throw OutputError("the bond-break log of '" + impl_->path.string() +
                      "' is damaged: " + impl_->event_error);
  const h5::QuietErrors quiet;
  const hid_t f = impl_->id();
  const std::size_t rows = impl_->event_rows;
  const std::string g = "events/bond_breaks/";
  const auto time = h5::read_dataset<double>(f, g + "time", 0, rows);
  const auto step = h5::read_dataset<std::int64_t>(f, g + "step", 0, rows);
  const auto id_i = h5::read_dataset<Index>(f, g + "id_i", 0, rows);
  const auto id_j = h5::read_dataset<Index>(f, g + "id_j", 0, rows);
  const auto midpoint = read_vec3(f, g + "midpoint", rows);
  const auto sigma_vm = h5::read_dataset<double>(f, g + "sigma_vm", 0, rows);
  const auto sigma_axial = h5::read_dataset<double>(f, g + "sigma_axial", 0, rows);
  const auto tau = h5::read_dataset<double>(f, g + "tau", 0, rows);
  const auto tension = h5::read_dataset<double>(f, g + "tension", 0, rows);
  const auto bending = h5::read_dataset<double>(f, g + "bending", 0, rows);
  const auto shear = h5::read_dataset<double>(f, g + "shear", 0, rows);
  const auto torsion = h5::read_dataset<double>(f, g + "torsion", 0, rows);
  const auto mode = h5::read_dataset<std::uint8_t>(f, g + "mode", 0, rows);
  std::vector<BondBreakEvent> events(rows);
  for (std::size_t k = 0; k < rows; ++k) {
    BondBreakEvent& e = events[k];
    e.time = time[k];
    e.step = step[k];
    e.id_i = id_i[k];
    e.id_j = id_j[k];
    e.midpoint = midpoint[k];
    e.stress.sigma_vm = sigma_vm[k];
    e.stress.sigma_axial = sigma_axial[k];
    e.stress.tau = tau[k];
    e.stress.tension = tension[k];
    e.stress.bending = bending[k];
    e.stress.shear = shear[k];
    e.stress.torsion = torsion[k];
    e.stress.dominant = static_cast<BondFailureMode>(mode[k]);
  }
  return events;
}

std::vector<BodyImpact> RunFile::read_body_impacts() const {
  const h5::QuietErrors quiet;
  const hid_t f = impl_->id();
  if (!h5::path_exists(f, "body_impacts")) return {};
  const h5::Handle g = h5::open_group(f, "body_impacts");
  const auto hit = h5::read_dataset<std::int32_t>(g.get(), "hit", 0);
  const auto step = h5::read_dataset<std::int64_t>(g.get(), "step", 0);
  const auto time = h5::read_dataset<double>(g.get(), "time", 0);
  const auto velocity = h5::read_dataset<double>(g.get(), "velocity", 3);
  const auto normal = h5::read_dataset<double>(g.get(), "normal", 3);
  const auto wall = h5::read_dataset<std::int32_t>(g.get(), "wall", 0);
  const std::size_t n = hit.size();
  if (step.size() != n || time.size() != n || velocity.size() != 3 * n || normal.size() != 3 * n || wall.size() != n)
    throw OutputError(fmt::format("/body_impacts of '{}' has columns of different lengths", impl_->path.string()));
  std::vector<BodyImpact> out(n);
  for (std::size_t b = 0; b < n; ++b) {
    out[b].hit = hit[b] != 0;
    out[b].step = step[b];
    out[b].time = time[b];
    out[b].velocity = Vec3(velocity[3 * b], velocity[3 * b + 1], velocity[3 * b + 2]);
    out[b].normal = Vec3(normal[3 * b], normal[3 * b + 1], normal[3 * b + 2]);
    out[b].wall = wall[b];
  }
  return out;
}

namespace {

// Writes one column, of whichever element type it holds, as a dataset `name` below group.
void write_column(hid_t group, const std::string& name, const RunTable::Column& column) {
  std::visit(
      [&](const auto& values) {
        using Value = typename std::decay_t<decltype(values)>::value_type;
        if constexpr (std::is_same_v<Value, Vec3>)
          h5::write_dataset(group, name, values.empty() ? nullptr : values.front().data(), values.size(), 3);
        else if constexpr (std::is_same_v<Value, std::string>)
          h5::write_string_dataset(group, name, values);
        else
          h5::write_dataset(group, name, values.data(), values.size());
      },
      column);
}

// Replaces `group` below the open file f with the table, parents first (HDF5 creates one level at a
// time), then flushes so a crash after it leaves the table readable.
void write_table_into(hid_t f, const std::string& path, std::string group, const RunTable& table) {
  if (group.starts_with('/')) group.erase(0, 1);
  for (std::size_t slash = group.find('/'); slash != std::string::npos; slash = group.find('/', slash + 1))
    if (!h5::path_exists(f, group.substr(0, slash))) h5::create_group(f, group.substr(0, slash));
  h5::remove_link(f, group);
  h5::Handle g = h5::create_group(f, group);
  for (const auto& [name, column] : table.columns) write_column(g.get(), name, column);
  for (const auto& [name, figure] : table.figures)
    std::visit([&](const auto& value) { h5::write_attribute(g.get(), name, value); }, figure);
  h5::check(H5Fflush(f, H5F_SCOPE_GLOBAL), "flushing '" + path + "'");
}

}  // namespace

void RunFile::write_fragment_labels(std::size_t k, const std::vector<Index>& labels) {
  impl_->require_writable();
  const h5::QuietErrors quiet;
  if (!std::binary_search(impl_->frames.begin(), impl_->frames.end(), k)) throw OutputError(impl_->absent_frame(k));
  h5::Handle group = impl_->open_frame(k);
  const std::size_t n = h5::dataset_shape(group.get(), "id").rows;
  if (labels.size() != n)
    throw OutputError(fmt::format("{} fragment labels for the {} particles of frame {} of '{}'", labels.size(), n, k,
                                  impl_->path.string()));
  h5::remove_link(group.get(), "fragment");
  h5::write_dataset(group.get(), "fragment", labels.data(), n);
  h5::check(H5Fflush(impl_->id(), H5F_SCOPE_GLOBAL), "flushing '" + impl_->path.string() + "'");
}

void RunFile::write_table(const std::string& group, const RunTable& table) {
  impl_->require_writable();
  const h5::QuietErrors quiet;
  write_table_into(impl_->id(), impl_->path.string(), group, table);
}

void write_table_file(const std::filesystem::path& file, const std::string& group, const RunTable& table) {
  const h5::QuietErrors quiet;
  std::error_code absent;
  const bool exists = std::filesystem::exists(file, absent);
  const hid_t id = exists ? H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)
                          : H5Fcreate(file.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, H5P_DEFAULT);
  if (id < 0)
    throw OutputError(fmt::format("cannot {} '{}' for a table: check the folder exists and is writable",
                                  exists ? "open" : "create", file.string()));
  const h5::Handle handle(id, H5Fclose);
  write_table_into(id, file.string(), group, table);
}

}  // namespace shard
