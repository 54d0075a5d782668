// The `shard fragments` sub-command end to end on a run file written in the documented layout.
#include <doctest/doctest.h>

#include <fstream>
#include <sstream>

#include "run_file_fixture.hpp"
#include "shard/analysis/fsd_plot.hpp"
#include "shard/app/fragments_cli.hpp"

using namespace shard;
using namespace shard::analysis;

namespace {

struct Scratch {
  std::filesystem::path dir;
  explicit Scratch(const std::string& name)
      : dir(std::filesystem::temp_directory_path() / ("shard_test_fragments_" + name)) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    test::write_run_file(dir / "run.h5", test::breaking_bar(), 2500.0);
  }
  ~Scratch() { std::filesystem::remove_all(dir); }
};

struct Result {
  int status = 0;
  std::string out, err;
};

// Parses argv with the CLI11 options as the `shard` binary would, then runs the command.
Result run(std::vector<std::string> args) {
  CLI::App app("fragments");
  FragmentsOptions options;
  add_fragments_options(app, options);
  std::reverse(args.begin(), args.end());  // CLI11 takes a reversed vector
  app.parse(args);
  std::ostringstream out, err;
  Result r;
  r.status = fragments_command(options, out, err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

std::size_t line_count(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::size_t lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  return lines;
}

}  // namespace

TEST_CASE("fragments: table, distribution, CSV and lineage of the last frame") {
  const Scratch s("table");
  const auto run_file = (s.dir / "run.h5").string();
  const auto csv = (s.dir / "frags.csv").string();
  const Result r = run({run_file, "--csv", csv, "--since", "0", "--fines", "0.003"});
  INFO(r.out, r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("frame 2 (step 1000") != std::string::npos);
  CHECK(r.out.find("fragments 2") != std::string::npos);
  // Two 3-sphere fragments: x50 = d_eq = 2 mm * 3^(1/3) = 2.8845 mm.
  CHECK(r.out.find("x50 2.8845 mm") != std::string::npos);
  // Both are above 3 mm? No: 2.88 mm < 3 mm, so all the mass is fines.
  CHECK(r.out.find("(100 % of the mass)") != std::string::npos);
  CHECK(r.out.find("0 -> 0 (3 particles), 1 (3 particles)") != std::string::npos);
  CHECK(line_count(csv) == 3);  // header + 2 fragments
}

TEST_CASE("fragments --write-labels stores the labels; a wrong frame is a clear error") {
  const Scratch s("labels");
  const auto run_file = (s.dir / "run.h5").string();
  REQUIRE(run({run_file, "--frame", "0", "--write-labels"}).status == 0);
  const hid_t h = H5Fopen(run_file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  CHECK(H5Lexists(h, "/frames/000000/fragment", H5P_DEFAULT) > 0);
  CHECK(H5Lexists(h, "/fragments", H5P_DEFAULT) > 0);
  CHECK(H5Lexists(h, "/frames/000002/fragment", H5P_DEFAULT) == 0);  // only the asked frame
  H5Fclose(h);
  const Result bad = run({run_file, "--frame", "7"});
  CHECK(bad.status == 1);
  CHECK(bad.err.find("no frame 7") != std::string::npos);
}

TEST_CASE("fragments --plot draws a PNG with gnuplot, or says how to get gnuplot") {
  const Scratch s("plot");
  const auto run_file = (s.dir / "run.h5").string();
  const auto png = s.dir / "fsd.png";
  const Result r = run({run_file, "--plot", png.string()});
  if (find_program("gnuplot")) {
    INFO(r.err);
    REQUIRE(r.status == 0);
    std::ifstream in(png, std::ios::binary);
    char magic[8] = {};
    in.read(magic, 8);
    CHECK(std::string(magic + 1, 3) == "PNG");
    CHECK(std::filesystem::exists(s.dir / "fsd.png.gp"));
  } else {
    CHECK(r.status == 1);
    CHECK(r.err.find("gnuplot-nox") != std::string::npos);
  }
}

TEST_CASE("titles and paths cannot inject gnuplot commands") {
  CHECK(gnuplot_quote("it's") == "'it''s'");
  CHECK(gnuplot_quote("a\nsystem('x')") == "'a system(''x'')'");
  if (!find_program("gnuplot")) return;
  const auto dir = std::filesystem::temp_directory_path() / "shard_test_plot_injection";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto marker = dir / "INJECTED";
  const std::string title = "x'\nsystem('touch " + marker.string() + "')\n'";
  const std::vector<double> d{1e-3, 2e-3}, mass{1.0, 1.0};
  plot_size_distribution(size_distribution(d, mass), dir / "p.svg", title);
  CHECK(std::filesystem::exists(dir / "p.svg"));
  CHECK_FALSE(std::filesystem::exists(marker));
  std::filesystem::remove_all(dir);
}
