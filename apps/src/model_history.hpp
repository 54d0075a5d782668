#pragma once
// The model history, <work>/history.jsonl: one JSON line per model version that `shard compare`
// and `shard calibrate-effect` judged, which `shard history` tabulates and plots.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "shard/measure/comparison.hpp"
#include "shard/measure/rate_comparison.hpp"

namespace shard {

// One model version in <work>/history.jsonl: what `shard history` tabulates.
struct HistoryEntry {
  std::string command, label;
  std::vector<std::string> effects;
  std::map<std::string, double> parameters;
  double nrmse = 0, chi_square = 0;
  std::map<std::string, double> regimes;   // mean standardised residual per regime
  std::map<std::string, double> features;  // relative error per feature
};
HistoryEntry history_entry(const std::string& command, const std::string& label, const measure::Comparison& c);
// Several rates in one entry: the joint NRMSE and chi-square; regimes and features named
// "<name>@<rate>" (as in the joint residual) when there is more than one rate.
HistoryEntry history_entry(const std::string& command, const std::string& label, const measure::RateComparison& c);
void append_history(const std::filesystem::path& work_dir, const HistoryEntry& entry);
std::vector<HistoryEntry> read_history(const std::filesystem::path& work_dir);

}  // namespace shard
