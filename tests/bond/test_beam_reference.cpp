// beam_bond against its stored reference data (beam_reference.hpp): the plugin file is loaded
// through the PluginHost, the stored bonded configuration recorded, and each stored step
// recomputed; forces, torques, energies, break decisions and break stresses must match. One file
// for plain beam_bond and one per effect policy (plugins/bond/beam_bond/reference/).
//
// Tolerance. On the machine and build that wrote the files the results are the same bits; another
// compiler, ISA or libm may fuse a multiply-add or sum in another order, which moves each result by
// a few ulp of the largest term entering it. The axial strain d / l0 - 1 cancels: at the smallest
// stored strains (~1e-4) a few ulp of 1 are ~1e-12 of the strain. So each component must agree to
//   |a - b| <= 1e-10 |b_vector| + 1e-12 max_file |b|,
// 100x above that estimate and far below any change of the physics (a change of one parameter by
// 1e-6 relative moves the results by ~1e-6). Break decisions must agree exactly: rounding can flip
// one only for a bond within ~1e-12 relative of its strength, a chance of ~1e-10 over the 108
// stored bond evaluations of a file.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "beam_reference.hpp"
#include "shard/plugin_host.hpp"

using namespace shard;

namespace {

constexpr double kRelative = 1e-10, kOfLargest = 1e-12;
const std::string kFolder = SHARD_SOURCE_DIR "/plugins/bond/beam_bond/reference";

double largest(const std::vector<test::ReferenceStep>& steps, std::vector<Vec3> test::ReferenceStep::* field) {
  double m = 0;
  for (const auto& s : steps)
    for (const Vec3& v : s.*field) m = std::max(m, v.cwiseAbs().maxCoeff());
  return m;
}

// Largest deviation over the file, in units of the tolerance (must stay <= 1).
struct Worst {
  double ratio = 0;
};

void compare(const Vec3& got, const Vec3& want, double scale, Worst& w) {
  const double tol = kRelative * want.norm() + kOfLargest * scale;
  for (int c = 0; c < 3; ++c) {
    const double dev = std::abs(got[c] - want[c]);
    w.ratio = std::max(w.ratio, tol > 0 ? dev / tol : (dev > 0 ? INFINITY : 0.0));
    CHECK(dev <= tol);
  }
}

}  // namespace

TEST_CASE("beam_bond reproduces its reference data, plain and with each effect policy") {
  PluginHost host;
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_beam_bond.so");
  for (const auto& c : test::beam_reference_cases()) {
    const std::string path = kFolder + "/" + c.name + ".toml";
    CAPTURE(path);
    REQUIRE(std::filesystem::exists(path));
    test::ReferenceData d = test::read_reference(path);
    // The file's parameters are the case's: a case edited without regenerating is caught here.
    REQUIRE(d.params.size() == c.params.size());
    const auto model = host.make_bond("beam_bond", host.params(PluginKind::Bond, "beam_bond", d.params));
    test::HandBonds s = d.bonded;
    s.dt = d.dt;
    s.initialize(*model);
    const double force_scale = largest(d.steps, &test::ReferenceStep::force);
    const double torque_scale = std::max(largest(d.steps, &test::ReferenceStep::torque_i),
                                         largest(d.steps, &test::ReferenceStep::torque_j));
    double energy_scale = 0;
    for (const auto& st : d.steps)
      for (const double e : st.energy) energy_scale = std::max(energy_scale, std::abs(e));
    Worst worst;
    std::size_t broken = 0, intact = 0;
    for (std::size_t k = 0; k < d.steps.size(); ++k) {
      const test::ReferenceStep& want = d.steps[k];
      CAPTURE(k);
      test::apply(want, s);
      s.compute(*model);
      for (std::size_t b = 0; b < s.i.size(); ++b) {
        CAPTURE(b);
        REQUIRE(int(s.broken[b]) == want.broken[b]);
        compare(s.force[b], want.force[b], force_scale, worst);
        compare(s.torque_i[b], want.torque_i[b], torque_scale, worst);
        compare(s.torque_j[b], want.torque_j[b], torque_scale, worst);
        const double e_tol = kRelative * std::abs(want.energy[b]) + kOfLargest * energy_scale;
        CHECK(std::abs(s.energy[b] - want.energy[b]) <= e_tol);
        if (s.broken[b]) {
          ++broken;
          CHECK(std::abs(s.stress[b].sigma_vm - want.sigma_vm[b]) <= kRelative * want.sigma_vm[b]);
        } else {
          ++intact;
        }
      }
    }
    MESSAGE(c.name, ": ", broken, " breaks, ", intact, " intact bond evaluations; worst deviation ", worst.ratio,
            " of the tolerance");
    // The data must exercise both outcomes, or the break check is not tested.
    CHECK(broken > 0);
    CHECK(intact > 0);
  }
}

TEST_CASE("a reference file with a missing key is refused naming the file and the key") {
  const std::string path = std::filesystem::temp_directory_path().string() + "/beam_reference_broken.toml";
  {
    std::ofstream out(path);
    out << "model = \"beam_bond\"\ndt = 1e-6\n[params]\n[bonded]\ni = [0]\n";
  }
  try {
    test::read_reference(path);
    FAIL("no error");
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    CHECK(what.find(path) != std::string::npos);
    CHECK(what.find("'j'") != std::string::npos);
  }
}
