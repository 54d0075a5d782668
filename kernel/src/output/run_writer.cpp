// RunWriter: the HDF5 run file and its XDMF index.
//
// Crash safety. HDF5 1.10 writes metadata in no crash-safe order: a kill inside H5Fflush can
// leave a group's header or link B-tree pointing at blocks not yet written (measured with
// tests/output/test_crash_safety.cpp (ctest test_output_crash) and a 1500-kill soak: about 1 kill in 150 lost /frames).
// So:
//  - metadata reaches the file only in H5Fflush (cache evictions off), once or twice per frame,
//    never between frames: a kill between flushes cannot tear anything;
//  - a frame's objects are created once and never modified after its flush;
//  - /frame_index, a contiguous dataset allocated at creation, receives each frame group's
//    object address as raw bytes overwritten in place (no metadata changes), so a reader finds
//    every flushed frame even when the /frames link index was torn;
//  - the 1.8 object format (libver low bound V18): a 1.10 superblock (v3) records "open for
//    writing" and HDF5 then refuses to open a killed run's file until `h5clear -s` is run;
//  - paged file-space aggregation: no metadata object smaller than a page straddles two pages.
//    A write that SIGKILL interrupts stops at a page boundary (the kernel copies page by page
//    and checks for a fatal signal between pages), so an object header rewritten in place at
//    every flush (each /series and /events column's extent) is either old or new, never torn
//    (across a boundary, its checksum fails and the column is lost).
// SWMR would order the flushes, but HDF5 1.10 forbids creating groups and datasets in SWMR
// mode, and every frame is a new group.
#include <fmt/format.h>

#include <cstdio>
#include <optional>
#include <system_error>

#include "break_event_writer.hpp"
#include "frame_writer.hpp"
#include "h5_io.hpp"
#include "run_layout.hpp"
#include "series_writer.hpp"
#include "shard/output.hpp"
#include "shard/plugin.hpp"
#include "xdmf_index.hpp"

namespace shard {

namespace {

// Rows buffered before a block is handed to HDF5.
constexpr std::size_t kBlockRows = 1024;
// Frames addressable through /frame_index (8 bytes each, allocated at creation); later frames
// are reachable through /frames only.
constexpr std::size_t kFrameIndexCapacity = 65536;

std::filesystem::path xmf_path_of(const std::filesystem::path& h5_path) {
  std::filesystem::path xmf = h5_path;
  xmf.replace_extension(".xmf");
  return xmf;
}

void make_parent_folder(const std::filesystem::path& path) {
  const std::filesystem::path parent = path.parent_path();
  if (parent.empty()) return;
  std::error_code error;
  std::filesystem::create_directories(parent, error);
  if (error)
    throw OutputError("cannot create the folder '" + parent.string() + "' for the run file '" +
                      path.string() + "': " + error.message() +
                      ". Choose an output path in a folder you can write to.");
}

// The metadata cache normally writes dirty entries whenever it evicts them, i.e. at arbitrary
// moments between flushes: a kill then finds, say, a group's header pointing at a continuation
// chunk that never reached the disk, and every frame is lost (measured: 3 of 400 kills).
// With evictions off, metadata reaches the file only in H5Fflush.
void hold_metadata_until_flush(hid_t access) {
  H5AC_cache_config_t config{};
  config.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  h5::check(H5Pget_mdc_config(access, &config), "reading the metadata cache settings");
  config.evictions_enabled = false;
  config.incr_mode = H5C_incr__off;
  config.flash_incr_mode = H5C_flash_incr__off;
  config.decr_mode = H5C_decr__off;
  h5::check(H5Pset_mdc_config(access, &config), "holding metadata until flush");
}

// The page is the kernel's (4 KiB), the unit a killed write is completed in.
void page_metadata(hid_t creation) {
  constexpr hsize_t kPageBytes = 4096;
  h5::check(H5Pset_file_space_strategy(creation, H5F_FSPACE_STRATEGY_PAGE, false, 1),
            "selecting paged file-space aggregation");
  h5::check(H5Pset_file_space_page_size(creation, kPageBytes), "setting the file-space page size");
}

h5::Handle create_file(const std::filesystem::path& path, const RunWriterAccess& shared) {
  h5::Handle access = h5::plist_handle(H5Pcreate(H5P_FILE_ACCESS), "creating file access list");
  if (shared.configure) shared.configure(access.get());
  h5::check(H5Pset_libver_bounds(access.get(), H5F_LIBVER_V18, H5F_LIBVER_LATEST),
            "selecting the file format");
  hold_metadata_until_flush(access.get());
  h5::Handle creation =
      h5::plist_handle(H5Pcreate(H5P_FILE_CREATE), "creating file creation list");
  page_metadata(creation.get());
  h5::check(H5Pset_attr_creation_order(creation.get(),
                                       H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
            "tracking attribute order");
  const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, creation.get(), access.get());
  if (id < 0) {
    const std::string cause = h5::take_error_stack();
    throw OutputError("cannot create the run file '" + path.string() + "'" +
                      (cause.empty() ? "" : " (" + cause + ")") +
                      ". Check that the folder exists and is writable and that no other "
                      "program has the file open, or choose another output path.");
  }
  return h5::Handle(id, H5Fclose);
}

h5::Handle create_run_file(const std::filesystem::path& path, const RunMetadata& meta,
                           const RunWriterAccess& shared) {
  h5::Handle handle = create_file(path, shared);
  const hid_t file = handle.get();
  h5::write_attribute(file, "shard_version", meta.shard_version);
  h5::write_attribute(file, "git_revision", meta.git_revision);
  h5::write_attribute(file, "scene_file", meta.scene_file);
  h5::write_attribute(file, "scene", meta.scene_text);
  h5::write_attribute(file, "seed", meta.seed);
  h5::write_attribute(file, "abi_version", static_cast<std::int64_t>(kAbiVersion));
  h5::write_run_format_version(file);
  h5::Handle plugins = h5::create_group(file, "plugins");
  for (const auto& [name, description] : meta.plugins)
    h5::write_attribute(plugins.get(), name, description);
  h5::Handle generator = h5::create_group(file, "generator");
  for (const auto& [name, value] : meta.generator_quality)
    h5::write_attribute(generator.get(), name, value);
  h5::Handle notes = h5::create_group(file, "notes");
  for (const auto& [name, text] : meta.notes) h5::write_attribute(notes.get(), name, text);
  return handle;
}

}  // namespace

struct RunWriter::Impl {
  Impl(const std::filesystem::path& file_path, const RunMetadata& meta,
       const std::vector<std::string>& wall_names, const RunWriterAccess& shared)
      : path(file_path),
        file(create_run_file(file_path, meta, shared)),
        series(file.get(), wall_names, kBlockRows),
        events(file.get(), kBlockRows),
        frames(h5::create_group(file.get(), "frames")),
        frame_index(h5::create_frame_index(file.get(), kFrameIndexCapacity)) {
    if (shared.writes_index) index.emplace(xmf_path_of(file_path), file_path.filename().string());
    flush_file();
  }

  // After a frame's datasets: its attributes and index entry, each behind a flush (the note at
  // the top), and its line in run.xmf.
  void close_frame(hid_t group, const std::string& name, std::int64_t step, double time, std::size_t particles,
                   std::size_t bonds, bool labelled) {
    flush_file();
    // The frame counts as written once these are on disk (see the note at the top).
    h5::write_attribute(group, "step", step);
    h5::write_attribute(group, "time", time);
    if (static_cast<std::size_t>(frame_count) < kFrameIndexCapacity)
      h5::record_frame_address(frame_index.get(), static_cast<std::size_t>(frame_count), group);
    flush_file();
    ++frame_count;
    if (index) index->add({"/frames/" + name, time, particles, bonds, labelled});
  }

  void flush_file() {
    h5::check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "flushing " + path.string());
  }

  void write_blocks() {
    series.write();
    events.write();
  }

  std::filesystem::path path;
  h5::Handle file;
  SeriesWriter series;
  BreakEventWriter events;
  h5::Handle frames;
  h5::Handle frame_index;
  std::optional<XdmfIndex> index;  // on the one process that keeps run.xmf
  std::int64_t frame_count = 0;
  std::vector<Index> pair_scratch;
};

RunWriter::RunWriter(const std::filesystem::path& path, const RunMetadata& meta,
                     const std::vector<std::string>& wall_names, const RunWriterAccess& access) {
  if (path.extension() == ".xmf")
    throw OutputError("run file '" + path.string() +
                      "' ends in .xmf, the name of its XDMF index: use a .h5 name");
  make_parent_folder(path);
  const h5::QuietErrors quiet;
  impl_ = std::make_unique<Impl>(path, meta, wall_names, access);
}

RunWriter::~RunWriter() {
  if (!impl_) return;
  try {
    const h5::QuietErrors quiet;
    impl_->write_blocks();
    impl_->flush_file();
  } catch (const std::exception& error) {
    // A destructor cannot throw; say what was lost rather than lose it silently.
    std::fprintf(stderr, "shard: the last series rows of %s were not written: %s\n",
                 impl_->path.c_str(), error.what());
  }
}

// Full blocks go to HDF5 at once (its chunk and metadata caches hold them), but the file is
// flushed only at frames: every flush is a moment a kill can tear (see the note at the top).
void RunWriter::append_series(const SeriesRow& row) {
  impl_->series.append(row);
  if (impl_->series.block_full()) {
    const h5::QuietErrors quiet;
    impl_->series.write();
  }
}

void RunWriter::append_break_events(const std::vector<BondBreakEvent>& events) {
  impl_->events.append(events);
  if (impl_->events.block_full()) {
    const h5::QuietErrors quiet;
    impl_->events.write();
  }
}

void RunWriter::write_frame(std::int64_t step, double time, const Particles& particles,
                            const Bonds& bonds, const std::vector<Index>* fragment_labels) {
  const h5::QuietErrors quiet;
  Impl& m = *impl_;
  m.write_blocks();
  collect_frame_bonds(particles, bonds, fragment_labels, m.pair_scratch);
  const std::string name = fmt::format("{:06d}", m.frame_count);
  h5::Handle group = h5::create_group(m.frames.get(), name);
  write_frame_datasets(group.get(), particles, m.pair_scratch, fragment_labels);
  m.close_frame(group.get(), name, step, time, particles.size(), m.pair_scratch.size() / 2,
                fragment_labels != nullptr);
}

void RunWriter::write_frame_part(std::int64_t step, double time, const FramePart& part) {
  const h5::QuietErrors quiet;
  Impl& m = *impl_;
  m.write_blocks();
  const std::string name = fmt::format("{:06d}", m.frame_count);
  h5::Handle group = h5::create_group(m.frames.get(), name);
  write_frame_part_datasets(group.get(), part);
  m.close_frame(group.get(), name, step, time, part.total_rows, part.total_bonds, part.labelled);
}

void RunWriter::write_body_impacts(const std::vector<BodyImpact>& impacts) {
  const h5::QuietErrors quiet;
  impl_->write_blocks();
  h5::Handle group = h5::create_group(impl_->file.get(), "body_impacts");
  const std::size_t n = impacts.size();
  std::vector<std::int32_t> hit(n), wall(n);
  std::vector<std::int64_t> step(n);
  std::vector<double> time(n), speed(n), angle(n);
  std::vector<Vec3> velocity(n), normal(n);
  for (std::size_t b = 0; b < n; ++b) {
    const BodyImpact& i = impacts[b];
    hit[b] = i.hit ? 1 : 0;
    wall[b] = i.wall;
    step[b] = i.step;
    time[b] = i.time;
    speed[b] = i.speed();
    angle[b] = i.angle_degrees();
    velocity[b] = i.velocity;
    normal[b] = i.normal;
  }
  const hid_t g = group.get();
  h5::write_dataset(g, "hit", hit.data(), n);
  h5::write_dataset(g, "step", step.data(), n);
  h5::write_dataset(g, "time", time.data(), n);
  h5::write_dataset(g, "velocity", n == 0 ? nullptr : velocity.front().data(), n, 3);
  h5::write_dataset(g, "normal", n == 0 ? nullptr : normal.front().data(), n, 3);
  h5::write_dataset(g, "wall", wall.data(), n);
  h5::write_dataset(g, "speed", speed.data(), n);
  h5::write_dataset(g, "angle", angle.data(), n);
  impl_->flush_file();
}

void RunWriter::flush() {
  const h5::QuietErrors quiet;
  impl_->write_blocks();
  impl_->flush_file();
}

const std::filesystem::path& RunWriter::path() const { return impl_->path; }

bool run_files_thread_safe() {
  hbool_t safe = 0;
  return H5is_library_threadsafe(&safe) >= 0 && safe;
}

}  // namespace shard
