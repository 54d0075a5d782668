#include "shard/measure/report.hpp"

#include <fmt/format.h>
#include <fmt/os.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <algorithm>
#include <cmath>
#include <stdexcept>

extern char** environ;  // POSIX: the child gets this process's environment

namespace shard::measure {
std::string comparison_markdown(const Comparison& c) {
  std::string md = fmt::format("**Verdict.** {}\n\n", c.verdict);
  md += fmt::format("Reference displacement w_ref = {:.4g} m, measured F_max (mean curve) = {:.4g} N, NRMSE = {:.2f} %.\n\n",
                    c.reference_displacement, c.measured_peak_force, 100 * c.nrmse);
  md += "| feature | unit | measured | u | simulated | u | error | rel. error | score (sigma) | beyond noise |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& f : c.features)
    md += fmt::format("| {} | {} | {:.4g} | {:.2g} | {:.4g} | {:.2g} | {:+.3g} | {:+.1f} % | {} | {} |\n",
                      feature_name(f.feature), feature_unit(f.feature), f.measured, f.u_measured, f.simulated,
                      f.u_simulated, f.error, 100 * f.relative_error,
                      std::isfinite(f.score) ? fmt::format("{:+.2f}", f.score) : "n/a",
                      !f.judged ? "not judged" : f.beyond_noise ? "**yes**" : "no");
  md += "\n| regime | xi range | points | mean residual (sigma) | RMS residual | force error | beyond noise |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const auto& g : c.regimes) {
    if (g.points() == 0) {
      md += fmt::format("| {} | - | 0 | - | - | - | - |\n", regime_name(g.regime));
      continue;
    }
    md += fmt::format("| {} | {:.2f}-{:.2f} | {} | {:+.2f} | {:.2f} | {:+.1f} % | {} |\n", regime_name(g.regime),
                      c.xi[g.first], c.xi[g.last - 1], g.points(), g.mean_residual, g.rms_residual,
                      100 * g.relative_error, g.beyond_noise ? "**yes**" : "no");
  }
  return md;
}

io::Json comparison_json(const Comparison& c) {
  io::Json j;
  j["verdict"] = c.verdict;
  j["adequate"] = c.adequate;
  j["nrmse"] = c.nrmse;
  j["reference_displacement"] = c.reference_displacement;
  j["measured_peak_force"] = c.measured_peak_force;
  j["features"] = io::Json::array();
  for (const auto& f : c.features)
    j["features"].push_back({{"name", std::string(feature_name(f.feature))},
                             {"unit", std::string(feature_unit(f.feature))}, {"measured", f.measured},
                             {"u_measured", f.u_measured}, {"simulated", f.simulated}, {"u_simulated", f.u_simulated},
                             {"error", f.error}, {"relative_error", f.relative_error}, {"score", f.score},
                             {"beyond_noise", f.beyond_noise}, {"judged", f.judged}});
  j["regimes"] = io::Json::array();
  for (const auto& g : c.regimes) {
    const bool any = g.points() > 0;
    j["regimes"].push_back({{"name", std::string(regime_name(g.regime))},
                            {"xi_first", any ? io::Json(c.xi[g.first]) : io::Json()},
                            {"xi_last", any ? io::Json(c.xi[g.last - 1]) : io::Json()}, {"points", g.points()},
                            {"mean_residual", g.mean_residual}, {"rms_residual", g.rms_residual},
                            {"chi_square", g.chi_square}, {"relative_error", g.relative_error},
                            {"beyond_noise", g.beyond_noise}});
  }
  return j;
}

int run_program(const std::string& program, const std::vector<std::string>& args) {
  std::vector<std::string> all{program};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (::posix_spawnp(&pid, program.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void plot_comparison(const Comparison& c, const std::filesystem::path& image, const std::string& title) {
  const auto data = std::filesystem::path(image).replace_extension(".dat");
  const auto script = std::filesystem::path(image).replace_extension(".gp");
  {
    auto out = fmt::output_file(data.string());
    out.print("# w_mm measured_mean u_measured simulated_mean u_simulated residual measured_1.. simulated_1..\n");
    for (std::size_t k = 0; k < c.xi.size(); ++k) {
      out.print("{:.6g} {:.6g} {:.6g} {:.6g} {:.6g} {:.6g}", 1e3 * c.xi[k] * c.reference_displacement,
                c.measured.mean[k], c.measured.u[k], c.simulated.mean[k], c.simulated.u[k], c.residual[k]);
      for (const auto& m : c.measured_curves) out.print(" {:.6g}", m[k]);
      for (const auto& s : c.simulated_curves) out.print(" {:.6g}", s[k]);
      out.print("\n");
    }
  }
  const bool svg = image.extension() == ".svg";
  const std::size_t nm = c.measured_curves.size(), ns = c.simulated_curves.size();
  auto out = fmt::output_file(script.string());
  out.print("set terminal {} size 900,800\nset output '{}'\n", svg ? "svg" : "pngcairo", image.string());
  out.print("set multiplot title '{}' noenhanced\n", title);
  out.print("set lmargin 12\nset xlabel 'loading-pin displacement w (mm)'\nset ylabel 'force F (N)'\n"
            "set key top left\nset grid\n");
  out.print("set size 1,0.62\nset origin 0,0.38\n");
  // Failing regimes shaded in both panels.
  int object = 1;
  for (const auto& g : c.regimes)
    if (g.beyond_noise && g.points() > 0)
      out.print("set object {} rect from {:.6g}, graph 0 to {:.6g}, graph 1 fc rgb '#f4cccc' fs solid 0.5 noborder "
                "behind\n",
                object++, 1e3 * c.xi[g.first] * c.reference_displacement,
                1e3 * c.xi[std::min(g.last, c.xi.size() - 1)] * c.reference_displacement);
  out.print("plot '{0}' u 1:($2-2*$3):($2+2*$3) w filledcurves fc rgb '#9ecae1' fs transparent solid 0.6 "
            "title 'measured mean +-2u'",
            data.string());
  for (std::size_t i = 0; i < nm; ++i)
    out.print(", '' u 1:{} w l lc rgb '#3182bd' lw 1 dt 3 {}", 7 + i, i == 0 ? "title 'measured specimens'" : "notitle");
  for (std::size_t i = 0; i < ns; ++i)
    out.print(", '' u 1:{} w l lc rgb '#fdae6b' lw 1 {}", 7 + nm + i, i == 0 ? "title 'simulated replicates'" : "notitle");
  out.print(", '' u 1:2 w l lc rgb '#08519c' lw 2 title 'measured mean', '' u 1:4 w l lc rgb '#d94801' lw 2 "
            "title 'simulated mean'\n");
  out.print("set size 1,0.38\nset origin 0,0\nset ylabel 'residual r (sigma)'\nunset title\n");
  out.print("plot '{}' u 1:6 w lp pt 7 ps 0.4 lc rgb 'black' title 'standardised residual', 2 w l dt 2 lc rgb "
            "'red' title '+-2 sigma', -2 w l dt 2 lc rgb 'red' notitle\n",
            data.string());
  out.print("unset multiplot\n");
  out.close();
  const int status = run_program("gnuplot", {script.string()});
  if (status != 0)
    throw std::runtime_error(fmt::format("gnuplot failed on {} (exit status {}); is gnuplot installed?",
                                         script.string(), status));
}

}  // namespace shard::measure
