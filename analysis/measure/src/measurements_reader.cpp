#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <toml++/toml.h>

#include "shard/measure/csv_table.hpp"
#include "shard/measure/measurement_error.hpp"
#include "shard/measure/measurements.hpp"

namespace shard::measure {
namespace {

constexpr std::size_t kMinCurveRows = 5;  // fewer cannot carry toe, elastic part and peak

long line_of(const toml::node& n) { return static_cast<long>(n.source().begin.line); }
long column_of(const toml::node& n) { return static_cast<long>(n.source().begin.column); }

double positive_number(const toml::table& t, const std::filesystem::path& file, const char* key, const char* unit,
                       bool required) {
  const toml::node* n = t.get(key);
  if (!n) {
    if (!required) return 0;
    throw MeasurementError(file, 0, 0, fmt::format("key '{}' is missing from [uncertainty]", key),
                           fmt::format("add '{} = <standard uncertainty in {}>' under [uncertainty]", key, unit));
  }
  const auto v = n->value<double>();
  if (!v || !(*v >= 0) || !std::isfinite(*v))
    throw MeasurementError(file, line_of(*n), column_of(*n), fmt::format("'{}' must be a number >= 0", key),
                           fmt::format("write the standard uncertainty in {}", unit));
  return *v;
}

// An unknown key of metadata.toml (top level or a table), named with the nearest known one.
[[noreturn]] void unknown_key(const std::filesystem::path& file, const toml::node& node, const std::string& key,
                              const std::string& table, const std::vector<std::string>& known) {
  const std::string closest = closest_name(key, known);
  throw MeasurementError(file, line_of(node), column_of(node),
                         fmt::format("unknown key '{}'{}", key, table.empty() ? "" : fmt::format(" in [{}]", table)),
                         fmt::format("{}Known keys: {}. Anything else the lab records goes under [notes], which is "
                                     "kept and never interpreted",
                                     closest.empty() ? "" : fmt::format("did you mean '{}'? ", closest),
                                     fmt::join(known, ", ")));
}

double test_number(const toml::table& t, const std::filesystem::path& file, const char* key, const char* unit,
                   bool may_be_negative) {
  const toml::node* n = t.get(key);
  if (!n) return 0;
  const auto v = n->value<double>();
  if (!v || !std::isfinite(*v) || (!may_be_negative && *v < 0))
    throw MeasurementError(file, line_of(*n), column_of(*n),
                           fmt::format("[test] {} must be a number{}", key, may_be_negative ? "" : " >= 0"),
                           fmt::format("write it in {}", unit));
  return *v;
}

TestConditions read_test_conditions(const toml::table& t, const std::filesystem::path& file) {
  static const std::vector<std::string> known = {"seating_preload", "zero_offset", "ramp", "ramp_time",
                                                 "grain_size", "fragment_size_threshold", "notes"};
  for (const auto& [key, node] : t)
    if (std::find(known.begin(), known.end(), std::string(key.str())) == known.end())
      unknown_key(file, node, std::string(key.str()), "test", known);
  TestConditions c;
  c.seating_preload = test_number(t, file, "seating_preload", "N (the force at which the curve's displacement is 0)", false);
  c.zero_offset = test_number(t, file, "zero_offset", "N (the load cell's reading at zero load)", true);
  c.ramp_time = test_number(t, file, "ramp_time", "s (the pins' time to reach the loading rate)", false);
  c.grain_size = test_number(t, file, "grain_size", "m", false);
  c.fragment_size_threshold = test_number(t, file, "fragment_size_threshold", "m (the smallest fragment counted)", false);
  if (const toml::node* n = t.get("ramp")) {
    const auto r = n->value<std::string>();
    if (!r || !is_ramp_name(*r))
      throw MeasurementError(file, line_of(*n), column_of(*n), "[test] ramp is not a ramp",
                             "write ramp = \"1-cos\", \"linear\" or \"none\" (the pins' acceleration to the loading rate)");
    c.ramp = *r;
  }
  if (c.has_ramp() && !(c.ramp_time > 0))
    throw MeasurementError(file, line_of(*t.get("ramp")), column_of(*t.get("ramp")),
                           fmt::format("[test] ramp = \"{}\" has no ramp_time", c.ramp),
                           "add ramp_time = <s to reach the loading rate>");
  if (!c.has_ramp() && c.ramp_time > 0)
    throw MeasurementError(file, line_of(*t.get("ramp_time")), column_of(*t.get("ramp_time")),
                           "[test] ramp_time is given without a ramp", "add ramp = \"1-cos\" or \"linear\"");
  if (const toml::node* n = t.get("notes")) {
    const auto text = n->value<std::string>();
    if (!text)
      throw MeasurementError(file, line_of(*n), column_of(*n), "[test] notes must be a string",
                             "write notes = \"...\" (or use a [notes] table for structured extras)");
    c.notes = *text;
  }
  return c;
}

}  // namespace

std::vector<double> MeasurementSet::loading_rates() const {
  std::vector<double> rates;
  for (const auto& s : specimens)
    if (std::none_of(rates.begin(), rates.end(),
                     [&](double r) { return std::abs(r - s.loading_rate) <= 1e-9 * std::abs(r); }))
      rates.push_back(s.loading_rate);
  std::sort(rates.begin(), rates.end());
  return rates;
}

Metadata read_metadata(const std::filesystem::path& file) {
  toml::table root;
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    if (!std::filesystem::exists(file))
      throw MeasurementError(file, 0, 0, "the metadata file is missing",
                             "create metadata.toml with an [uncertainty] table (docs/how-to/bring-lab-data.md)");
    throw MeasurementError(file, static_cast<long>(e.source().begin.line), static_cast<long>(e.source().begin.column),
                           std::string(e.description()), "write valid TOML (key = value)");
  }
  Metadata m;
  static const std::vector<std::string> known = {"name", "notes", "uncertainty", "test"};
  for (const auto& [key, node] : root)
    if (std::find(known.begin(), known.end(), std::string(key.str())) == known.end())
      unknown_key(file, node, std::string(key.str()), "", known);
  m.name = root["name"].value_or(std::string{});
  if (const toml::node* n = root.get("notes")) {
    if (const auto text = n->value<std::string>()) m.notes = *text;
    else if (const auto* t = n->as_table()) {
      std::ostringstream s;
      s << *t;
      m.notes = s.str();
    } else {
      throw MeasurementError(file, line_of(*n), column_of(*n), "notes must be text or a table",
                             "write notes = \"...\" or a [notes] table of key = value lines");
    }
  }
  if (const toml::node* n = root.get("test")) {
    const auto* t = n->as_table();
    if (!t)
      throw MeasurementError(file, line_of(*n), column_of(*n), "test must be a table",
                             "write [test] on its own line, then seating_preload = ..., ramp = ... below it");
    m.test = read_test_conditions(*t, file);
  }
  const toml::table* u = root["uncertainty"].as_table();
  if (!u)
    throw MeasurementError(file, 0, 0, "table [uncertainty] is missing",
                           "add [uncertainty] with load_cell (N) and displacement (m) standard uncertainties");
  for (const auto& [key, node] : *u) {
    const std::string k(key.str());
    if (k != "load_cell" && k != "displacement" && k != "crack_position")
      unknown_key(file, node, k, "uncertainty", {"load_cell", "displacement", "crack_position"});
  }
  m.load_cell_uncertainty = positive_number(*u, file, "load_cell", "N", true);
  m.displacement_uncertainty = positive_number(*u, file, "displacement", "m", true);
  m.crack_position_uncertainty = positive_number(*u, file, "crack_position", "m", false);
  return m;
}

Curve read_curve(const std::filesystem::path& file, const Metadata& metadata) {
  const CsvTable t = CsvTable::read(file);
  t.reject_unknown({"time", "displacement", "force", "u_displacement", "u_force"});
  const auto ct = t.require("time", "s");
  const auto cw = t.require("displacement", "loading-pin displacement, m");
  const auto cf = t.require("force", "force on the loading pins, N");
  const auto cuw = t.find("u_displacement");
  const auto cuf = t.find("u_force");
  if (!cuf && !(metadata.load_cell_uncertainty > 0))
    throw MeasurementError(file, 0, 0, "no force uncertainty: the curve has no 'u_force' column and metadata.toml "
                                       "gives load_cell = 0",
                           "add a u_force column or set [uncertainty] load_cell > 0");
  if (t.rows().size() < kMinCurveRows)
    throw MeasurementError(file, 0, 0, fmt::format("the curve has {} rows", t.rows().size()),
                           fmt::format("record at least {} points (toe, elastic part and peak)", kMinCurveRows));
  Curve c;
  c.id = file.stem().string();
  for (const auto& row : t.rows()) {
    const double time = t.number(row, ct, "time in s");
    if (!c.time.empty() && !(time > c.time.back()))
      throw MeasurementError(file, row.line, static_cast<long>(ct + 1),
                             fmt::format("time is not increasing: {} after {}", time, c.time.back()),
                             "sort the rows by time and remove repeated rows");
    c.time.push_back(time);
    c.displacement.push_back(t.number(row, cw, "displacement in m"));
    c.force.push_back(t.number(row, cf, "force in N") - metadata.test.zero_offset);
    const double uw = cuw ? t.number(row, *cuw, "standard uncertainty of the displacement in m")
                          : metadata.displacement_uncertainty;
    const double uf = cuf ? t.number(row, *cuf, "standard uncertainty of the force in N")
                          : metadata.load_cell_uncertainty;
    if (uw < 0 || uf < 0 || (cuf && !(uf > 0)))
      throw MeasurementError(file, row.line, static_cast<long>((uw < 0 ? *cuw : *cuf) + 1),
                             "an uncertainty is negative or the force uncertainty is zero",
                             "write standard uncertainties as positive numbers");
    c.u_displacement.push_back(uw);
    c.u_force.push_back(uf);
  }
  if (!(*std::max_element(c.force.begin(), c.force.end()) > 0))
    throw MeasurementError(file, 0, 0, "the force is never positive",
                           "the force on the pins is positive in compression of the specimen; flip the sign");
  return c;
}

void read_fragments(const std::filesystem::path& file, Specimen& specimen) {
  const CsvTable t = CsvTable::read(file);
  t.reject_unknown({"size", "mass"});
  const auto cs = t.require("size", "equivalent diameter of the fragment, m");
  const auto cm = t.find("mass");
  for (const auto& row : t.rows()) {
    const double size = t.number(row, cs, "fragment size in m");
    if (!(size > 0))
      throw MeasurementError(file, row.line, static_cast<long>(cs + 1), "a fragment size is not positive",
                             "write the equivalent diameter in m");
    specimen.fragment_sizes.push_back(size);
    if (cm) specimen.fragment_masses.push_back(t.number(row, *cm, "fragment mass in kg"));
  }
}

MeasurementSet read_measurements(const std::filesystem::path& folder) {
  MeasurementSet set;
  set.folder = folder;
  if (!std::filesystem::is_directory(folder))
    throw MeasurementError(folder, 0, 0, "not a folder", "pass the measurement folder (docs/how-to/bring-lab-data.md)");
  set.metadata = read_metadata(folder / "metadata.toml");
  const auto specimens_file = folder / "specimens.csv";
  const CsvTable t = CsvTable::read(specimens_file);
  t.reject_unknown({"id", "length", "width", "height", "span", "pin_distance", "loading_rate", "crack_position",
                    "fragment_count", "curve", "fragments"});
  const auto cid = t.require("id", "specimen name");
  const auto cl = t.require("length", "specimen length L, m");
  const auto cb = t.require("width", "specimen width b, m");
  const auto ch = t.require("height", "specimen height h, m");
  const auto cs = t.require("span", "support distance, m");
  const auto cd = t.require("pin_distance", "loading-pin distance d, m");
  const auto cr = t.require("loading_rate", "loading-pin speed, m/s");
  const auto ccrack = t.find("crack_position");
  const auto ccount = t.find("fragment_count");
  const auto ccurve = t.find("curve");
  const auto cfrag = t.find("fragments");
  if (t.rows().empty())
    throw MeasurementError(specimens_file, 0, 0, "no specimens", "add one row per tested specimen");
  std::set<std::string> ids;
  for (const auto& row : t.rows()) {
    Specimen s;
    s.id = t.text(row, cid);
    if (s.id.empty() || !ids.insert(s.id).second)
      throw MeasurementError(specimens_file, row.line, static_cast<long>(cid + 1),
                             s.id.empty() ? "the id is empty" : fmt::format("id '{}' appears twice", s.id),
                             "give every specimen its own non-empty id");
    const struct {
      std::size_t col;
      double* value;
      const char* what;
    } positives[] = {{cl, &s.length, "length in m"},     {cb, &s.width, "width in m"},
                     {ch, &s.height, "height in m"},     {cs, &s.span, "span in m"},
                     {cd, &s.pin_distance, "pin distance in m"}, {cr, &s.loading_rate, "loading rate in m/s"}};
    for (const auto& p : positives) {
      *p.value = t.number(row, p.col, p.what);
      if (!(*p.value > 0))
        throw MeasurementError(specimens_file, row.line, static_cast<long>(p.col + 1),
                               fmt::format("'{}' must be positive", t.header()[p.col]),
                               fmt::format("write the {}", p.what));
    }
    if (!(s.pin_distance < s.span) || s.span > s.length * (1 + 1e-9))
      throw MeasurementError(specimens_file, row.line, static_cast<long>(cd + 1),
                             fmt::format("geometry is not a four-point bending test: pin distance {} m, span {} m, "
                                         "length {} m",
                                         s.pin_distance, s.span, s.length),
                             "the loading pins lie inside the span, and the span is at most the length");
    if (ccrack) s.crack_position = t.optional_number(row, *ccrack, "crack position in m from the centre");
    if (ccount) s.fragment_count = t.optional_number(row, *ccount, "number of fragments");
    const std::string curve_name = ccurve && !t.text(row, *ccurve).empty() ? t.text(row, *ccurve)
                                                                           : "curves/" + s.id + ".csv";
    const auto curve_file = folder / curve_name;
    if (!std::filesystem::exists(curve_file))
      throw MeasurementError(specimens_file, row.line, ccurve ? static_cast<long>(*ccurve + 1) : 0,
                             fmt::format("the curve file {} of specimen '{}' does not exist", curve_file.string(), s.id),
                             "put the curve at curves/<id>.csv or name it in a 'curve' column");
    s.curve = read_curve(curve_file, set.metadata);
    s.curve.id = s.id;
    std::string frag_name = cfrag ? t.text(row, *cfrag) : "";
    if (frag_name.empty() && std::filesystem::exists(folder / "fragments" / (s.id + ".csv")))
      frag_name = "fragments/" + s.id + ".csv";
    if (!frag_name.empty()) read_fragments(folder / frag_name, s);
    set.specimens.push_back(std::move(s));
  }
  return set;
}

}  // namespace shard::measure
