// `shard history`: every model version `shard compare` and `shard calibrate-effect` recorded in
// <work>/history.jsonl, as a table (effects, parameters, errors per regime) and a plot of the
// error falling as effects are added.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <fstream>
#include <memory>
#include <set>

#include "measure_commands.hpp"
#include "model_history.hpp"
#include "shard/app/commands.hpp"
#include "shard/measure/report.hpp"

namespace shard {

void add_history_command(CLI::App& app, CommandContext& ctx) {
  struct Options {
    std::filesystem::path work = "shard_work", plot;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("history", "model versions with their effects, parameters and errors; plot of the error");
  cmd->add_option("--work", o->work, "work folder holding history.jsonl");
  cmd->add_option("--plot", o->plot, "image to write (default <work>/history.png)");
  cmd->callback([o, &ctx] {
    const auto h = read_history(o->work);
    std::set<std::string> regimes;
    for (const auto& e : h)
      for (const auto& [k, v] : e.regimes) regimes.insert(k);
    std::string md = "| version | command | label | effects | parameters | NRMSE | chi^2 |";
    for (const auto& r : regimes) md += fmt::format(" {} |", r);
    md += "\n|---|---|---|---|---|---|---|";
    for (std::size_t i = 0; i < regimes.size(); ++i) md += "---|";
    md += "\n";
    for (std::size_t v = 0; v < h.size(); ++v) {
      std::string effects, params;
      for (const auto& e : h[v].effects) effects += (effects.empty() ? "" : ", ") + e;
      for (const auto& [k, x] : h[v].parameters) params += fmt::format("{}{}={:.4g}", params.empty() ? "" : ", ", k, x);
      md += fmt::format("| {} | {} | {} | {} | {} | {:.1f} % | {:.1f} |", v + 1, h[v].command, h[v].label,
                        effects.empty() ? "-" : effects, params.empty() ? "-" : params, 100 * h[v].nrmse, h[v].chi_square);
      for (const auto& r : regimes) {
        const auto it = h[v].regimes.find(r);
        md += it == h[v].regimes.end() ? std::string(" - |") : fmt::format(" {:+.1f} |", it->second);
      }
      md += "\n";
    }
    fmt::print("{}(regime columns: mean standardised residual, |r| > 2 is beyond noise)\n", md);
    const auto image = o->plot.empty() ? o->work / "history.png" : o->plot;
    const auto dat = std::filesystem::path(image).replace_extension(".dat");
    {
      std::ofstream out(dat);
      for (std::size_t v = 0; v < h.size(); ++v)
        out << fmt::format("{} {:.6g} \"{}\"\n", v + 1, 100 * h[v].nrmse, h[v].label);
    }
    const auto gp = std::filesystem::path(image).replace_extension(".gp");
    std::ofstream(gp) << fmt::format(
        "set terminal pngcairo size 800,500\nset output '{}'\nset title 'model history'\nset xlabel 'model version'\n"
        "set ylabel 'NRMSE of the force [%]'\nset yrange [0:*]\nset xtics 1\nset grid\nset key off\n"
        "plot '{}' using 1:2 with linespoints lw 2 pt 7, '' using 1:2:3 with labels offset 0,1 font ',9'\n",
        image.string(), dat.string());
    if (measure::run_program("gnuplot", {gp.string()}) != 0) throw std::runtime_error("gnuplot failed on " + gp.string());
    fmt::print("plot: {}\n", image.string());
    ctx.exit_code = 0;
  });
}

}  // namespace shard
