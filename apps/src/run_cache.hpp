#pragma once
// The measurement loop's run cache: one file per finished run, <folder>/<key>.run, keyed by the
// hash of the run's resolved scene text (measure_runner.hpp). An entry is the outcome record the
// workers send (run_job.hpp) behind a header naming the format, its version, the Shard release
// that made the run and the key, so an entry of another layout, of a machine of the other byte
// order, of another release (whose laws may give another outcome for the same scene), cut short,
// or renamed from another key is refused by name and the run is made again, never misread.
// Entries are written to a temporary file and renamed into place: a killed command leaves no torn
// entry, and two processes sharing the work folder never write into one file.
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>

#include "run_job.hpp"

namespace shard {

inline constexpr std::uint32_t kRunCacheFormat = 2;
// Format 1 kept no release; only Shard 0.1.0 wrote it.
inline constexpr std::string_view kFormatOneRelease = "0.1.0";

class RunCache {
 public:
  // `release`: the Shard release whose runs this cache gives back (this build's by default).
  explicit RunCache(std::filesystem::path folder, std::string release = {});
  std::filesystem::path entry(const std::string& key) const { return folder_ / (key + ".run"); }
  // The cached outcome of `key` (cached set), or none: no entry, or one this shard does not read,
  // which `log` names with the reason ("... is run again").
  std::optional<RunOutcome> find(const std::string& key, std::ostream& log) const;
  // Writes the entry and returns the outcome as it keeps it (at_cache_precision, key set); throws
  // std::runtime_error naming the entry when it cannot be written.
  RunOutcome store(const std::string& key, const RunOutcome& outcome) const;

 private:
  std::filesystem::path folder_;
  std::string release_;
};

// The outcome as the cache keeps it: the curve, the crack and the fragment sizes at nine
// significant digits and the kinetic/elastic ratio at six (shard/measure/significant_digits.hpp),
// the precision the loop's figures in docs/ were made with. Far below a testing machine's noise;
// a fresh run and a cached one give the same figures.
RunOutcome at_cache_precision(RunOutcome outcome);

}  // namespace shard
