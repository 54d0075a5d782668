#pragma once
// Stored reference results of the contact laws (in the spirit of LAMMPS' unittest/force-styles,
// in the TOML layout of beam_bond's, plugins/bond/beam_bond/reference/): one small file per law
// and effect policy, plugins/contact/<law>/reference/<case>.toml, holds a fixed random
// configuration (its inputs, written out, so no random generator need agree across platforms)
// and the forces, couples, energies and tangential springs the law gave over a few steps.
// test_contact_reference recomputes them through the plugin interface and compares; the target
// contact_reference regenerates them after a deliberate physics change (plugins/contact/README.md).
//
//   model = "hertz_mindlin"        dt = 1e-06
//   [params]                       the plugin's parameters (numbers; `effects` as text)
//   [contacts]                     j, normal, velocity, overlap, r_eff, m_eff (one entry per contact)
//   [[steps]]                      force, couple, energy, spring after each step (springs carry over)
// Numbers are written with 17 significant digits, which round-trip.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <variant>

#include <toml++/toml.h>
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
  return source_dir / "plugins/contact" / c.plugin / "reference" / (c.file + ".toml");
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

// A TOML float that reads back to the same bits (-0.0, 1.0e-06 stay floats).
inline std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  std::string s = text;
  if (s.find_first_of(".ein") == std::string::npos) s += ".0";
  return s;
}

inline std::string vectors(const std::vector<Vec3>& v) {
  std::string s = "[";
  for (std::size_t k = 0; k < v.size(); ++k)
    s += (k ? ", [" : "[") + number(v[k].x()) + ", " + number(v[k].y()) + ", " + number(v[k].z()) + "]";
  return s + "]";
}

inline std::string numbers(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t k = 0; k < v.size(); ++k) s += (k ? ", " : "") + number(v[k]);
  return s + "]";
}

inline void write_reference(const std::filesystem::path& file, const ReferenceCase& c, const ReferenceRun& run) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file);
  out << "# " << c.plugin << " reference data (tests/contact/contact_reference.hpp). Do not edit: after a\n"
      << "# deliberate physics change regenerate every file with\n"
      << "#   cmake --build build/release --target contact_reference\n"
      << "# and state the change in the commit (plugins/contact/README.md).\n"
      << "model = \"" << c.plugin << "\"\n"
      << "dt = " << number(run.dt) << "\n\n[params]\n";
  for (const auto& [key, value] : c.params) {
    if (const auto* d = std::get_if<double>(&value)) out << key << " = " << number(*d) << "\n";
    if (const auto* t = std::get_if<std::string>(&value)) out << key << " = \"" << *t << "\"\n";
  }
  const ContactArrays& in = run.inputs;
  out << "\n[contacts]  # the configuration, one entry per contact\nj = [";
  for (std::size_t k = 0; k < run.count; ++k) out << (k ? ", " : "") << in.j[k];
  out << "]\nnormal = " << vectors(in.normal) << "\nvelocity = " << vectors(in.velocity)
      << "\noverlap = " << numbers(in.overlap) << "\nr_eff = " << numbers(in.r_eff) << "\nm_eff = " << numbers(in.m_eff)
      << "\n";
  for (const auto& step : run.results) {
    std::vector<Vec3> force, couple, spring;
    std::vector<double> energy;
    for (const auto& r : step) {
      force.emplace_back(r[0], r[1], r[2]);
      couple.emplace_back(r[3], r[4], r[5]);
      energy.push_back(r[6]);
      spring.emplace_back(r[7], r[8], r[9]);
    }
    out << "\n[[steps]]\nforce = " << vectors(force) << "\ncouple = " << vectors(couple)
        << "\nenergy = " << numbers(energy) << "\nspring = " << vectors(spring) << "\n";
  }
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

struct StoredReference {
  ReferenceCase c;
  ReferenceRun run;
};

inline StoredReference read_reference(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file))
    throw std::runtime_error(file.string() + ": no reference file; the target contact_reference writes it");
  const toml::table root = toml::parse_file(file.string());
  const auto fail = [&](const std::string& what) { throw std::runtime_error(file.string() + ": " + what); };
  const auto doubles = [&](const toml::node_view<const toml::node>& n, const char* name) {
    std::vector<double> out;
    const auto* a = n.as_array();
    if (!a) fail(std::string("no array ") + name);
    for (const auto& x : *a) out.push_back(x.value<double>().value());
    return out;
  };
  const auto vecs = [&](const toml::node_view<const toml::node>& n, const char* name) {
    std::vector<Vec3> out;
    const auto* a = n.as_array();
    if (!a) fail(std::string("no array ") + name);
    for (const auto& x : *a) {
      const auto* v = x.as_array();
      if (!v || v->size() != 3) fail(std::string(name) + ": each entry is [x, y, z]");
      out.emplace_back((*v)[0].value<double>().value(), (*v)[1].value<double>().value(), (*v)[2].value<double>().value());
    }
    return out;
  };
  StoredReference r;
  r.c.plugin = root["model"].value_or(std::string());
  r.run.dt = root["dt"].value_or(0.0);
  if (const auto* params = root["params"].as_table())
    for (const auto& [key, value] : *params) {
      if (const auto* t = value.as_string()) r.c.params[std::string(key.str())] = t->get();
      else r.c.params[std::string(key.str())] = value.value<double>().value();
    }
  const auto contacts = root["contacts"];
  const auto j = doubles(contacts["j"], "j");
  r.run.count = j.size();
  r.run.inputs = ContactArrays(r.run.count, 3);
  ContactArrays& c = r.run.inputs;
  c.normal = vecs(contacts["normal"], "normal");
  c.velocity = vecs(contacts["velocity"], "velocity");
  c.overlap = doubles(contacts["overlap"], "overlap");
  c.r_eff = doubles(contacts["r_eff"], "r_eff");
  c.m_eff = doubles(contacts["m_eff"], "m_eff");
  for (std::size_t k = 0; k < r.run.count; ++k) c.i[k] = static_cast<Index>(k), c.j[k] = static_cast<Index>(j[k]);
  if (c.normal.size() != r.run.count || c.velocity.size() != r.run.count || c.overlap.size() != r.run.count ||
      c.r_eff.size() != r.run.count || c.m_eff.size() != r.run.count)
    fail("[contacts]: every array needs one entry per contact");
  const auto* steps = root["steps"].as_array();
  if (!steps) fail("no [[steps]]");
  for (const auto& node : *steps) {
    const toml::node_view<const toml::node> step(node);
    const auto force = vecs(step["force"], "force"), couple = vecs(step["couple"], "couple"),
               spring = vecs(step["spring"], "spring");
    const auto energy = doubles(step["energy"], "energy");
    if (force.size() != r.run.count || couple.size() != r.run.count || spring.size() != r.run.count ||
        energy.size() != r.run.count)
      fail("[[steps]]: every array needs one entry per contact");
    std::vector<std::array<double, 10>> out(r.run.count);
    for (std::size_t k = 0; k < r.run.count; ++k)
      out[k] = {force[k].x(),  force[k].y(),  force[k].z(),  couple[k].x(), couple[k].y(),
                couple[k].z(), energy[k],     spring[k].x(), spring[k].y(), spring[k].z()};
    r.run.results.push_back(std::move(out));
  }
  r.run.steps = static_cast<int>(r.run.results.size());
  return r;
}

}  // namespace shard::test
