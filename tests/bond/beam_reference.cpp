// beam_bond reference files: TOML written with every double in its shortest round-trip form
// (fmt's "{}"), so reading a file back gives the very bits that were written.
#include "beam_reference.hpp"

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>
#include <toml++/toml.h>
#include <variant>

namespace shard::test {
namespace {

// A TOML float: fmt's shortest round-trip text, with ".0" where it would read as an integer.
std::string number(double x) {
  std::string s = fmt::format("{}", x);
  if (s.find_first_of(".eEni") == std::string::npos) s += ".0";
  return s;
}

template <class T, class F>
std::string array(const std::vector<T>& values, F&& text) {
  std::string s = "[";
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (k) s += ", ";
    s += text(values[k]);
  }
  s += "]";
  return s;
}

std::string vec3(const Vec3& v) { return fmt::format("[{}, {}, {}]", number(v.x()), number(v.y()), number(v.z())); }
std::string quat(const Quat& q) {  // (w, x, y, z)
  return fmt::format("[{}, {}, {}, {}]", number(q.w()), number(q.x()), number(q.y()), number(q.z()));
}

std::string value_text(const ParamValue& v) {
  if (const double* d = std::get_if<double>(&v)) return number(*d);
  if (const bool* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
  if (const std::string* s = std::get_if<std::string>(&v)) return fmt::format("\"{}\"", *s);
  return vec3(std::get<Vec3>(v));
}

// Reading: every key is required; a missing or mistyped one names the file, the table and the key.
struct Reader {
  std::string path;

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw std::runtime_error(fmt::format("{}: {}: {} (regenerate with `cmake --build build/release --target "
                                         "beam_bond_reference`, docs/how-to/write-a-plugin.md)",
                                         path, where, what));
  }

  const toml::array& array_at(const toml::table& t, const std::string& where, const char* key) const {
    const toml::array* a = t[key].as_array();
    if (!a) fail(where, fmt::format("key '{}' missing or not an array", key));
    return *a;
  }

  double to_double(const toml::node& n, const std::string& where) const {
    if (const auto d = n.value<double>()) return *d;
    fail(where, "expected a number");
  }

  std::vector<double> numbers(const toml::table& t, const std::string& where, const char* key) const {
    std::vector<double> out;
    for (const auto& n : array_at(t, where, key)) out.push_back(to_double(n, where + "." + key));
    return out;
  }

  std::vector<double> tuple(const toml::node& n, std::size_t size, const std::string& where) const {
    const toml::array* a = n.as_array();
    if (!a || a->size() != size) fail(where, fmt::format("expected an array of {} numbers", size));
    std::vector<double> out;
    for (const auto& x : *a) out.push_back(to_double(x, where));
    return out;
  }

  std::vector<Vec3> vec3s(const toml::table& t, const std::string& where, const char* key) const {
    std::vector<Vec3> out;
    for (const auto& n : array_at(t, where, key)) {
      const auto v = tuple(n, 3, where + "." + key);
      out.emplace_back(v[0], v[1], v[2]);
    }
    return out;
  }

  std::vector<Quat> quats(const toml::table& t, const std::string& where, const char* key) const {
    std::vector<Quat> out;
    for (const auto& n : array_at(t, where, key)) {
      const auto v = tuple(n, 4, where + "." + key);
      out.emplace_back(v[0], v[1], v[2], v[3]);
    }
    return out;
  }

  std::vector<Index> indices(const toml::table& t, const std::string& where, const char* key) const {
    std::vector<Index> out;
    for (const auto& n : array_at(t, where, key)) {
      const auto v = n.value<std::int64_t>();
      if (!v) fail(where + "." + key, "expected an integer");
      out.push_back(static_cast<Index>(*v));
    }
    return out;
  }
};

}  // namespace

void write_reference(const std::string& path, const ReferenceData& d) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  const HandBonds& b = d.bonded;
  out << "# " << d.model << " reference data (tests/bond/beam_reference.hpp). Do not edit: after a deliberate\n"
      << "# physics change regenerate every file with\n"
      << "#   cmake --build build/release --target beam_bond_reference\n"
      << "# and state the change in the commit (docs/how-to/write-a-plugin.md, \"Reference data\").\n";
  out << "model = \"" << d.model << "\"\n";
  out << "description = \"" << d.description << "\"\n";
  out << "dt = " << number(d.dt) << "\n\n[params]\n";
  for (const auto& [k, v] : d.params) out << k << " = " << value_text(v) << "\n";
  auto integer = [](auto v) { return std::to_string(v); };
  out << "\n[bonded]  # the configuration the bonds were recorded in\n";
  out << "i = " << array(b.i, integer) << "\n";
  out << "j = " << array(b.j, integer) << "\n";
  out << "id = " << array(b.id, integer) << "\n";
  out << "radius = " << array(b.radius, number) << "\n";
  out << "mass = " << array(b.mass, number) << "\n";
  out << "inertia = " << array(b.inertia, number) << "\n";
  out << "position = " << array(b.position, vec3) << "\n";
  out << "orientation = " << array(b.orientation, quat) << "  # (w, x, y, z)\n";
  for (const ReferenceStep& s : d.steps) {
    out << "\n[[steps]]\n";
    out << "position = " << array(s.position, vec3) << "\n";
    out << "orientation = " << array(s.orientation, quat) << "\n";
    out << "velocity = " << array(s.velocity, vec3) << "\n";
    out << "omega = " << array(s.omega, vec3) << "\n";
    out << "force = " << array(s.force, vec3) << "  # on i\n";
    out << "torque_i = " << array(s.torque_i, vec3) << "\n";
    out << "torque_j = " << array(s.torque_j, vec3) << "\n";
    out << "energy = " << array(s.energy, number) << "\n";
    out << "broken = " << array(s.broken, integer) << "\n";
    out << "sigma_vm = " << array(s.sigma_vm, number) << "  # at failure; 0 while intact\n";
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

ReferenceData read_reference(const std::string& path) {
  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw std::runtime_error(fmt::format("{}:{}:{}: {}", path, e.source().begin.line, e.source().begin.column,
                                         e.description()));
  }
  const Reader r{path};
  ReferenceData d;
  d.model = root["model"].value_or(std::string());
  d.description = root["description"].value_or(std::string());
  const auto dt = root["dt"].value<double>();
  if (!dt) r.fail("top level", "key 'dt' missing or not a number");
  d.dt = *dt;
  const toml::table* params = root["params"].as_table();
  if (!params) r.fail("top level", "table [params] missing");
  for (const auto& [key, node] : *params) {
    if (const auto b = node.value_exact<bool>()) d.params[std::string(key.str())] = *b;
    else if (const auto s = node.value_exact<std::string>()) d.params[std::string(key.str())] = *s;
    else d.params[std::string(key.str())] = r.to_double(node, fmt::format("params.{}", key.str()));
  }
  const toml::table* bonded = root["bonded"].as_table();
  if (!bonded) r.fail("top level", "table [bonded] missing");
  HandBonds& b = d.bonded;
  b.i = r.indices(*bonded, "bonded", "i");
  b.j = r.indices(*bonded, "bonded", "j");
  b.id = r.indices(*bonded, "bonded", "id");
  b.radius = r.numbers(*bonded, "bonded", "radius");
  b.mass = r.numbers(*bonded, "bonded", "mass");
  b.inertia = r.numbers(*bonded, "bonded", "inertia");
  b.position = r.vec3s(*bonded, "bonded", "position");
  b.orientation = r.quats(*bonded, "bonded", "orientation");
  const std::size_t n = b.position.size(), bonds = b.i.size();
  if (b.j.size() != bonds || b.id.size() != n || b.radius.size() != n || b.mass.size() != n ||
      b.inertia.size() != n || b.orientation.size() != n)
    r.fail("bonded", "arrays of different lengths (i and j per bond, the rest per particle)");
  b.velocity.assign(n, Vec3::Zero());
  b.omega.assign(n, Vec3::Zero());
  b.material.assign(n, 0);
  const toml::array* steps = root["steps"].as_array();
  if (!steps || steps->empty()) r.fail("top level", "array of tables [[steps]] missing");
  for (std::size_t k = 0; k < steps->size(); ++k) {
    const std::string where = fmt::format("steps[{}]", k);
    const toml::table* t = (*steps)[k].as_table();
    if (!t) r.fail(where, "not a table");
    ReferenceStep s;
    s.position = r.vec3s(*t, where, "position");
    s.orientation = r.quats(*t, where, "orientation");
    s.velocity = r.vec3s(*t, where, "velocity");
    s.omega = r.vec3s(*t, where, "omega");
    s.force = r.vec3s(*t, where, "force");
    s.torque_i = r.vec3s(*t, where, "torque_i");
    s.torque_j = r.vec3s(*t, where, "torque_j");
    s.energy = r.numbers(*t, where, "energy");
    s.sigma_vm = r.numbers(*t, where, "sigma_vm");
    for (const Index v : r.indices(*t, where, "broken")) s.broken.push_back(static_cast<int>(v));
    if (s.position.size() != n || s.orientation.size() != n || s.velocity.size() != n || s.omega.size() != n)
      r.fail(where, "particle arrays not of the [bonded] particle count");
    if (s.force.size() != bonds || s.torque_i.size() != bonds || s.torque_j.size() != bonds ||
        s.energy.size() != bonds || s.sigma_vm.size() != bonds || s.broken.size() != bonds)
      r.fail(where, "bond arrays not of the [bonded] bond count");
    d.steps.push_back(std::move(s));
  }
  return d;
}

}  // namespace shard::test
