#pragma once
// Stored reference results of the contact laws (in the spirit of LAMMPS' unittest/force-styles):
// one small text file per law and effect policy, plugins/contact/<law>/reference/<case>.txt, holds
// a fixed random configuration (its inputs, written out, so no random generator need agree across
// platforms) and the forces, couples, energies and tangential springs the law gave over a few
// steps. test_contact_reference recomputes them through the plugin interface and compares;
// write_contact_reference regenerates them after a deliberate physics change (README.md beside
// the files says how).
//
// File format (text, one record per line, numbers with 17 significant digits, which round-trip):
//   # comments
//   plugin NAME
//   param KEY VALUE        (a number, or text for `effects`)
//   dt SECONDS
//   steps N
//   contact K j nx ny nz vx vy vz delta r_eff m_eff          (inputs, N contacts)
//   result STEP K fx fy fz cx cy cz energy xi_x xi_y xi_z     (after each step; the springs carry over)
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <variant>
#include <vector>

#include "contact_arrays.hpp"
#include "shard/plugin_host.hpp"

namespace shard::test {

struct ReferenceCase {
  std::string file;  // plugins/contact/<law>/reference/<file>.txt
  std::string plugin;
  std::map<std::string, ParamValue> params;
};

// The laws and their policies, each on at a plausible size (the effect library's).
inline std::vector<ReferenceCase> reference_cases() {
  return {
      {"hertz_mindlin", "hertz_mindlin", {}},
      {"hertz_mindlin_cohesion", "hertz_mindlin", {{"effects", std::string("cohesion")}, {"cohesion_stress", 5e4}}},
      {"hertz_mindlin_support_friction", "hertz_mindlin",
       {{"effects", std::string("support_friction")}, {"support_friction_ratio", 0.15}}},
      {"linear_spring", "linear_spring", {}},
      {"linear_spring_support_friction", "linear_spring",
       {{"effects", std::string("support_friction")}, {"support_friction_ratio", 0.15}}},
  };
}

inline std::filesystem::path reference_file(const std::filesystem::path& source_dir, const ReferenceCase& c) {
  return source_dir / "plugins/contact" / c.plugin / "reference" / (c.file + ".txt");
}

struct ReferenceRun {
  double dt = 1e-6;
  int steps = 4;
  std::size_t count = 0;
  ContactArrays inputs{0, 3};
  // Per step and contact: fx fy fz cx cy cz energy xi_x xi_y xi_z.
  std::vector<std::vector<std::array<double, 10>>> results;
};

// A uniform double in [0, 1) from the raw 64 bits (portable: std:: distributions are not).
struct Bits {
  std::uint64_t state;
  double next() {
    state += 0x9e3779b97f4a7c15ull;  // splitmix64
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
};

// 48 contacts of 0.2-1 mm spheres, a quarter with walls: overlaps 1e-8..1e-5 m, relative speeds
// 1e-5..0.3 m/s, so that over the steps some stick, some slide and some are clamped (separating
// fast enough that the dashpot outweighs the spring).
inline ContactArrays random_configuration(std::size_t n) {
  Bits b{20261202};
  ContactArrays c(n, 3);
  const auto unit = [&b] {
    const double z = 2 * b.next() - 1, phi = 6.283185307179586 * b.next(), s = std::sqrt(1 - z * z);
    return Vec3(s * std::cos(phi), s * std::sin(phi), z);
  };
  for (std::size_t k = 0; k < n; ++k) {
    c.i[k] = static_cast<Index>(k);
    c.j[k] = k % 4 == 3 ? -1 - static_cast<Index>(k % 3) : static_cast<Index>(k + 1);
    c.normal[k] = unit();
    c.velocity[k] = std::pow(10.0, -5.0 + 4.5 * b.next()) * unit();
    c.overlap[k] = std::pow(10.0, -8.0 + 3.0 * b.next());
    const double r = (0.2 + 0.8 * b.next()) * 1e-3, m = 2500 * 4.18879 * r * r * r;
    c.r_eff[k] = c.j[k] < 0 ? r : 0.5 * r;
    c.m_eff[k] = c.j[k] < 0 ? m : 0.5 * m;
  }
  return c;
}

inline ReferenceRun run_case(const PluginHost& host, const ReferenceCase& c, ContactArrays inputs, double dt,
                             int steps) {
  const auto model = host.make_contact(c.plugin, host.params(PluginKind::Contact, c.plugin, c.params));
  ReferenceRun run;
  run.dt = dt;
  run.steps = steps;
  run.count = inputs.i.size();
  run.inputs = inputs;
  ContactArrays work = inputs;
  work.history.assign(run.count * model->history_size(), 0.0);
  for (int s = 0; s < steps; ++s) {
    ContactBatch batch = work.batch(dt);
    model->compute(batch);
    std::vector<std::array<double, 10>> step(run.count);
    for (std::size_t k = 0; k < run.count; ++k)
      step[k] = {work.force[k].x(),  work.force[k].y(),  work.force[k].z(),  work.couple[k].x(),
                 work.couple[k].y(), work.couple[k].z(), work.energy[k],     work.history[3 * k],
                 work.history[3 * k + 1], work.history[3 * k + 2]};
    run.results.push_back(std::move(step));
  }
  return run;
}

inline std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

inline void write_reference(const std::filesystem::path& file, const ReferenceCase& c, const ReferenceRun& run) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file);
  out << "# Reference results of contact law " << c.plugin << " (tests/contact/contact_reference.hpp: format).\n"
      << "# Regenerate after a deliberate physics change: see plugins/contact/README.md.\n"
      << "plugin " << c.plugin << "\n";
  for (const auto& [key, value] : c.params) {
    if (const auto* d = std::get_if<double>(&value)) out << "param " << key << " " << number(*d) << "\n";
    if (const auto* t = std::get_if<std::string>(&value)) out << "param " << key << " " << *t << "\n";
  }
  out << "dt " << number(run.dt) << "\nsteps " << run.steps << "\n";
  const ContactArrays& in = run.inputs;
  for (std::size_t k = 0; k < run.count; ++k) {
    out << "contact " << k << " " << in.j[k];
    for (const double v : {in.normal[k].x(), in.normal[k].y(), in.normal[k].z(), in.velocity[k].x(), in.velocity[k].y(),
                           in.velocity[k].z(), in.overlap[k], in.r_eff[k], in.m_eff[k]})
      out << " " << number(v);
    out << "\n";
  }
  for (int s = 0; s < run.steps; ++s)
    for (std::size_t k = 0; k < run.count; ++k) {
      out << "result " << s << " " << k;
      for (const double v : run.results[static_cast<std::size_t>(s)][k]) out << " " << number(v);
      out << "\n";
    }
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

struct StoredReference {
  ReferenceCase c;
  ReferenceRun run;
};

inline StoredReference read_reference(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": no reference file; write_contact_reference makes it");
  StoredReference r;
  std::vector<std::vector<double>> contacts;
  std::vector<std::tuple<int, std::size_t, std::array<double, 10>>> results;
  std::string line;
  int number_of_line = 0;
  while (std::getline(in, line)) {
    ++number_of_line;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string kind;
    words >> kind;
    const auto fail = [&] {
      throw std::runtime_error(file.string() + ":" + std::to_string(number_of_line) + ": cannot read '" + line + "'");
    };
    if (kind == "plugin") {
      words >> r.c.plugin;
    } else if (kind == "param") {
      std::string key, value;
      words >> key >> value;
      if (key == "effects") {
        std::string rest;
        if (std::getline(words, rest)) value += rest;  // names separated by blanks
        words.clear();
        r.c.params[key] = value;
      } else {
        r.c.params[key] = std::stod(value);
      }
    } else if (kind == "dt") {
      words >> r.run.dt;
    } else if (kind == "steps") {
      words >> r.run.steps;
    } else if (kind == "contact") {
      std::vector<double> v(11);
      for (auto& x : v) words >> x;
      contacts.push_back(v);
    } else if (kind == "result") {
      int s = 0;
      std::size_t k = 0;
      std::array<double, 10> v{};
      words >> s >> k;
      for (auto& x : v) words >> x;
      results.emplace_back(s, k, v);
    } else {
      fail();
    }
    if (words.fail()) fail();
  }
  r.run.count = contacts.size();
  r.run.inputs = ContactArrays(r.run.count, 3);
  for (std::size_t k = 0; k < r.run.count; ++k) {
    const auto& v = contacts[k];
    ContactArrays& c = r.run.inputs;
    c.i[k] = static_cast<Index>(k);
    c.j[k] = static_cast<Index>(v[1]);
    c.normal[k] = Vec3(v[2], v[3], v[4]);
    c.velocity[k] = Vec3(v[5], v[6], v[7]);
    c.overlap[k] = v[8];
    c.r_eff[k] = v[9];
    c.m_eff[k] = v[10];
  }
  r.run.results.assign(static_cast<std::size_t>(r.run.steps), std::vector<std::array<double, 10>>(r.run.count));
  for (const auto& [s, k, v] : results) r.run.results.at(static_cast<std::size_t>(s)).at(k) = v;
  return r;
}

}  // namespace shard::test
