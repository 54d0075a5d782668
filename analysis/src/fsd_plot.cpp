#include "shard/analysis/fsd_plot.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

extern char** environ;  // POSIX: the process environment, handed to gnuplot unchanged

namespace shard::analysis {

std::optional<std::filesystem::path> find_program(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return std::nullopt;
  std::stringstream folders(path);
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    if (folder.empty()) continue;
    const std::filesystem::path candidate = std::filesystem::path(folder) / name;
    if (::access(candidate.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(candidate)) {
      return candidate;
    }
  }
  return std::nullopt;
}

int run_program(const std::filesystem::path& program, const std::vector<std::string>& args) {
  std::vector<std::string> storage;
  storage.push_back(program.string());
  storage.insert(storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int started = ::posix_spawn(&pid, program.c_str(), nullptr, nullptr, argv.data(), environ);
  if (started != 0) {
    throw PlotError("cannot start " + program.string() + ": " + std::strerror(started));
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw PlotError("lost track of " + program.string());
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

std::string gnuplot_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') {
      out += "''";
    } else if (c == '\n' || c == '\r') {
      out += ' ';  // a newline would end the gnuplot command
    } else {
      out += c;
    }
  }
  return out + "'";
}

std::filesystem::path write_fsd_plot_script(const SizeDistribution& fsd,
                                            const std::filesystem::path& image,
                                            const std::string& title) {
  const std::string extension = image.extension().string();
  std::string terminal;
  if (extension == ".png") {
    terminal = "pngcairo size 900,600 enhanced font 'Sans,11'";
  } else if (extension == ".svg") {
    terminal = "svg size 900,600 enhanced font 'Sans,11'";
  } else {
    throw PlotError("plot file must end in .png or .svg: " + image.string());
  }
  if (fsd.points.empty()) throw PlotError("no fragment to plot");
  std::filesystem::path data = image;
  data += ".dat";
  std::filesystem::path script = image;
  script += ".gp";
  {
    std::ofstream out(data);
    if (!out) throw PlotError("cannot write " + data.string());
    out << "# d_eq[mm] Q[%]  (mass-weighted cumulative fragment size distribution)\n";
    // The first size carries Q_1 of the mass: draw the rise from 0 at d_1.
    out << fmt::format("{:.9g} {:.9g}\n", fsd.points.front().d * 1e3, 0.0);
    for (const DistributionPoint& p : fsd.points) {
      out << fmt::format("{:.9g} {:.9g}\n", p.d * 1e3, p.cumulative * 100.0);
    }
  }
  const double d_min = fsd.points.front().d * 1e3, d_max = fsd.points.back().d * 1e3;
  const bool log_axis = d_min > 0 && d_max / d_min > 10.0;
  std::ofstream out(script);
  if (!out) throw PlotError("cannot write " + script.string());
  out << "set terminal " << terminal << "\n";
  out << "set output " << gnuplot_quote(image.string()) << "\n";
  out << "set title " << gnuplot_quote(title) << " noenhanced\n";
  out << "set xlabel 'equivalent diameter d_{eq} [mm]'\n";
  out << "set ylabel 'cumulative mass Q(d_{eq}) [%]'\n";
  out << "set yrange [0:100]\nset grid\nset key bottom right\n";
  if (log_axis) out << "set logscale x\n";
  // A margin of 20 % around the sizes keeps the x10 label off the frame (and gives one-size
  // distributions a non-empty range).
  out << fmt::format("set xrange [{:.9g}:{:.9g}]\n", d_min / 1.2, d_max * 1.2);
  struct Mark {
    const char* name;
    double x;
  };
  for (const Mark m : {Mark{"x_{10}", fsd.x10}, Mark{"x_{50}", fsd.x50}, Mark{"x_{90}", fsd.x90}}) {
    out << fmt::format("set arrow from {0:.9g}, graph 0 to {0:.9g}, graph 1 nohead dt 2 lc rgb 'gray40'\n",
                       m.x * 1e3);
    out << fmt::format("set label '{} = {:.4g} mm' at {:.9g}, graph 0.04 rotate by 90 offset -0.6,0\n", m.name,
                       m.x * 1e3, m.x * 1e3);
  }
  out << fmt::format("plot {} using 1:2 with linespoints lw 2 pt 7 ps 0.6 title '{} fragments'\n",
                     gnuplot_quote(data.string()), fsd.fragments);
  if (!out) throw PlotError("cannot write " + script.string());
  return script;
}

void plot_size_distribution(const SizeDistribution& fsd, const std::filesystem::path& image,
                            const std::string& title) {
  const auto gnuplot = find_program("gnuplot");
  if (!gnuplot) {
    throw PlotError("gnuplot is not installed (on Debian: apt-get install gnuplot-nox); "
                    "the distribution is still printed and written to --csv");
  }
  const std::filesystem::path script = write_fsd_plot_script(fsd, image, title);
  const int status = run_program(*gnuplot, {script.string()});
  if (status != 0) {
    throw PlotError("gnuplot failed (exit status " + std::to_string(status) + ") on " + script.string());
  }
  if (!std::filesystem::exists(image)) throw PlotError("gnuplot wrote no " + image.string());
}

}  // namespace shard::analysis
