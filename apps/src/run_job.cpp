#include "run_job.hpp"

#include <unistd.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "byte_record.hpp"
#include "shard/app/run_command.hpp"
#include "shard/bending/bending_run.hpp"
#include "shard/driver/scene_rules.hpp"
#include "shard/driver/run_driver.hpp"
#include "shard/plugin_host.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;

// Record kinds and their layout version (the last letter): a worker of another build is refused,
// not misread; so is a run cache entry of another layout (run_cache.hpp).
constexpr std::uint32_t kJobRecord = 0x314a4853;      // "SHJ1"
constexpr std::uint32_t kOutcomeRecord = 0x32524853;  // "SHR2"

void check_kind(ByteReader& in, std::uint32_t kind, const char* what) {
  if (in.number<std::uint32_t>() != kind)
    throw std::runtime_error(fmt::format("{}: not a record of this build of shard (run the same shard on every rank "
                                         "and as the worker)",
                                         what));
}

void write_value(ByteWriter& out, const SceneOverride::Value& value) {
  out.number<std::uint8_t>(static_cast<std::uint8_t>(value.index()));
  std::visit(
      [&out](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, bool>) out.number<std::uint8_t>(v ? 1 : 0);
        else if constexpr (std::is_same_v<T, std::int64_t> || std::is_same_v<T, double>) out.number(v);
        else if constexpr (std::is_same_v<T, std::string>) out.text(v);
        else if constexpr (std::is_same_v<T, Vec3>) out.numbers({v.x(), v.y(), v.z()});
        else if constexpr (std::is_same_v<T, std::vector<double>>) out.numbers(v);
        else {
          out.number<std::uint64_t>(v.size());
          for (const auto& s : v) out.text(s);
        }
      },
      value);
}

SceneOverride::Value read_value(ByteReader& in) {
  switch (in.number<std::uint8_t>()) {
    case 0: return in.number<std::uint8_t>() != 0;
    case 1: return in.number<std::int64_t>();
    case 2: return in.number<double>();
    case 3: return in.text();
    case 4: {
      const auto v = in.numbers();
      if (v.size() != 3) break;
      return Vec3(v[0], v[1], v[2]);
    }
    case 5: return in.numbers();
    case 6: {
      std::vector<std::string> words(in.number<std::uint64_t>());
      for (auto& w : words) w = in.text();
      return words;
    }
    default: break;
  }
  throw std::runtime_error("run job record: a scene override of unknown type");
}

// Whatever standard input holds, as bytes.
std::string read_standard_input() {
  std::string bytes;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(STDIN_FILENO, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error("run-worker: cannot read the job from standard input");
    if (n == 0) return bytes;
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
}

void write_fd(int fd, const std::string& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error("run-worker: cannot write the run's outcome to standard output");
    done += static_cast<std::size_t>(n);
  }
}

RunOutcome run_here(const RunJob& job, const std::vector<fs::path>& extra_plugin_dirs) {
  PluginHost host;
  std::vector<fs::path> dirs = job.plugin_dirs;
  dirs.insert(dirs.end(), extra_plugin_dirs.begin(), extra_plugin_dirs.end());
  std::ostringstream quiet;
  load_plugins(host, dirs, quiet);
  return execute_run_job(job, host);
}

}  // namespace

RunOutcome execute_run_job(const RunJob& job, const PluginHost& host) {
  driver::RunSpec spec;
  spec.scene = job.scene;
  spec.overrides = job.overrides;
  spec.out_dir = job.out_dir;
  spec.threads = 1;
  std::error_code ignored;
  fs::remove_all(spec.out_dir, ignored);  // a killed earlier attempt's leftovers
  driver::SceneRules scene_rules;
  const driver::RunResult r = driver::run(spec, host, scene_rules.observers());
  RunOutcome out;
  out.curve = r.curve;
  out.kinetic_to_elastic = r.max_kinetic_to_elastic;
  out.wall_seconds = r.wall_seconds;
  try {
    const bending::BendingReport report = bending::analyse_bending_run(r.output);
    if (report.crack.found) out.crack_position = report.crack.position;
    out.fragment_sizes = report.fragments.sizes;
  } catch (const std::exception&) {
    // not a four-point bending run: the curve is all there is
  }
  fs::remove_all(spec.out_dir, ignored);  // the curve and the fracture are all the loop uses
  return out;
}

RunOutcome execute_run_job_isolated(const RunJob& job, const driver::WorkerCommand& worker) {
  RunOutcome out = decode_outcome(driver::run_worker_process(worker, encode_job(job)));
  if (!out.failure.empty()) throw std::runtime_error(out.failure);
  return out;
}

driver::WorkerCommand shard_run_worker() { return {fs::read_symlink("/proc/self/exe"), {"run-worker"}}; }

int serve_run_job(const std::vector<fs::path>& extra_plugin_dirs) {
  // Standard output carries the record alone: the run's own lines go to standard error.
  std::cout.flush();
  const int record_fd = ::dup(STDOUT_FILENO);
  if (record_fd < 0 || ::dup2(STDERR_FILENO, STDOUT_FILENO) < 0)
    throw std::runtime_error("run-worker: cannot set standard output aside for the outcome");
  RunOutcome outcome;
  try {
    outcome = run_here(decode_job(read_standard_input()), extra_plugin_dirs);
  } catch (const std::exception& e) {
    outcome = RunOutcome{};
    outcome.failure = e.what();
    if (outcome.failure.empty()) outcome.failure = "the run failed without a message";
  }
  write_fd(record_fd, encode_outcome(outcome));
  ::close(record_fd);
  return 0;
}

std::string run_encoded_job(std::string_view job_record) {
  RunOutcome outcome;
  try {
    const RunJob job = decode_job(job_record);
    outcome = job.isolated ? execute_run_job_isolated(job, shard_run_worker()) : run_here(job, {});
  } catch (const std::exception& e) {
    outcome = RunOutcome{};
    outcome.failure = e.what();
    if (outcome.failure.empty()) outcome.failure = "the run failed without a message";
  }
  return encode_outcome(outcome);
}

std::string encode_job(const RunJob& job) {
  ByteWriter out;
  out.number(kJobRecord);
  out.text(job.key);
  out.text(job.scene.string());
  out.number<std::uint64_t>(job.overrides.size());
  for (const auto& o : job.overrides) {
    out.text(o.key);
    write_value(out, o.value);
  }
  out.text(job.out_dir.string());
  out.number<std::uint64_t>(job.plugin_dirs.size());
  for (const auto& d : job.plugin_dirs) out.text(d.string());
  out.number<std::uint8_t>(job.isolated ? 1 : 0);
  return out.bytes();
}

RunJob decode_job(std::string_view record) {
  ByteReader in(record, "run job record");
  check_kind(in, kJobRecord, "run job record");
  RunJob job;
  job.key = in.text();
  job.scene = in.text();
  const auto overrides = in.number<std::uint64_t>();
  for (std::uint64_t k = 0; k < overrides; ++k) {
    std::string key = in.text();
    job.overrides.emplace_back(std::move(key), read_value(in));
  }
  job.out_dir = in.text();
  const auto dirs = in.number<std::uint64_t>();
  for (std::uint64_t k = 0; k < dirs; ++k) job.plugin_dirs.emplace_back(in.text());
  job.isolated = in.number<std::uint8_t>() != 0;
  if (!in.at_end()) throw std::runtime_error("run job record: longer than its fields (another build of shard?)");
  return job;
}

std::string encode_outcome(const RunOutcome& o) {
  ByteWriter out;
  out.number(kOutcomeRecord);
  out.text(o.failure);
  out.numbers(o.curve.time);
  out.numbers(o.curve.displacement);
  out.numbers(o.curve.force);
  out.number(o.kinetic_to_elastic);
  out.number(o.wall_seconds);
  out.number(o.crack_position.value_or(std::numeric_limits<double>::quiet_NaN()));
  out.numbers(o.fragment_sizes);
  return out.bytes();
}

RunOutcome decode_outcome(std::string_view record) {
  ByteReader in(record, "run outcome record");
  check_kind(in, kOutcomeRecord, "run outcome record");
  RunOutcome o;
  o.failure = in.text();
  o.curve.time = in.numbers();
  o.curve.displacement = in.numbers();
  o.curve.force = in.numbers();
  o.kinetic_to_elastic = in.number<double>();
  o.wall_seconds = in.number<double>();
  if (const double crack = in.number<double>(); !std::isnan(crack)) o.crack_position = crack;
  o.fragment_sizes = in.numbers();
  if (!in.at_end()) throw std::runtime_error("run outcome record: longer than its fields (another build of shard?)");
  if (o.curve.displacement.size() != o.curve.time.size() || o.curve.force.size() != o.curve.time.size())
    throw std::runtime_error("run outcome record: the curve's columns differ in length");
  // A simulated curve carries no measurement noise; the measurement workflow reads every curve
  // with its uncertainties (shard/measure/curve.hpp).
  o.curve.u_displacement.assign(o.curve.size(), 0.0);
  o.curve.u_force.assign(o.curve.size(), 0.0);
  return o;
}

}  // namespace shard
