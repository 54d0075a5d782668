#include "model_history.hpp"

#include <fmt/format.h>

#include <ctime>
#include <fstream>
#include <stdexcept>

#include "shard/io/json.hpp"
#include "shard/measure/report.hpp"

namespace shard {

namespace fs = std::filesystem;
using namespace measure;

HistoryEntry history_entry(const std::string& command, const std::string& label, const Comparison& c) {
  HistoryEntry h;
  h.command = command;
  h.label = label;
  h.nrmse = c.nrmse;
  for (double r : c.residual_vector().values) h.chi_square += r * r;
  for (const auto& g : c.regimes)
    if (g.points() > 0) h.regimes[std::string(regime_name(g.regime))] = g.mean_residual;
  for (const auto& f : c.features) h.features[std::string(feature_name(f.feature))] = f.relative_error;
  return h;
}

HistoryEntry history_entry(const std::string& command, const std::string& label, const RateComparison& c) {
  if (c.at.size() == 1) return history_entry(command, label, c.at.front());
  HistoryEntry h;
  h.command = command;
  h.label = label;
  h.nrmse = c.nrmse();
  h.chi_square = c.chi_square();
  for (std::size_t k = 0; k < c.at.size(); ++k) {
    const HistoryEntry one = history_entry(command, label, c.at[k]);
    for (const auto& [name, v] : one.regimes) h.regimes[fmt::format("{}@{:g}", name, c.rates[k])] = v;
    for (const auto& [name, v] : one.features) h.features[fmt::format("{}@{:g}", name, c.rates[k])] = v;
  }
  return h;
}

namespace {

// history.jsonl's record format: raise it when a key changes meaning or disappears.
constexpr int kHistoryFormatVersion = 1;

// A flat object of numbers ("parameters", "regimes", "features"); absent reads as empty.
std::map<std::string, double> number_map(const io::JsonFields& row, const std::string& key) {
  std::map<std::string, double> m;
  if (!row.has(key)) return m;
  const io::JsonFields object = row.object(key);
  for (const auto& [name, value] : object.json().items()) m[name] = object.number(name);
  return m;
}

HistoryEntry history_row(const io::Json& line, const std::string& origin) {
  const io::JsonFields row(line, origin);
  if (row.has("format_version") && row.integer("format_version") > kHistoryFormatVersion)
    throw io::JsonError(fmt::format("{}: format_version {} is newer than this shard reads ({}); read it with a newer "
                                    "shard or start a new --work folder",
                                    origin, row.integer("format_version"), kHistoryFormatVersion));
  HistoryEntry h;
  h.command = row.text("command");
  h.label = row.text("label");
  if (row.has("effects")) {
    const io::Json& effects = row.json().at("effects");
    if (!effects.is_array())
      throw io::JsonError(fmt::format("{}: key 'effects' is not an array; expected the names of the effects", origin));
    for (std::size_t i = 0; i < effects.size(); ++i) {
      if (!effects[i].is_string())
        throw io::JsonError(fmt::format("{}: key effects[{}]: expected the name of an effect (a string)", origin, i));
      h.effects.push_back(effects[i].get<std::string>());
    }
  }
  h.parameters = number_map(row, "parameters");
  h.nrmse = row.number("nrmse");
  h.chi_square = row.number("chi_square");
  h.regimes = number_map(row, "regimes");
  h.features = number_map(row, "features");
  return h;
}

}  // namespace

void append_history(const fs::path& work_dir, const HistoryEntry& h) {
  fs::create_directories(work_dir);
  io::Json line = io::json_document(kHistoryFormatVersion);
  line["time"] = static_cast<long long>(std::time(nullptr));
  line["command"] = h.command;
  line["label"] = h.label;
  line["effects"] = h.effects;
  line["parameters"] = h.parameters;
  line["nrmse"] = h.nrmse;
  line["chi_square"] = h.chi_square;
  line["regimes"] = h.regimes;
  line["features"] = h.features;
  std::ofstream out(work_dir / "history.jsonl", std::ios::app);
  out << io::json_line(line);
  if (!out) throw std::runtime_error(fmt::format("{}: cannot append the model version (disk full or read-only?)",
                                                 (work_dir / "history.jsonl").string()));
}

std::vector<HistoryEntry> read_history(const fs::path& work_dir) {
  const fs::path file = work_dir / "history.jsonl";
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error(fmt::format("{}: no history yet; `shard compare` and `shard calibrate-effect` with "
                                         "--work {} write it",
                                         file.string(), work_dir.string()));
  std::vector<HistoryEntry> out;
  std::string line;
  for (std::size_t n = 1; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const std::string origin = fmt::format("{}:{}", file.string(), n);
    out.push_back(history_row(io::parse_json(line, file.string(), n), origin));
  }
  return out;
}

}  // namespace shard
