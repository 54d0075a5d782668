// Failures say which path and what to do, arrive as OutputError, and HDF5 prints nothing of
// its own to stderr. (Tests run as root in CI, so "unwritable" is made with a file standing
// where a folder must be, which no permission bit overrides.)
#include <doctest/doctest.h>
#include <fcntl.h>
#include <unistd.h>

#include <fstream>
#include <functional>

#include "run_fixtures.hpp"
#include "shard/run_file.hpp"

using namespace shard;
using namespace shard::test;

namespace {

// Runs `action`, which must throw OutputError; returns its message and whatever reached stderr.
std::pair<std::string, std::string> capture_failure(const std::filesystem::path& scratch,
                                                    const std::function<void()>& action) {
  const auto log = scratch / "stderr.txt";
  std::fflush(stderr);
  const int saved = ::dup(2);
  const int sink = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ::dup2(sink, 2);
  std::string message;
  try {
    action();
  } catch (const OutputError& error) {
    message = error.what();
  }
  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(saved);
  ::close(sink);
  std::ifstream in(log);
  return {message, std::string(std::istreambuf_iterator<char>(in), {})};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("an output path that cannot be written fails at construction, naming the path") {
  TempFolder folder("errors");
  const auto blocker = folder.path() / "not_a_folder";
  std::ofstream(blocker) << "a file where the output folder should be";

  SUBCASE("folder blocked by a file") {
    const auto path = blocker / "run.h5";
    const auto [message, printed] = capture_failure(folder.path(), [&] {
      RunWriter writer(path, make_metadata(), {});
    });
    CHECK(contains(message, blocker.string()));
    CHECK(contains(message, "writ"));  // "... a folder you can write to"
    CHECK(printed.empty());
  }
  SUBCASE("path is a folder") {
    const auto [message, printed] = capture_failure(folder.path(), [&] {
      RunWriter writer(folder.path(), make_metadata(), {});
    });
    CHECK(contains(message, "cannot create the run file '" + folder.path().string() + "'"));
    CHECK(contains(message, "writable"));
    CHECK(printed.empty());  // HDF5's own error stack is not printed
  }
  SUBCASE("the .xmf name is refused as a run file") {
    CHECK_THROWS_AS(RunWriter(folder.path() / "run.xmf", make_metadata(), {}), OutputError);
  }
}

TEST_CASE("inconsistent input is refused before anything is written") {
  TempFolder folder("refuse");
  const auto path = folder.path() / "run.h5";
  {
    RunWriter writer(path, make_metadata(), {"pin"});
    CHECK_THROWS_AS(writer.append_series(make_row(0, 2)), OutputError);  // two walls for one
    Particles p = make_particles(4, 0);
    p.radius.pop_back();
    CHECK_THROWS_AS(writer.write_frame(0, 0.0, p, Bonds{}), OutputError);
    Bonds b = make_chain(4, 99);
    b.j.back() = 4;  // past the last particle
    CHECK_THROWS_AS(writer.write_frame(0, 0.0, make_particles(4, 0), b), OutputError);
    std::vector<Index> labels(3, 0);
    CHECK_THROWS_AS(writer.write_frame(0, 0.0, make_particles(4, 0), Bonds{}, &labels),
                    OutputError);
    CHECK_THROWS_AS(RunWriter(folder.path() / "bad_wall.h5", make_metadata(), {"a/b"}),
                    OutputError);
    // The refused frames left nothing behind: the next frame is frame 0.
    writer.write_frame(7, 1.0, make_particles(4, 0), make_chain(4, 99));
  }
  const RunFile run(path);
  REQUIRE(run.frame_count() == 1);
  CHECK(run.read_frame(0).step == 7);
  CHECK(run.read_frame(0).bond_i.size() == 3);
}

TEST_CASE("RunFile refuses missing files and files that are not run files") {
  TempFolder folder("reader");
  const auto missing = folder.path() / "missing.h5";
  const auto [message, printed] = capture_failure(folder.path(), [&] { RunFile run(missing); });
  CHECK(contains(message, missing.string()));
  CHECK(printed.empty());
  const auto text = folder.path() / "notes.h5";
  std::ofstream(text) << "not HDF5";
  const auto [text_message, text_printed] =
      capture_failure(folder.path(), [&] { RunFile run(text); });
  CHECK(contains(text_message, text.string()));
  CHECK(text_printed.empty());
}
