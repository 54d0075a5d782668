#include "shard/bending/bending_plot.hpp"

#include <fmt/format.h>

#include <fstream>

#include "shard/analysis/fsd_plot.hpp"
#include "shard/bending/beam_theory.hpp"

namespace shard::bending {

std::filesystem::path write_bending_plot_script(const analysis::LoadCurve& curve, const CurveAnalysis& a,
                                                const std::filesystem::path& image, const std::string& title) {
  using analysis::PlotError;
  std::string terminal;
  if (image.extension() == ".png")
    terminal = "pngcairo size 900,600 enhanced font 'Sans,11'";
  else if (image.extension() == ".svg")
    terminal = "svg size 900,600 enhanced font 'Sans,11'";
  else
    throw PlotError("plot file must end in .png or .svg: " + image.string());
  if (curve.force.empty()) throw PlotError("no load curve to plot");
  auto data = image;
  data += ".dat";
  auto script = image;
  script += ".gp";
  {
    std::ofstream out(data);
    if (!out) throw PlotError("cannot write " + data.string());
    out << "# w_s from the contact onset (mm), F (N)\n";
    for (std::size_t k = 0; k < curve.force.size(); ++k)
      out << fmt::format("{:.9g} {:.9g}\n", 1e3 * (curve.displacement[k] - a.onset), curve.force[k]);
  }
  std::ofstream gp(script);
  if (!gp) throw PlotError("cannot write " + script.string());
  const std::string label = fmt::format(
      "F_{{max}} = {:.4g} N\\nw_{{s,max}} = {:.3f} mm\\nE (eq. 14) = {:.4g} MPa\\n{{/Symbol s}}_b (eq. 15) = {:.4g} MPa\\n"
      "k = {:.4g} N/mm ({:.0f}-{:.0f} % F_{{max}})",
      a.force_max, 1e3 * a.deflection_at_peak, 1e-6 * a.youngs_modulus, 1e-6 * a.flexural_strength, 1e-3 * a.stiffness,
      100 * a.fit_low, 100 * a.fit_high);
  gp << "set terminal " << terminal << "\n";
  gp << "set output " << analysis::gnuplot_quote(image.string()) << "\n";
  gp << "set title " << analysis::gnuplot_quote(title) << " noenhanced\n";
  gp << "set xlabel 'pin deflection w_s from contact onset (mm)'\nset ylabel 'force F on the pins (N)'\n";
  gp << "set grid\nset key bottom right\nset yrange [0:*]\n";
  gp << "set label 1 \"" << label << "\" at graph 0.03, graph 0.95 left front\n";
  gp << fmt::format("k = {:.9g}\n", 1e-3 * a.stiffness);  // N/mm
  gp << fmt::format("set arrow 1 from {:.9g},0 to {:.9g},{:.9g} nohead dt 3 lc rgb 'gray40'\n", 1e3 * a.deflection_at_peak,
                    1e3 * a.deflection_at_peak, a.force_max);
  gp << "plot " << analysis::gnuplot_quote(data.string()) << " using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'simulation', \\\n"
     << fmt::format("  (x >= 0 && k * x <= {:.9g} ? k * x : 1/0) with lines dt 2 lw 1.5 lc rgb '#d62728' title 'initial stiffness', \\\n",
                    1.1 * a.force_max)
     << "  '-' using 1:2 with points pt 7 ps 1.5 lc rgb '#2ca02c' title 'F_{max}'\n"
     << fmt::format("{:.9g} {:.9g}\ne\n", 1e3 * a.deflection_at_peak, a.force_max);
  return script;
}

void plot_bending_curve(const analysis::LoadCurve& curve, const CurveAnalysis& a, const std::filesystem::path& image,
                        const std::string& title) {
  const auto script = write_bending_plot_script(curve, a, image, title);
  const auto gnuplot = analysis::find_program("gnuplot");
  if (!gnuplot) throw analysis::PlotError("gnuplot is not installed (Debian: apt-get install gnuplot-nox)");
  if (int status = analysis::run_program(*gnuplot, {script.string()}); status != 0)
    throw analysis::PlotError(fmt::format("gnuplot failed on {} (status {})", script.string(), status));
}

}  // namespace shard::bending
