// The process boundary of an isolated run (shard/driver/worker_process.hpp), with ordinary
// programs as workers: bytes go in and come back unchanged, and a worker that dies is told apart
// by its signal or its exit status, never taking the caller with it.
#include <doctest/doctest.h>

#include <csignal>
#include <string>

#include "shard/driver/worker_process.hpp"

using shard::driver::describe_signal;
using shard::driver::run_worker_process;
using shard::driver::WorkerCommand;
using shard::driver::WorkerDied;

namespace {

WorkerCommand shell(const std::string& script) { return {"/bin/sh", {"-c", script}}; }

}  // namespace

TEST_CASE("a worker's output is returned byte for byte") {
  std::string input = "a record with a NUL";
  input.push_back('\0');
  input += "and binary \xff\x01 bytes";
  CHECK(run_worker_process({"/bin/cat", {}}, input) == input);
}

TEST_CASE("a worker killed by a signal is reported with the signal's name") {
  CHECK(describe_signal(SIGSEGV) == "SIGSEGV (Segmentation fault)");
  try {
    run_worker_process(shell("kill -SEGV $$"), "");
    FAIL("a killed worker must throw");
  } catch (const WorkerDied& e) {
    CHECK(e.signal() == SIGSEGV);
    CHECK(std::string(e.what()).find("SIGSEGV") != std::string::npos);
  }
}

TEST_CASE("a worker's exit status other than 0 is a failure; one that never reads its input harms nothing") {
  try {
    run_worker_process(shell("exit 3"), "");
    FAIL("a worker exiting with 3 must throw");
  } catch (const WorkerDied& e) {
    CHECK(e.signal() == 0);
    CHECK(e.exit_code() == 3);
  }
  // Far more than a pipe holds, to a worker that exits at once: the write fails with EPIPE, the
  // SIGPIPE it raises is taken back, and the worker's status is all that is reported.
  const std::string big(4 << 20, 'x');
  CHECK(run_worker_process(shell("exit 0"), big).empty());
  CHECK_THROWS_AS(run_worker_process(shell("exit 5"), big), WorkerDied);
}

TEST_CASE("a worker program that does not exist cannot be started, and says so") {
  CHECK_THROWS_WITH(run_worker_process({"/nonexistent/shard", {"run-worker"}}, ""),
                    doctest::Contains("cannot start the worker process /nonexistent/shard"));
}
