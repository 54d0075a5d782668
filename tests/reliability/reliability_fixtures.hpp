#pragma once
// Helpers shared by the reliability tests: scratch folders, running the real `shard` binary, and
// comparing checkpoints bit for bit.
#include <doctest/doctest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "shard/checkpoint.hpp"

namespace shard::test {

inline const std::filesystem::path kSource = SHARD_SOURCE_DIR;
inline const std::filesystem::path kShard = std::filesystem::path(SHARD_BUILD_DIR) / "bin" / "shard";
inline const std::filesystem::path kScenes = kSource / "tests" / "reliability" / "scenes";

inline std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("shard_reliability_" + std::to_string(getpid())) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Outcome {
  int exit_code = -1;
  std::string err;
};

// Runs `shard <args>` through the shell in `dir`, stderr to a file.
inline Outcome run_shard(const std::string& args, const std::filesystem::path& dir, const std::string& prefix = "") {
  // Kept outside `dir`, which may be a source folder (the catalogue runs in bad_inputs/).
  const auto err_file = scratch("stderr") / "stderr.txt";
  const std::string command =
      "cd '" + dir.string() + "' && " + prefix + "'" + kShard.string() + "' " + args + " >/dev/null 2>'" + err_file.string() + "'";
  const int status = std::system(command.c_str());
  Outcome o;
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  o.err = read_text(err_file);
  return o;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Every array of two simulation states, compared as bytes (NaN-safe, -0.0 != +0.0).
inline void require_identical(const SimulationState& a, const SimulationState& b) {
  CHECK(a.step == b.step);
  CHECK(std::memcmp(&a.time, &b.time, sizeof(double)) == 0);
  CHECK(a.dt == b.dt);
  CHECK(same_bits(a.particles.position, b.particles.position));
  CHECK(same_bits(a.particles.velocity, b.particles.velocity));
  CHECK(same_bits(a.particles.orientation, b.particles.orientation));
  CHECK(same_bits(a.particles.omega, b.particles.omega));
  CHECK(same_bits(a.particles.force, b.particles.force));
  CHECK(same_bits(a.particles.torque, b.particles.torque));
  CHECK(same_bits(a.particles.id, b.particles.id));
  CHECK(same_bits(a.bonds.i, b.bonds.i));
  CHECK(same_bits(a.bonds.j, b.bonds.j));
  CHECK(same_bits(a.bonds.state, b.bonds.state));  // the bonds' reference state
  // The runs keep no per-bond loads; the bond energy summed in the last step stands for them.
  CHECK(std::memcmp(&a.bond_energy, &b.bond_energy, sizeof(double)) == 0);
  CHECK(std::memcmp(&a.contact_energy, &b.contact_energy, sizeof(double)) == 0);
  CHECK(a.bonds_broken == b.bonds_broken);
  REQUIRE(a.events.size() == b.events.size());
  for (std::size_t k = 0; k < a.events.size(); ++k) {
    CHECK(a.events[k].step == b.events[k].step);
    CHECK(a.events[k].id_i == b.events[k].id_i);
    CHECK(a.events[k].id_j == b.events[k].id_j);
    CHECK(std::memcmp(a.events[k].midpoint.data(), b.events[k].midpoint.data(), 3 * sizeof(double)) == 0);
    CHECK(std::memcmp(&a.events[k].stress.sigma_vm, &b.events[k].stress.sigma_vm, sizeof(double)) == 0);
  }
  REQUIRE(a.walls.size() == b.walls.size());
  for (std::size_t w = 0; w < a.walls.size(); ++w) {
    CHECK(std::memcmp(a.walls[w].displacement.data(), b.walls[w].displacement.data(), 3 * sizeof(double)) == 0);
    CHECK(std::memcmp(a.walls[w].force.data(), b.walls[w].force.data(), 3 * sizeof(double)) == 0);
  }
  CHECK(same_bits(a.neighbours.first, b.neighbours.first));
  CHECK(same_bits(a.neighbours.second, b.neighbours.second));
  CHECK(same_bits(a.neighbours.history, b.neighbours.history));  // the contact history
  CHECK(a.neighbours.rebuilds == b.neighbours.rebuilds);
  CHECK(a.contacts == b.contacts);
}

}  // namespace shard::test
