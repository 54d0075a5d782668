#include "shard/driver/run_report.hpp"

#include <fmt/format.h>

#include <fstream>

#include "shard/output.hpp"

namespace shard::driver {

void RunReport::on_finish(RunState& run) {
  const RunResult& r = run.result;
  out_(fmt::format("done: {} ({}); {} steps, t = {:.4g} s, {} bonds broken, {:.1f} s wall", r.output.string(),
                   r.stop_reason, r.steps, r.time, r.bonds_broken, r.wall_seconds));
  if (!run.sensor.empty())
    out_(fmt::format("peak load {:.5g} N at displacement {:.5g} m; kinetic/elastic energy before breakage <= {:.3g}",
                     r.peak_load, r.displacement_at_peak, r.max_kinetic_to_elastic));
}

void CurveCsvWriter::on_finish(RunState& run) {
  if (run.sensor.empty()) return;
  const RunResult& r = run.result;
  const auto csv = r.output.parent_path() / (r.output.stem().string() + "_curve.csv");
  std::ofstream out(csv);
  out << "time_s,displacement_m,force_N\n";
  for (std::size_t k = 0; k < r.curve.size(); ++k)
    out << fmt::format("{:.9g},{:.9g},{:.9g}\n", r.curve.time[k], r.curve.displacement[k], r.curve.force[k]);
  out.close();
  if (!out)
    throw OutputError(fmt::format("cannot write the load curve '{}' (disk full or folder not writable); the run "
                                  "file {} is complete",
                                  csv.string(), r.output.string()));
  if (out_) out_(fmt::format("load curve: {}", csv.string()));
}

}  // namespace shard::driver
