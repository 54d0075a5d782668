// The measurement loop's run cache (apps/src/run_cache.hpp): an entry gives back the outcome it
// was given, at the loop's precision; an entry of another format or version, one another release
// made, a text entry of the earlier layout, one cut short and one renamed from another key are
// refused by name, so their runs are made again; an entry is written whole (no temporary file is left beside it).
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "byte_record.hpp"
#include "run_cache.hpp"
#include "shard/version.hpp"

namespace fs = std::filesystem;
using namespace shard;

namespace {

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  return dir;
}

RunOutcome sample_outcome() {
  RunOutcome o;
  o.curve.time = {0.0, 1e-3, 2e-3};
  o.curve.displacement = {0.0, 1.0 / 3.0 * 1e-5, 2.0 / 3.0 * 1e-5};
  o.curve.force = {0.0, 12.345678912345, 25.5};
  o.kinetic_to_elastic = 0.00123456789;
  o.wall_seconds = 1.25;
  o.crack_position = 2.0 / 3.0 * 1e-3;
  o.fragment_sizes = {1.0 / 7.0 * 1e-2, 1e-3};
  return o;
}

void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("a cache entry gives back its outcome at nine significant digits, marked cached") {
  const RunCache cache(fresh("run_cache_round_trip"));
  const RunOutcome kept = cache.store("00ab", sample_outcome());
  CHECK_FALSE(kept.cached);
  CHECK(kept.curve.force[1] == 12.3456789);  // the value {:.9g} writes, read back
  CHECK(kept.kinetic_to_elastic == 0.00123457);
  CHECK(kept.curve.u_force == std::vector<double>(3, 0.0));  // as the entry gives it back
  std::ostringstream log;
  const auto found = cache.find("00ab", log);
  REQUIRE(found.has_value());
  CHECK(log.str().empty());
  CHECK(found->cached);
  CHECK(found->key == "00ab");
  CHECK(found->curve.time == kept.curve.time);
  CHECK(found->curve.displacement == kept.curve.displacement);
  CHECK(found->curve.force == kept.curve.force);
  CHECK(found->curve.u_force == std::vector<double>(3, 0.0));  // a simulated curve has no measurement noise
  CHECK(found->curve.u_displacement == std::vector<double>(3, 0.0));
  CHECK(found->kinetic_to_elastic == kept.kinetic_to_elastic);
  CHECK(found->wall_seconds == 1.25);
  CHECK(found->crack_position == kept.crack_position);
  CHECK(found->fragment_sizes == kept.fragment_sizes);

  // Written whole: the folder holds the entry and nothing else.
  std::size_t files = 0;
  for (const auto& f : fs::directory_iterator(cache.entry("00ab").parent_path()))
    if (f.is_regular_file()) ++files;
  CHECK(files == 1);
}

TEST_CASE("a run without a crack keeps none") {
  const RunCache cache(fresh("run_cache_no_crack"));
  RunOutcome o = sample_outcome();
  o.crack_position.reset();
  o.fragment_sizes.clear();
  cache.store("c0", o);
  std::ostringstream log;
  const auto found = cache.find("c0", log);
  REQUIRE(found.has_value());
  CHECK_FALSE(found->crack_position.has_value());
  CHECK(found->fragment_sizes.empty());
}

TEST_CASE("entries this shard does not read are refused by name, and their runs are made again") {
  const fs::path folder = fresh("run_cache_refused");
  const RunCache cache(folder);
  std::ostringstream log;

  SUBCASE("no entry: nothing to say") {
    CHECK_FALSE(cache.find("0001", log).has_value());
    CHECK(log.str().empty());
  }
  SUBCASE("the earlier text layout") {
    write_bytes(folder / "0002.csv", "# kinetic_to_elastic=0.001 wall_seconds=1.000\ntime,displacement,force\n0,0,0\n");
    CHECK_FALSE(cache.find("0002", log).has_value());
    CHECK(log.str().find((folder / "0002.csv").string()) != std::string::npos);
    CHECK(log.str().find("earlier format") != std::string::npos);
  }
  SUBCASE("a foreign file under the entry's name") {
    write_bytes(cache.entry("0003"), "time,displacement,force\n0,0,0\n");
    CHECK_FALSE(cache.find("0003", log).has_value());
    CHECK(log.str().find(cache.entry("0003").string()) != std::string::npos);
    CHECK(log.str().find("not a run cache entry") != std::string::npos);
    CHECK(log.str().find("its run is made again") != std::string::npos);
  }
  SUBCASE("another format version") {
    cache.store("0004", sample_outcome());
    std::string bytes = read_bytes(cache.entry("0004"));
    ByteWriter version;
    version.number<std::uint32_t>(kRunCacheFormat + 1);
    bytes.replace(4, 4, version.bytes());
    write_bytes(cache.entry("0004"), bytes);
    CHECK_FALSE(cache.find("0004", log).has_value());
    CHECK(log.str().find(fmt::format("format version {}, this shard reads version {}", kRunCacheFormat + 1,
                                     kRunCacheFormat)) != std::string::npos);
  }
  SUBCASE("another release's run") {
    RunCache(folder, "0.0.9").store("0008", sample_outcome());
    CHECK_FALSE(cache.find("0008", log).has_value());
    CHECK(log.str().find(fmt::format("made by shard 0.0.9, this is shard {}", shard::version())) != std::string::npos);
    CHECK(RunCache(folder, "0.0.9").find("0008", log).has_value());
  }
  SUBCASE("the first format, which only release 0.1.0 wrote") {
    ByteWriter old;
    old.number<std::uint32_t>(0x43524853);
    old.number<std::uint32_t>(1);
    old.text("0009");
    old.text(encode_outcome(sample_outcome()));
    write_bytes(cache.entry("0009"), old.bytes());
    CHECK(RunCache(folder, "0.1.0").find("0009", log).has_value());
    CHECK_FALSE(RunCache(folder, "0.2.0").find("0009", log).has_value());
    CHECK(log.str().find("made by shard 0.1.0, this is shard 0.2.0") != std::string::npos);
  }
  SUBCASE("an entry cut short") {
    cache.store("0005", sample_outcome());
    const std::string bytes = read_bytes(cache.entry("0005"));
    write_bytes(cache.entry("0005"), bytes.substr(0, bytes.size() / 2));
    CHECK_FALSE(cache.find("0005", log).has_value());
    CHECK(log.str().find("cut short") != std::string::npos);
  }
  SUBCASE("an entry renamed from another key") {
    cache.store("0006", sample_outcome());
    fs::copy_file(cache.entry("0006"), cache.entry("0007"));
    CHECK_FALSE(cache.find("0007", log).has_value());
    CHECK(log.str().find("holds the run of key 0006") != std::string::npos);
  }
}
