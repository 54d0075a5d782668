#pragma once
// Deterministic inputs for the output tests: every value is a function of its indices, so a
// reader can check a file it did not write (the crash test's child process) exactly.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "shard/bonds.hpp"
#include "shard/output.hpp"
#include "shard/particles.hpp"

namespace shard::test {

// A fresh, empty folder under the system temp folder, removed when the object dies.
class TempFolder {
 public:
  explicit TempFolder(const std::string& tag)
      : path_(std::filesystem::temp_directory_path() /
              ("shard_output_" + tag + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Non-round values (thirds, sevenths) so an accidental float32 round trip would show.
inline Particles make_particles(std::size_t n, int frame) {
  Particles p;
  for (std::size_t k = 0; k < n; ++k) {
    const double x = static_cast<double>(k) + frame / 3.0;
    p.position.emplace_back(x, -x / 7.0, 1e-3 * x);
    p.velocity.emplace_back(0.1 * x, 1.0 / (x + 1.0), -2.0 / 3.0);
    p.orientation.push_back(Quat::Identity());
    p.omega.emplace_back(frame / 11.0, x / 13.0, -1e5 * x);
    p.force.push_back(Vec3::Zero());
    p.torque.push_back(Vec3::Zero());
    p.radius.push_back(1e-3 * (1.0 + static_cast<double>(k % 5) / 9.0));
    p.mass.push_back(1.0);
    p.inertia.push_back(1.0);
    p.material.push_back(static_cast<std::int32_t>(k % 3));
    p.flags.push_back(0);
    p.id.push_back(static_cast<Index>(1000 + 3 * k + static_cast<std::size_t>(frame)));
    p.body.push_back(static_cast<std::int32_t>(k % 2));
  }
  return p;
}

// A chain 0-1, 1-2, ..., with bond `broken_at` flagged broken (not yet removed).
inline Bonds make_chain(std::size_t n, std::size_t broken_at) {
  Bonds b;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    b.i.push_back(static_cast<Index>(k));
    b.j.push_back(static_cast<Index>(k + 1));
    b.broken.push_back(k == broken_at ? 1 : 0);
  }
  return b;
}

inline SeriesRow make_row(std::int64_t r, std::size_t walls) {
  SeriesRow row;
  const double x = static_cast<double>(r);
  row.step = 10 * r;
  row.time = x * 1e-7 / 3.0;
  row.kinetic_energy = x / 7.0;
  row.bond_energy = x * x / 9.0;
  row.contact_energy = -x / 11.0;
  row.bonds_intact = 5000 - r;
  row.bonds_broken = r;
  row.contacts = 2 * r + 1;
  for (std::size_t w = 0; w < walls; ++w) {
    const double s = static_cast<double>(w + 1);
    row.wall_force.emplace_back(s * x, -s * x / 3.0, 1.0 / (x + s));
    row.wall_torque.emplace_back(x / 17.0, s, -x);
    row.wall_displacement.emplace_back(0.0, 0.0, -1e-6 * x * s);
    row.wall_impact_energy.push_back(x * s / 13.0);
    row.wall_impacts.push_back(r * static_cast<std::int64_t>(w + 1));
  }
  return row;
}

inline BondBreakEvent make_event(std::int64_t e) {
  BondBreakEvent event;
  const double x = static_cast<double>(e);
  event.time = x * 1e-6 / 7.0;
  event.step = 100 + e;
  event.id_i = static_cast<Index>(e);
  event.id_j = static_cast<Index>(2 * e + 1);
  event.midpoint = Vec3(x / 3.0, -x, 1e-3);
  event.stress.sigma_axial = 1e6 * x / 3.0;
  event.stress.tau = 2e6 / (x + 1.0);
  event.stress.sigma_vm = 3e6 + x;
  event.stress.tension = x;
  event.stress.bending = 2 * x;
  event.stress.shear = 3 * x;
  event.stress.torsion = 4 * x;
  event.stress.dominant = static_cast<BondFailureMode>(1 + e % 4);
  return event;
}

inline RunMetadata make_metadata() {
  RunMetadata meta;
  meta.scene_text = "[run]\nsteps = 100\n# ünïcödé comment\n";
  meta.scene_file = "scenes/beam.toml";
  meta.seed = 18446744073709551557ull;  // largest 64-bit prime: needs all 64 bits
  meta.shard_version = "0.1.0";
  meta.git_revision = "abc1234-dirty";
  meta.plugins = {{"contact/hertz_mindlin", "version=1.0; E=7e10"},
                  {"bond/beam", "version=2; sigma_max=2e7"}};
  meta.generator_quality = {{"particles", 5.0}, {"solid_fraction", 0.6123456789}};
  meta.notes = {{"time_step", "dt = 1e-7 s (0.2 of Rayleigh)"}};
  return meta;
}

}  // namespace shard::test
