// The breakage curve on hand-made plates whose answers are known exactly: Wilson's interval from
// its formula, the pooled x50 of a fragment table, the speed bins, the bootstrap interval of a
// two-plate population, and the tables as CSV and HDF5.
#include <doctest/doctest.h>
#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "shard/analysis/body_statistics.hpp"
#include "shard/analysis/breakage_curve.hpp"
#include "shard/analysis/breakage_tables.hpp"
#include "shard/analysis/column_table.hpp"
#include "shard/analysis/fragment_table.hpp"
#include "shard/analysis/plate_outcome.hpp"

using namespace shard;
using namespace shard::analysis;

namespace {

PlateOutcome plate(double speed, bool broken, std::vector<double> d, std::vector<double> mass, double value = 0) {
  PlateOutcome p;
  p.impacted = speed > 0;
  p.impact_speed = speed;
  p.broken = broken;
  p.fragment_d = std::move(d);
  p.fragment_mass = std::move(mass);
  p.fragments = p.fragment_d.size();
  p.value = value;
  return p;
}

std::vector<const PlateOutcome*> pointers(const std::vector<PlateOutcome>& plates) {
  std::vector<const PlateOutcome*> out;
  for (const auto& p : plates) out.push_back(&p);
  return out;
}

}  // namespace

TEST_CASE("Wilson's score interval equals its closed form (values computed independently to 17 digits)") {
  // (k, n) -> [lower, upper] at z = 1.959963984540054, from centre +- half of the header's formula
  // evaluated in Python's double arithmetic.
  const Interval a = wilson_interval(4, 6);
  CHECK(a.lower == doctest::Approx(0.29999331513839206).epsilon(1e-13));
  CHECK(a.upper == doctest::Approx(0.9032285888942195).epsilon(1e-13));
  const Interval b = wilson_interval(7, 20);
  CHECK(b.lower == doctest::Approx(0.18119182410108206).epsilon(1e-13));
  CHECK(b.upper == doctest::Approx(0.5671457233147638).epsilon(1e-13));
  // At k = 0 and k = n one bound is exact; the other is z^2 / (n + z^2) from the end.
  const Interval none = wilson_interval(0, 5);
  CHECK(none.lower == 0.0);
  CHECK(none.upper == doctest::Approx(0.43448246478317476).epsilon(1e-13));
  const Interval all = wilson_interval(3, 3);
  CHECK(all.upper == 1.0);
  CHECK(all.lower == doctest::Approx(0.43850296824495455).epsilon(1e-13));
  const Interval empty = wilson_interval(0, 0);
  CHECK(empty.lower == 0.0);
  CHECK(empty.upper == 1.0);
  CHECK_THROWS_AS(wilson_interval(3, 2), std::invalid_argument);
  // Narrower with more plates at the same share: 40 of 60 against 4 of 6.
  const Interval more = wilson_interval(40, 60);
  CHECK(more.upper - more.lower < 0.5 * (a.upper - a.lower));
}

TEST_CASE("a group's pooled x50 is the mass-weighted median of all its plates' fragments") {
  // Plate A: fragments 1, 2, 3 mm of 1, 1, 2 kg; plate B: one 4 mm piece of 4 kg. Pooled Q =
  // 1/8, 2/8, 4/8, 8/8 at 1, 2, 3, 4 mm: x50 = 3 mm exactly (p = Q_3), x10 = 1 mm (p <= Q_1),
  // x90 = 3 + (0.9 - 0.5) / 0.5 * (4 - 3) = 3.8 mm.
  const std::vector<PlateOutcome> plates{plate(1.2, true, {1e-3, 2e-3, 3e-3}, {1, 1, 2}),
                                         plate(1.3, false, {4e-3}, {4})};
  const BreakageGroup g = breakage_group(pointers(plates));
  CHECK(g.plates == 2);
  CHECK(g.broken == 1);
  CHECK(g.broken_share == 0.5);
  CHECK(g.fragments == 4);
  CHECK(g.x50 == doctest::Approx(3e-3).epsilon(1e-15));
  CHECK(g.x10 == doctest::Approx(1e-3).epsilon(1e-15));
  CHECK(g.x90 == doctest::Approx(3.8e-3).epsilon(1e-14));
  CHECK(g.mean_speed == doctest::Approx(1.25));
  CHECK(g.min_speed == 1.2);
  CHECK(g.max_speed == 1.3);
  const Interval w = wilson_interval(1, 2);
  CHECK(g.broken_interval.lower == w.lower);
  CHECK(g.broken_interval.upper == w.upper);
}

TEST_CASE("the bootstrap interval of x50 resamples whole plates, deterministically") {
  // Two single-fragment plates of equal mass, 1 mm and 3 mm. A resample is {A, A} (x50 = 1 mm),
  // {B, B} (3 mm) or {A, B} (Q = 0.5 at 1 mm, so x50 = 1 mm): x50 is 1 mm with probability 3/4
  // and 3 mm with 1/4, so the 2.5 % and 97.5 % quantiles of 2000 resamples are 1 and 3 mm.
  const std::vector<PlateOutcome> two{plate(1, false, {1e-3}, {1}), plate(1, false, {3e-3}, {1})};
  const Interval i = bootstrap_x50(pointers(two));
  CHECK(i.lower == 1e-3);
  CHECK(i.upper == 3e-3);
  const Interval again = bootstrap_x50(pointers(two));
  CHECK(again.lower == i.lower);
  CHECK(again.upper == i.upper);
  // Identical plates leave nothing to resample: the interval is the point.
  const std::vector<PlateOutcome> same{plate(1, true, {1e-3, 2e-3}, {1, 3}), plate(1, true, {1e-3, 2e-3}, {1, 3})};
  const BreakageGroup g = breakage_group(pointers(same));
  CHECK(g.x50 == doctest::Approx(1e-3 + (0.5 - 0.25) / 0.75 * 1e-3).epsilon(1e-14));
  CHECK(g.x50_interval.lower == doctest::Approx(g.x50).epsilon(1e-15));
  CHECK(g.x50_interval.upper == doctest::Approx(g.x50).epsilon(1e-15));
  // A spread population: the interval brackets the estimate and lies within the sizes.
  std::vector<PlateOutcome> spread;
  for (int k = 1; k <= 12; ++k) spread.push_back(plate(1, k % 2 == 0, {k * 1e-3, 0.5e-3}, {1.0 * k, 0.3}));
  const BreakageGroup s = breakage_group(pointers(spread));
  CHECK(s.x50_interval.lower <= s.x50);
  CHECK(s.x50_interval.upper >= s.x50);
  CHECK(s.x50_interval.lower >= 0.5e-3);
  CHECK(s.x50_interval.upper <= 12e-3);
  CHECK(s.x50_interval.upper > s.x50_interval.lower);
}

TEST_CASE("speed bins: equal widths over the impacted plates, [lower, upper) with the last closed") {
  std::vector<PlateOutcome> plates{plate(1.0, false, {1e-3}, {1}), plate(1.4, true, {1e-3}, {1}),
                                   plate(2.0, true, {1e-3}, {1}), plate(2.0, true, {2e-3}, {1}),
                                   plate(0, false, {3e-3}, {1})};  // no wall contact: in no bin
  const std::vector<double> edges = speed_bin_edges(plates);  // 4 impacted: round(sqrt 4) = 2 bins
  REQUIRE(edges.size() == 3);
  CHECK(edges[0] == 1.0);
  CHECK(edges[1] == 1.5);
  CHECK(edges[2] == 2.0);
  const auto bins = breakage_by_speed(plates, edges);
  REQUIRE(bins.size() == 2);
  CHECK(bins[0].plates == 2);
  CHECK(bins[0].broken == 1);
  CHECK(bins[1].plates == 2);
  CHECK(bins[1].broken == 2);
  CHECK(bins[1].broken_interval.upper == 1.0);
  CHECK(bins[0].lower == 1.0);
  CHECK(bins[1].upper == 2.0);
  CHECK_THROWS_AS(breakage_by_speed(plates, {1.0, 1.0, 2.0}), std::invalid_argument);
  // By value: the plate without contact counts as a plate of its value, flagged.
  plates[4].value = 1;
  const auto by_value = breakage_by_value(plates);
  REQUIRE(by_value.size() == 2);
  CHECK(by_value[0].lower == 0);
  CHECK(by_value[0].plates == 4);
  CHECK(by_value[1].plates == 1);
  CHECK(by_value[1].not_impacted == 1);
}

TEST_CASE("plate outcomes carry each body's own fragments") {
  // Body 0: particles 0 and 1, unbonded (two fragments); body 1: particles 2 and 3, bonded (one).
  const std::vector<Index> id{0, 1, 2, 3};
  const std::vector<Vec3> x{Vec3(0, 0, 0), Vec3(0.01, 0, 0), Vec3(0.1, 0, 0), Vec3(0.11, 0, 0)};
  const std::vector<Vec3> v(4, Vec3::Zero());
  const std::vector<double> r{0.005, 0.004, 0.005, 0.005}, m{2, 1, 1, 1};
  const std::vector<std::int32_t> body{0, 0, 1, 1};
  const std::vector<Index> bi{2}, bj{3};
  const ParticleSample sample{id, x, v, r, m, body};
  const FragmentAnalysis a = analyse_fragments(sample, {bi, bj});
  BodyReport report = body_statistics(sample, a.fragments, 0.9, 0);
  attach_impacts(report, {BodyImpact{true, 1, 0.01, Vec3(0, 0, -1.5), Vec3(0, 0, 1), 0}, BodyImpact{}});
  const auto plates = plate_outcomes(report, a.fragments, "run", 2.5, 3);
  REQUIRE(plates.size() == 2);
  CHECK(plates[0].fragment_d.size() == 2);
  CHECK(plates[0].broken);  // largest fraction 2/3 < 0.9
  CHECK(plates[0].impacted);
  CHECK(plates[0].impact_speed == 1.5);
  CHECK(plates[0].value == 2.5);
  CHECK(plates[0].seed == 3);
  CHECK(plates[1].fragment_d.size() == 1);
  CHECK_FALSE(plates[1].broken);
  CHECK_FALSE(plates[1].impacted);
  CHECK(plates[0].x50 == report.bodies[0].fsd.x50);
}

TEST_CASE("tables are written as CSV and as HDF5 groups with the same columns") {
  const std::vector<PlateOutcome> plates{plate(1.0, false, {1e-3}, {1}), plate(2.0, true, {1e-3, 2e-3}, {1, 1})};
  const auto bins = breakage_by_speed(plates, {0.5, 1.5, 2.5});
  const ColumnTable t = group_table(bins, GroupedBy::impact_speed, {});
  const auto dir = std::filesystem::temp_directory_path() / "breakage_tables";
  std::filesystem::create_directories(dir);
  write_csv(t, dir / "bins.csv");
  std::ifstream in(dir / "bins.csv");
  std::string header, row1, row2, extra;
  std::getline(in, header);
  std::getline(in, row1);
  std::getline(in, row2);
  CHECK_FALSE(static_cast<bool>(std::getline(in, extra)));
  CHECK(header.rfind("speed_lower_m_s,speed_upper_m_s,plates,broken,broken_share,broken_share_lower", 0) == 0);
  CHECK(row2.rfind("1.5,2.5,1,1,1,", 0) == 0);

  const auto h5 = dir / "tables.h5";
  std::filesystem::remove(h5);
  write_hdf5_table(h5, "/curve/by_speed", t);
  write_hdf5_table(h5, "/plates", plate_table(plates, "value"));
  write_hdf5_table(h5, "/curve/by_speed", t);  // replaced, not duplicated
  const hid_t f = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  const hid_t set = H5Dopen2(f, "/curve/by_speed/broken_share_upper", H5P_DEFAULT);
  REQUIRE(set >= 0);
  double upper[2] = {0, 0};
  CHECK(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, upper) >= 0);
  CHECK(upper[0] == wilson_interval(0, 1).upper);
  CHECK(upper[1] == 1.0);
  H5Dclose(set);
  CHECK(H5Aexists_by_name(f, "/curve/by_speed", "broken_share_interval", H5P_DEFAULT) > 0);
  CHECK(H5Lexists(f, "/plates/run", H5P_DEFAULT) > 0);
  H5Fclose(f);
}
