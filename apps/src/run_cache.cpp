#include "run_cache.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <fstream>
#include <iterator>
#include <stdexcept>

#include "byte_record.hpp"
#include "shard/io/atomic_file.hpp"
#include "shard/measure/significant_digits.hpp"
#include "shard/version.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kRunCacheMagic = 0x43524853;  // "SHRC" in this machine's byte order

std::string file_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot be read");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The entry's outcome; throws with the reason the entry is not one of this format and release for `key`.
RunOutcome decode_entry(const std::string& bytes, const std::string& key, const std::string& release) {
  ByteReader in(bytes, "run cache entry");
  if (bytes.size() < 8 || in.number<std::uint32_t>() != kRunCacheMagic)
    throw std::runtime_error("not a run cache entry of shard (or one written on a machine of the other byte order)");
  const auto format = in.number<std::uint32_t>();
  if (format != kRunCacheFormat && format != 1)
    throw std::runtime_error(fmt::format("format version {}, this shard reads version {}", format, kRunCacheFormat));
  const std::string made_by = format == 1 ? std::string(kFormatOneRelease) : in.text();
  if (made_by != release)
    throw std::runtime_error(fmt::format("made by shard {}, this is shard {} (a release may run a scene otherwise)",
                                         made_by, release));
  if (const auto stored = in.text(); stored != key)
    throw std::runtime_error(fmt::format("holds the run of key {}", stored));
  RunOutcome outcome = decode_outcome(in.text());
  if (!in.at_end()) throw std::runtime_error("longer than its fields");
  return outcome;
}

}  // namespace

RunCache::RunCache(fs::path folder, std::string release)
    : folder_(std::move(folder)), release_(release.empty() ? std::string(version()) : std::move(release)) {
  fs::create_directories(folder_);
}

std::optional<RunOutcome> RunCache::find(const std::string& key, std::ostream& log) const {
  const fs::path file = entry(key);
  if (!fs::exists(file)) {
    if (fs::exists(folder_ / (key + ".csv")))
      fmt::print(log, "  run cache: {} is of an earlier format (text), so its run is made again\n",
                 (folder_ / (key + ".csv")).string());
    return std::nullopt;
  }
  try {
    RunOutcome outcome = decode_entry(file_bytes(file), key, release_);
    outcome.key = key;
    outcome.cached = true;
    return outcome;
  } catch (const std::exception& e) {
    fmt::print(log, "  run cache: {}: {}; its run is made again\n", file.string(), e.what());
    return std::nullopt;
  }
}

RunOutcome RunCache::store(const std::string& key, const RunOutcome& outcome) const {
  const std::string record = encode_outcome(at_cache_precision(outcome));
  ByteWriter out;
  out.number(kRunCacheMagic);
  out.number(kRunCacheFormat);
  out.text(release_);
  out.text(key);
  out.text(record);
  io::write_file_atomically(entry(key), out.bytes());
  // What find() will give back (the record decoded: zero uncertainties the length of the curve).
  RunOutcome kept = decode_outcome(record);
  kept.key = key;
  return kept;
}

RunOutcome at_cache_precision(RunOutcome o) {
  auto nine = [](std::vector<double>& values) {
    for (double& v : values) v = significant(v, 9);
  };
  nine(o.curve.time);
  nine(o.curve.displacement);
  nine(o.curve.force);
  nine(o.fragment_sizes);
  if (o.crack_position) o.crack_position = significant(*o.crack_position, 9);
  o.kinetic_to_elastic = significant(o.kinetic_to_elastic, 6);
  return o;
}

}  // namespace shard
