#include "shard/app/fragments_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "shard/analysis/body_statistics.hpp"
#include "shard/analysis/fragment_table.hpp"
#include "shard/analysis/fsd_plot.hpp"
#include "shard/analysis/lineage.hpp"
#include "shard/analysis/process_report.hpp"
#include "shard/analysis/run_tables.hpp"
#include "shard/analysis/size_distribution.hpp"
#include "shard/run_file.hpp"

namespace shard {

using namespace analysis;

namespace {

void print_table(const std::vector<Fragment>& fragments, std::size_t rows, std::ostream& out) {
  out << fmt::format("{:>8} {:>9} {:>12} {:>11} {:>11} {:>11} {:>11} {:>5}\n", "fragment",
                     "particles", "mass[kg]", "d_eq[mm]", "x[m]", "y[m]", "z[m]", "body");
  const std::size_t shown = std::min(rows, fragments.size());
  for (std::size_t k = 0; k < shown; ++k) {
    const Fragment& f = fragments[k];
    out << fmt::format("{:>8} {:>9} {:>12.5g} {:>11.5g} {:>11.4g} {:>11.4g} {:>11.4g} {:>5}{}\n",
                       f.label, f.particles, f.mass, f.d_eq * 1e3, f.centre.x(), f.centre.y(),
                       f.centre.z(), f.body, f.mixed_bodies ? "*" : "");
  }
  if (shown < fragments.size()) {
    out << fmt::format("{:>8} ... {} more fragments (all in --csv)\n", "", fragments.size() - shown);
  }
}

void print_distribution(const SizeDistribution& fsd, std::ostream& out) {
  out << fmt::format("fragments {}  total mass {:.6g} kg\n", fsd.fragments, fsd.total_mass);
  out << fmt::format("x10 {:.5g} mm  x50 {:.5g} mm  x90 {:.5g} mm  (mass-weighted, d_eq)\n",
                     fsd.x10 * 1e3, fsd.x50 * 1e3, fsd.x90 * 1e3);
  if (fsd.fines_size > 0) {
    out << fmt::format("fines below {:.5g} mm: {:.6g} kg ({:.3g} % of the mass)\n",
                       fsd.fines_size * 1e3, fsd.fines_mass, 100.0 * fsd.fines_fraction());
  }
}

void write_csv(const std::vector<Fragment>& fragments, const std::filesystem::path& path) {
  std::ofstream csv(path);
  if (!csv) throw std::runtime_error("cannot write " + path.string());
  csv << "fragment,particles,mass_kg,volume_m3,d_eq_m,cx_m,cy_m,cz_m,vx_m_s,vy_m_s,vz_m_s,"
         "min_x_m,min_y_m,min_z_m,max_x_m,max_y_m,max_z_m,body,mixed_bodies,smallest_id\n";
  for (const Fragment& f : fragments) {
    csv << fmt::format("{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},"
                       "{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{},{},{}\n",
                       f.label, f.particles, f.mass, f.volume, f.d_eq, f.centre.x(), f.centre.y(),
                       f.centre.z(), f.velocity.x(), f.velocity.y(), f.velocity.z(), f.box_min.x(),
                       f.box_min.y(), f.box_min.z(), f.box_max.x(), f.box_max.y(), f.box_max.z(),
                       f.body, f.mixed_bodies ? 1 : 0, f.smallest_id);
  }
  if (!csv) throw std::runtime_error("cannot write " + path.string());
}

void print_bodies(const BodyReport& report, std::size_t rows, std::ostream& out) {
  out << fmt::format("per body (broken: largest fragment < {:g} of the body's mass):\n", report.intact_fraction);
  out << fmt::format("{:>6} {:>9} {:>12} {:>9} {:>8} {:>6} {:>9} {:>9} {:>9} {:>11} {:>10} {:>9}\n", "body",
                     "particles", "mass[kg]", "fragments", "largest", "broken", "x10[mm]", "x50[mm]", "x90[mm]",
                     "fines[kg]", "v_imp[m/s]", "angle[deg]");
  const std::size_t shown = std::min(rows, report.bodies.size());
  for (std::size_t k = 0; k < shown; ++k) {
    const BodyStatistics& b = report.bodies[k];
    const std::string speed = b.impacted ? fmt::format("{:.4g}", b.impact_speed) : "-";
    const std::string angle = b.impacted ? fmt::format("{:.3g}", b.impact_angle) : "-";
    out << fmt::format("{:>6} {:>9} {:>12.5g} {:>9} {:>8.4f} {:>6} {:>9.4g} {:>9.4g} {:>9.4g} {:>11.4g} {:>10} {:>9}\n",
                       b.body, b.particles, b.mass, b.fragments, b.largest_fraction, b.broken ? "yes" : "no",
                       b.fsd.x10 * 1e3, b.fsd.x50 * 1e3, b.fsd.x90 * 1e3, b.fsd.fines_mass, speed, angle);
  }
  if (shown < report.bodies.size())
    out << fmt::format("{:>6} ... {} more bodies (all in --body-csv)\n", "", report.bodies.size() - shown);
  out << fmt::format("bodies {}  broken {}  breakage probability {:.4g}\n", report.bodies.size(), report.broken,
                     report.breakage_probability);
  out << fmt::format("pooled: x10 {:.5g} mm  x50 {:.5g} mm  x90 {:.5g} mm  (mass-weighted d_eq of all fragments)\n",
                     report.pooled.x10 * 1e3, report.pooled.x50 * 1e3, report.pooled.x90 * 1e3);
}

void write_body_csv(const BodyReport& report, const std::filesystem::path& path) {
  std::ofstream csv(path);
  if (!csv) throw std::runtime_error("cannot write " + path.string());
  csv << "body,particles,mass_kg,fragments,largest_fraction,broken,x10_m,x50_m,x90_m,fines_size_m,fines_mass_kg,"
         "impacted,impact_time_s,impact_speed_m_s,impact_angle_deg,impact_wall\n";
  for (const BodyStatistics& b : report.bodies) {
    csv << fmt::format("{},{},{:.17g},{},{:.17g},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{},{:.17g},{:.17g},{:.17g},{}\n",
                       b.body, b.particles, b.mass, b.fragments, b.largest_fraction, b.broken ? 1 : 0, b.fsd.x10,
                       b.fsd.x50, b.fsd.x90, b.fsd.fines_size, b.fsd.fines_mass, b.impacted ? 1 : 0, b.impact_time,
                       b.impact_speed, b.impact_angle, b.impact_wall);
  }
  if (!csv) throw std::runtime_error("cannot write " + path.string());
}

// Bounded output: the first `rows` fragments of the earlier frame, at most 8 pieces each.
void print_lineage(std::int64_t from, std::int64_t to, const Lineage& l, std::size_t rows,
                   std::ostream& out) {
  constexpr std::size_t kPiecesShown = 8;
  std::size_t split = 0;
  for (const auto& c : l.children) split += c.size() > 1 ? 1 : 0;
  out << fmt::format("lineage frame {} -> frame {} (by shared particle ids): {} fragments became {}, "
                     "{} of them broke\n",
                     from, to, l.children.size(), l.parent.size(), split);
  std::vector<std::vector<const Overlap*>> by_parent(l.children.size());
  for (const Overlap& o : l.overlaps) by_parent[static_cast<std::size_t>(o.a)].push_back(&o);
  const std::size_t shown = std::min(rows, by_parent.size());
  for (std::size_t a = 0; a < shown; ++a) {
    std::string pieces;
    for (std::size_t k = 0; k < std::min(kPiecesShown, by_parent[a].size()); ++k) {
      const Overlap& o = *by_parent[a][k];
      if (!pieces.empty()) pieces += ", ";
      pieces += fmt::format("{} ({} particles{})", o.b, o.shared,
                            l.parent[static_cast<std::size_t>(o.b)] == o.a ? "" : ", parent elsewhere");
    }
    if (by_parent[a].size() > kPiecesShown) {
      pieces += fmt::format(", ... {} more", by_parent[a].size() - kPiecesShown);
    }
    out << fmt::format("  {} -> {}\n", a, pieces.empty() ? std::string("(gone)") : pieces);
  }
  if (shown < by_parent.size()) out << fmt::format("  ... {} more fragments\n", by_parent.size() - shown);
  std::size_t orphans = 0;
  for (Index p : l.parent) orphans += p < 0 ? 1 : 0;
  if (orphans > 0) out << fmt::format("  {} fragments have no particle in frame {}\n", orphans, from);
}

// --frame and --since: a frame number k of /frames/<k:06d>.
std::size_t frame_number(std::int64_t k, const RunFile& file) {
  if (k < 0)
    throw std::invalid_argument(fmt::format("no frame {} in {}: frames are numbered from 0 (the last is {})", k,
                                            file.path().string(), file.frames().back()));
  return static_cast<std::size_t>(k);
}

// Options that only make sense with another one, or not together, refused before the run file is opened.
void check_option_combinations(const FragmentsOptions& options) {
  if (options.body_csv && !options.by_body)
    throw std::invalid_argument("--body-csv writes the per-body table of --by-body: add --by-body");
  if (options.report && !options.by_body)
    throw std::invalid_argument("--report is the breakage report of --by-body: add --by-body");
  if ((options.speed_bins > 0 || !options.speed_edges.empty()) && !options.report)
    throw std::invalid_argument("--speed-bins and --speed-edges bin the impact speeds of --report: add --report DIR");
  if (options.speed_bins > 0 && !options.speed_edges.empty())
    throw std::invalid_argument("give either --speed-bins or --speed-edges, not both");
  for (std::size_t e = 1; e < options.speed_edges.size(); ++e)
    if (!(options.speed_edges[e] > options.speed_edges[e - 1]))
      throw std::invalid_argument(fmt::format("--speed-edges must ascend: {} follows {}", options.speed_edges[e],
                                              options.speed_edges[e - 1]));
}

// --by-body: each body's breakage, stored in the run file and printed; with --body-csv and --report.
void report_bodies(RunFile& file, std::size_t k, const FrameData& frame, const FragmentAnalysis& analysis,
                   const FragmentsOptions& options, std::ostream& out) {
  BodyReport report =
      body_statistics(particle_sample(frame), analysis.fragments, options.intact_fraction, options.fines_size);
  attach_impacts(report, file.read_body_impacts());
  print_bodies(report, options.rows, out);
  write_body_table(file, k, report);
  out << fmt::format("wrote /bodies/{}\n", frame_name(k));
  if (options.body_csv) {
    write_body_csv(report, *options.body_csv);
    out << "wrote " << options.body_csv->string() << "\n";
  }
  if (options.report) {
    RunReportOptions ro;
    ro.dir = *options.report;
    ro.speed_bins = options.speed_bins;
    ro.speed_edges = options.speed_edges;
    ro.command = options.command_line;
    write_run_breakage_report(file, {static_cast<std::int64_t>(k), frame.time, analysis.fragments, report},
                              options.intact_fraction, ro, out);
  }
}

}  // namespace

int fragments_command(const FragmentsOptions& options, std::ostream& out, std::ostream& err) {
  try {
    check_option_combinations(options);
    const bool writes = options.write_labels || options.by_body;
    RunFile file(options.run_file, writes ? RunFile::Mode::read_write : RunFile::Mode::read);
    const std::vector<std::size_t>& frames = file.frames();
    if (frames.empty()) throw std::runtime_error(options.run_file.string() + " holds no frame yet");
    const std::size_t k = frame_number(options.frame.value_or(static_cast<std::int64_t>(frames.back())), file);
    const FrameData frame = file.read_frame(k, options.density);
    const FragmentAnalysis analysis = analyse_fragments(particle_sample(frame), bond_list(frame));
    const SizeDistribution fsd = size_distribution(analysis.fragments, options.fines_size);

    out << fmt::format("{}: frame {} (step {}, t = {:.6g} s), {} particles, {} bonds\n",
                       options.run_file.string(), k, frame.step, frame.time, frame.id.size(),
                       frame.bond_i.size());
    out << "masses: " << frame.mass_source << "\n";
    print_table(analysis.fragments, options.rows, out);
    print_distribution(fsd, out);

    if (options.since) {
      const FrameData earlier = file.read_frame(frame_number(*options.since, file), options.density);
      const FragmentAnalysis before = analyse_fragments(particle_sample(earlier), bond_list(earlier));
      const Lineage l = lineage({earlier.id, before.labels, static_cast<Index>(before.fragments.size())},
                                {frame.id, analysis.labels, static_cast<Index>(analysis.fragments.size())});
      print_lineage(*options.since, static_cast<std::int64_t>(k), l, options.rows, out);
    }
    if (options.csv) {
      write_csv(analysis.fragments, *options.csv);
      out << "wrote " << options.csv->string() << "\n";
    }
    if (options.write_labels) {
      file.write_fragment_labels(k, analysis.labels);
      write_fragment_table(file, k, analysis.fragments, fsd);
      out << fmt::format("wrote /frames/{0}/fragment and /fragments/{0}\n", frame_name(k));
    }
    if (options.by_body) report_bodies(file, k, frame, analysis, options, out);
    if (options.plot) {
      plot_size_distribution(fsd, *options.plot,
                             fmt::format("{} frame {}", options.run_file.filename().string(), k));
      out << "wrote " << options.plot->string() << "\n";
    }
    return 0;
  } catch (const std::exception& e) {
    // One line naming the run file, as every shard error (docs/reference/errors.md).
    const std::string what = e.what();
    const std::string file = options.run_file.string();
    err << "shard: error: " << (what.find(file) == std::string::npos ? file + ": " : "") << what << "\n";
    return 1;
  }
}

}  // namespace shard
