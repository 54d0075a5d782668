#include "shard/measure/contrast_study.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <ostream>
#include <stdexcept>

#include "shard/measure/effect_library.hpp"
#include "shard/measure/group_scatter.hpp"
#include "shard/measure/rate_groups.hpp"
#include "shard/measure/statistics.hpp"
#include "paired_seeds.hpp"
#include "square_matrix.hpp"

namespace shard::measure {

namespace fs = std::filesystem;

namespace {

constexpr double kGeometryTolerance = 0.02;  // as Simulator::check_inputs: 2 % is a different fixture
constexpr double kShrinkage = 0.1;           // off-diagonal shrinkage of the pooled covariance
constexpr std::size_t kCurvePoints = 60;

std::string folder_name(const fs::path& folder) {
  const fs::path p = folder.lexically_normal();
  return (p.has_filename() ? p.filename() : p.parent_path().filename()).string();
}

std::size_t rates_spanned(const std::vector<ContrastGroup>& groups, const std::vector<std::size_t>& of) {
  std::vector<double> seen;
  auto add = [&](double v) {
    for (double x : seen)
      if (same_rate(x, v)) return;
    seen.push_back(v);
  };
  for (std::size_t gi : of) add(groups[gi].rate), add(groups[gi].reference_rate);
  return seen.size();
}

void check_geometry(const ContrastSets& s) {
  const std::size_t first = s.reference.value_or(0);
  const Specimen& ref = s.sets[first].specimens.front();
  struct Dim {
    const char* name;
    double Specimen::*field;
  };
  const Dim dims[] = {{"span", &Specimen::span}, {"pin distance", &Specimen::pin_distance},
                      {"width", &Specimen::width}, {"height", &Specimen::height}};
  for (std::size_t k = 0; k < s.sets.size(); ++k)
    for (const auto& sp : s.sets[k].specimens)
      for (const auto& d : dims)
        if (std::abs(sp.*d.field - ref.*d.field) > kGeometryTolerance * ref.*d.field)
          throw std::runtime_error(fmt::format(
              "{}/specimens.csv: specimen {} has {} {:.4g} mm, but {} specimen {} has {:.4g} mm (more than 2 % apart). "
              "A contrast holds specimen and fixture fixed so that the model's form error cancels; diagnose sets of "
              "another geometry on their own (shard diagnose SET) or with a reference of their geometry",
              s.sets[k].folder.string(), sp.id, d.name, 1e3 * (sp.*d.field), s.names[first], ref.id, 1e3 * (ref.*d.field)));
}

// The model is run and recorded as the reference's metadata says ([test]: ramp, preload); a set
// tested otherwise would differ by its test, not by its material.
void check_test_conditions(const ContrastSets& s) {
  const std::size_t first = s.reference.value_or(0);
  const TestConditions& ref = s.sets[first].metadata.test;
  for (std::size_t k = 0; k < s.sets.size(); ++k) {
    const TestConditions& t = s.sets[k].metadata.test;
    auto differ = [&](const char* key, const std::string& a, const std::string& b) {
      if (a != b)
        throw std::runtime_error(fmt::format(
            "{}/metadata.toml: [test] {} = {}, but {}'s is {}. A contrast holds the test fixed (the model is run as "
            "the reference was); diagnose sets tested another way on their own, or against a reference tested "
            "their way",
            s.sets[k].folder.string(), key, a.empty() ? "(not given)" : a, s.names[first], b.empty() ? "(not given)" : b));
    };
    differ("seating_preload", t.seating_preload > 0 ? fmt::format("{:g} N", t.seating_preload) : "",
           ref.seating_preload > 0 ? fmt::format("{:g} N", ref.seating_preload) : "");
    differ("ramp", t.has_ramp() ? fmt::format("{} over {:g} s", t.ramp, t.ramp_time) : "",
           ref.has_ramp() ? fmt::format("{} over {:g} s", ref.ramp, ref.ramp_time) : "");
  }
}

std::string rates_text(const std::vector<double>& rates) {
  std::string out;
  for (double r : rates) out += fmt::format("{}{:g} mm/s", out.empty() ? "" : ", ", 1e3 * r);
  return out;
}

// A set with no loading rate in common with the reference differs from it by its batch and by its
// rate at once, and only the model's rate response (which holds no rate effect) could part them:
// a batch difference would be named a rate effect, or the reverse.
void check_shared_rates(const ContrastSets& s) {
  if (!s.reference) return;
  const std::vector<double> ref = s.sets[*s.reference].loading_rates();
  for (std::size_t k = 0; k < s.sets.size(); ++k) {
    const std::vector<double> rates = s.sets[k].loading_rates();
    const bool shared = std::any_of(rates.begin(), rates.end(), [&](double r) {
      return std::any_of(ref.begin(), ref.end(), [&](double q) { return same_rate(r, q); });
    });
    if (!shared)
      throw std::runtime_error(fmt::format(
          "{}/specimens.csv: tested at {} only, the reference {} at {}: no loading rate in common, so this set's "
          "difference from the reference mixes the batch with the loading rate. Fix: test some of its specimens at "
          "the reference's rate (or the reference at this set's), or diagnose it on its own (shard diagnose SET)",
          s.sets[k].folder.string(), rates_text(rates), s.names[*s.reference], rates_text(ref)));
  }
}

double mean_peak_displacement(const std::vector<Curve>& curves) {
  double sum = 0;
  for (const auto& c : curves) sum += c.displacement[peak_index(c)];
  return curves.empty() ? 0 : sum / static_cast<double>(curves.size());
}

// The RMS differences of a curve contrast, over every point and over the rising branch, and the
// floor over every point.
void summarise(ContrastStudy::CurveContrast& c) {
  double sum = 0, floor = 0, rising_sum = 0;
  std::size_t rising = 0;
  for (std::size_t i = 0; i < c.xi.size(); ++i) {
    const double d2 = std::pow(c.measured[i] - c.simulated[i], 2);
    const double u2 = std::pow(c.u_measured[i], 2) + std::pow(c.u_simulated[i], 2);
    sum += d2, floor += u2;
    if (c.rising[i]) rising_sum += d2, ++rising;
  }
  auto rms = [](double s, std::size_t n) { return n == 0 ? 0.0 : std::sqrt(s / static_cast<double>(n)); };
  c.nrmse = rms(sum, c.xi.size()), c.floor = rms(floor, c.xi.size());
  c.rising_nrmse = rms(rising_sum, rising);
}

}  // namespace

void check_contrast_sets(const ContrastSets& s) {
  for (std::size_t k = 0; k < s.sets.size(); ++k) {
    const RateGroups g = rate_groups(s.sets[k], 0);
    for (std::size_t r = 0; r < g.rates.size(); ++r)
      if (g.specimens[r].size() < 2)
        throw std::runtime_error(fmt::format(
            "{}/specimens.csv: {} specimen at {:g} m/s; a contrast needs at least two specimens per set and rate (their scatter "
            "is the noise a difference is judged against). Fix: add replicates, or leave this set out",
            s.sets[k].folder.string(), g.specimens[r].size(), g.rates[r]));
  }
  check_geometry(s);
  check_test_conditions(s);
  check_shared_rates(s);
}

ContrastSets read_contrast_sets(const std::vector<fs::path>& folders, const std::string& reference) {
  if (folders.size() < 2)
    throw std::runtime_error(fmt::format("a contrast needs at least two measurement sets, got {}: give the reference "
                                         "and the sets to hold against it (shard diagnose REF SET_A ... --reference REF)",
                                         folders.size()));
  ContrastSets s;
  for (const auto& f : folders) {
    s.sets.push_back(read_measurements(f));
    s.names.push_back(folder_name(f));
    for (std::size_t k = 0; k + 1 < s.names.size(); ++k)
      if (s.names[k] == s.names.back())
        throw std::runtime_error(fmt::format("two measurement sets are named '{}' ({} and {}): rename one folder",
                                             s.names.back(), folders[k].string(), f.string()));
  }
  if (!reference.empty()) {
    for (std::size_t k = 0; k < folders.size(); ++k) {
      std::error_code ec;
      if (s.names[k] == reference || s.names[k] == folder_name(reference) || fs::equivalent(folders[k], reference, ec))
        s.reference = k;
    }
    if (!s.reference) {
      std::string names;
      for (const auto& n : s.names) names += (names.empty() ? "" : ", ") + n;
      throw std::runtime_error(fmt::format("--reference {}: not among the sets given ({}). Fix: add its folder to the "
                                           "list of sets, or name one of them",
                                           reference, names));
    }
  }
  check_contrast_sets(s);
  return s;
}

ContrastStudy::ContrastStudy(const ContrastSets& sets, Simulator& simulator, ModelPlan base, double own_scatter_p)
    : sets_(sets), simulator_(simulator), base_(std::move(base)) {
  // The scales come from the reference's slowest rate, or without a reference from the rate most
  // specimens were tested at.
  std::map<double, std::size_t> count;
  for (std::size_t k = 0; k < sets_.sets.size(); ++k)
    for (const auto& sp : sets_.sets[k].specimens)
      if (!sets_.reference || *sets_.reference == k) ++count[sp.loading_rate];
  scale_rate_ = std::max_element(count.begin(), count.end(), [](auto& a, auto& b) { return a.second < b.second; })->first;
  if (sets_.reference) scale_rate_ = count.begin()->first;
  std::vector<Curve> scale_curves;
  for (std::size_t k = 0; k < sets_.sets.size(); ++k)
    if (!sets_.reference || *sets_.reference == k)
      for (const auto& sp : sets_.sets[k].specimens)
        if (same_rate(sp.loading_rate, scale_rate_)) scale_curves.push_back(sp.curve);
  measured_scale_ = contrast_scale(scale_curves);
  band_ = stiffness_band(measured_scale_);

  std::vector<std::vector<std::vector<double>>> pooled;
  for (std::size_t k = 0; k < sets_.sets.size(); ++k) {
    const RateGroups g = rate_groups(sets_.sets[k], 0);
    const std::vector<double> reference_rates =
        sets_.reference ? sets_.sets[*sets_.reference].loading_rates() : g.rates;
    for (std::size_t r = 0; r < g.rates.size(); ++r) {
      ContrastGroup group;
      group.set = k;
      group.rate = g.rates[r];
      group.reference_rate = *std::min_element(reference_rates.begin(), reference_rates.end(), [&](double a, double b) {
        return std::abs(std::log(a / group.rate)) < std::abs(std::log(b / group.rate));
      });
      for (const auto& sp : g.specimens[r]) group.components.push_back(contrast_components(sp.curve, band_));
      pooled.push_back(group.components);
      groups_.push_back(std::move(group));
    }
  }
  scatter_ = group_scatter(pooled, kShrinkage, own_scatter_p);
}

std::vector<double> ContrastStudy::rates() const {
  std::vector<double> r;
  auto add = [&](double v) {
    for (double x : r)
      if (same_rate(x, v)) return;
    r.push_back(v);
  };
  add(scale_rate_);
  for (const auto& g : groups_) add(g.rate), add(g.reference_rate);
  std::sort(r.begin(), r.end());
  return r;
}

std::size_t ContrastStudy::rate_index(double rate) const {
  const auto r = rates();
  for (std::size_t k = 0; k < r.size(); ++k)
    if (same_rate(r[k], rate)) return k;
  throw std::logic_error("contrast: a rate that was not simulated");
}

std::vector<ContrastStudy::Simulated> ContrastStudy::simulate(const std::vector<ModelPlan>& models, std::ostream& log) {
  std::vector<Specimen> every;
  for (const auto& s : sets_.sets) every.insert(every.end(), s.specimens.begin(), s.specimens.end());
  if (!models.empty()) simulator_.check_inputs(models.front(), every, sets_.sets[sets_.reference.value_or(0)].metadata);
  const auto r = rates();
  std::vector<ModelPlan> runs;
  for (const auto& m : models)
    for (double v : r) {
      ModelPlan at = m;
      at.loading_rate = v;
      runs.push_back(std::move(at));
    }
  const auto sims = simulator_.simulate(runs, log);
  std::vector<Simulated> out(models.size());
  for (std::size_t m = 0; m < models.size(); ++m)
    for (std::size_t k = 0; k < r.size(); ++k) {
      std::vector<Curve> curves;
      for (const auto& sp : sims[m * r.size() + k]) curves.push_back(sp.curve);
      out[m].curves.push_back(std::move(curves));
    }
  for (auto& run : out) read_components(run);
  return out;
}

void ContrastStudy::read_components(Simulated& run) const {
  const auto r = rates();
  run.components.assign(r.size(), {});
  for (std::size_t k = 0; k < r.size(); ++k)
    for (const auto& c : run.curves[k]) try {
        run.components[k].push_back(contrast_components(c, band_));
      } catch (const CurveWithoutRise& e) {
        throw std::runtime_error(simulated_without_rise(e, r[k]));
      }
}

ContrastScale ContrastStudy::simulated_scale(const Simulated& base) const {
  return contrast_scale(base.curves[rate_index(scale_rate_)]);
}

const std::vector<std::vector<double>>& ContrastStudy::components(const Simulated& model, double rate) const {
  return model.components[rate_index(rate)];
}

namespace {

// What a group's mean is held against: the reference's group at its reference rate, or the
// consensus of the other sets at its rate; the covariance of that mean is weight x sigma, shared
// by every group held against the same (`key`).
struct HeldAgainst {
  std::vector<double> mean;
  double weight = 0;
  const std::vector<std::vector<double>>* sigma = nullptr;
  std::string key;
};

HeldAgainst held_against(const ContrastSets& sets, const std::vector<ContrastGroup>& groups,
                         const GroupScatter& scatter, std::size_t set, const ContrastGroup& g) {
  HeldAgainst h;
  h.sigma = &scatter.pooled;
  if (sets.reference) {
    for (std::size_t hi = 0; hi < groups.size(); ++hi) {
      const ContrastGroup& r = groups[hi];
      if (r.set == *sets.reference && same_rate(r.rate, g.reference_rate)) {
        h.mean = component_mean(r.components);
        h.weight = 1.0 / static_cast<double>(r.components.size());
        h.sigma = &scatter.covariance[hi];
      }
    }
    h.key = fmt::format("reference@{}", g.reference_rate);
    return h;
  }
  // The consensus: the median of the other sets' means at this rate. Its variance is taken as
  // the median's large-sample pi/2 times that of the pooled mean of those specimens.
  std::vector<std::vector<double>> others;
  double n_others = 0;
  for (const auto& r : groups)
    if (r.set != set && same_rate(r.rate, g.rate)) {
      others.push_back(component_mean(r.components));
      n_others += static_cast<double>(r.components.size());
    }
  if (others.size() < 2)
    throw std::runtime_error(fmt::format("{}: fewer than two other sets were tested at {:g} m/s, so there is no "
                                         "consensus to hold it against. Fix: name a reference with --reference",
                                         sets.names[set], g.rate));
  h.mean = median_of(others);
  h.weight = std::numbers::pi / 2 / n_others;
  h.key = fmt::format("consensus-without-{}@{}", set, g.rate);
  return h;
}

// One group's part of a contrast: its difference, the covariance of its own mean, of what it is
// held against (shared with the groups of the same key) and of the base's rate shift.
struct ContrastBlock {
  std::vector<double> d, var_base;
  Eigen::MatrixXd own, shared;
  std::string shared_key;
};

// The blocks' joint covariance: each block's own on the diagonal, the shared parts wherever two
// blocks are held against the same mean.
std::vector<std::vector<double>> joint_covariance(const std::vector<ContrastBlock>& blocks, std::size_t m) {
  const auto n = static_cast<Eigen::Index>(blocks.size() * m);
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(n, n);
  const auto mm = static_cast<Eigen::Index>(m);
  for (std::size_t a = 0; a < blocks.size(); ++a)
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      auto block = cov.block(static_cast<Eigen::Index>(a) * mm, static_cast<Eigen::Index>(b) * mm, mm, mm);
      if (blocks[a].shared_key == blocks[b].shared_key) block += blocks[a].shared;
      if (a == b) {
        block += blocks[a].own;
        for (std::size_t i = 0; i < m; ++i) block(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) += blocks[a].var_base[i];
      }
    }
  return from_matrix(cov);
}

}  // namespace

ContrastStudy::Contrast ContrastStudy::contrast(std::size_t set, const Simulated& base) const {
  Contrast c;
  const std::size_t m = contrast_component_names().size();
  std::vector<ContrastBlock> blocks;
  for (std::size_t gi = 0; gi < groups_.size(); ++gi) {
    const ContrastGroup& g = groups_[gi];
    if (g.set != set) continue;
    const HeldAgainst held = held_against(sets_, groups_, scatter_, set, g);
    const std::vector<double> mean = component_mean(g.components);
    std::vector<double> base_shift(m, 0.0), base_var(m, 0.0);
    if (!same_rate(g.rate, g.reference_rate))
      paired(components(base, g.rate), components(base, g.reference_rate), base_shift, base_var);
    ContrastBlock b;
    for (std::size_t i = 0; i < m; ++i) b.d.push_back(mean[i] - held.mean[i] - base_shift[i]);
    b.var_base = base_var;
    b.own = to_matrix(scatter_.covariance[gi]) / static_cast<double>(g.components.size());
    b.shared = to_matrix(*held.sigma) * held.weight;
    b.shared_key = held.key;
    for (std::size_t i = 0; i < m; ++i) {
      c.names.push_back(fmt::format("{}@{:g}", contrast_component_names()[i], g.rate));
      c.difference.push_back(b.d[i]);
    }
    c.groups.push_back(gi);
    blocks.push_back(std::move(b));
  }
  c.weight = spd_inverse(joint_covariance(blocks, m));
  if (blocks.size() == 1)  // one rate: the component names need no rate
    c.names.assign(contrast_component_names().begin(), contrast_component_names().end());
  c.coverage = DataCoverage{rates_spanned(groups_, c.groups), 1};
  return c;
}

std::vector<double> ContrastStudy::model_contrast(const Contrast& c, const Simulated& with_effect,
                                                  const Simulated& base) const {
  std::vector<double> out;
  for (std::size_t gi : c.groups) {
    std::vector<double> mean, var;
    paired(components(with_effect, groups_[gi].rate), components(base, groups_[gi].rate), mean, var);
    out.insert(out.end(), mean.begin(), mean.end());
  }
  return out;
}

std::vector<std::vector<double>> ContrastStudy::seed_moves(const Contrast& c, const Simulated& moved,
                                                           const Simulated& from) const {
  std::vector<std::vector<double>> out;
  for (std::size_t gi : c.groups) {
    const auto &a = components(moved, groups_[gi].rate), &b = components(from, groups_[gi].rate);
    out.resize(a.size());
    for (std::size_t s = 0; s < a.size(); ++s)
      for (std::size_t i = 0; i < a[s].size(); ++i) out[s].push_back(a[s][i] - b[s][i]);
  }
  return out;
}

ContrastStudy::CurveContrast ContrastStudy::curve_contrast(const Contrast& c, const Simulated& model,
                                                           const Simulated& base) const {
  CurveContrast out;
  const ContrastScale ms = measured_scale_, ss = simulated_scale(base);
  for (std::size_t gi : c.groups) {
    const ContrastGroup& g = groups_[gi];
    auto curves_of = [&](std::size_t set, double rate) {
      std::vector<Curve> v;
      for (const auto& sp : sets_.sets[set].specimens)
        if (same_rate(sp.loading_rate, rate)) v.push_back(sp.curve);
      return v;
    };
    const std::vector<Curve> own = curves_of(g.set, g.rate);
    std::vector<std::vector<Curve>> refs;
    if (sets_.reference) {
      refs.push_back(curves_of(*sets_.reference, g.reference_rate));
    } else {
      for (std::size_t k = 0; k < sets_.sets.size(); ++k)
        if (k != g.set && !curves_of(k, g.rate).empty()) refs.push_back(curves_of(k, g.rate));
    }
    // To failure: the longest curve sets the range (a shorter one is continued with its last,
    // post-failure force), so a set or a model that fails later is judged there too.
    double xi_end = 0;
    auto limit = [&](const std::vector<Curve>& v) {
      for (const auto& cv : v) xi_end = std::max(xi_end, std::min(3.0, cv.displacement.back() / ms.w_ref));
    };
    limit(own);
    for (const auto& r : refs) limit(r);
    auto mean_sd = [](const std::vector<Curve>& v, double w, double& sd) {
      std::vector<double> f;
      for (const auto& cv : v) f.push_back(force_at(cv, w));
      sd = sample_sd(f);
      return measure::mean(f);
    };
    const double xi_rising = std::min(mean_peak_displacement(own) / ms.w_ref,
                                      mean_peak_displacement(model.curves[rate_index(g.rate)]) / ss.w_ref);
    for (std::size_t k = 0; k < kCurvePoints; ++k) {
      const double xi = xi_end * static_cast<double>(k) / static_cast<double>(kCurvePoints - 1);
      out.rising.push_back(xi <= xi_rising);
      double sd_own = 0, sd_ref = 0;
      const double f_own = mean_sd(own, xi * ms.w_ref, sd_own);
      double f_ref = 0;
      if (refs.size() == 1) {
        f_ref = mean_sd(refs.front(), xi * ms.w_ref, sd_ref);
      } else {
        std::vector<std::vector<double>> means;
        for (const auto& r : refs) {
          double sd = 0;
          means.push_back({mean_sd(r, xi * ms.w_ref, sd)});
          sd_ref = std::max(sd_ref, sd);
        }
        f_ref = median_of(means).front();
      }
      const double n_own = static_cast<double>(own.size()), n_ref = static_cast<double>(refs.front().size());
      const auto& sim_own = model.curves[rate_index(g.rate)];
      const auto& sim_ref = base.curves[rate_index(g.reference_rate)];
      // The model's contrast seed by seed (common random numbers pair model and base runs).
      std::vector<double> per_seed;
      for (std::size_t seed = 0; seed < std::min(sim_own.size(), sim_ref.size()); ++seed)
        per_seed.push_back((force_at(sim_own[seed], xi * ss.w_ref) - force_at(sim_ref[seed], xi * ss.w_ref)) / ss.f_ref);
      out.xi.push_back(xi);
      out.measured.push_back((f_own - f_ref) / ms.f_ref);
      out.u_measured.push_back(std::sqrt(sd_own * sd_own / n_own + sd_ref * sd_ref / n_ref) / ms.f_ref);
      out.simulated.push_back(measure::mean(per_seed));
      out.u_simulated.push_back(per_seed.size() > 1 ? sample_sd(per_seed) / std::sqrt(static_cast<double>(per_seed.size()))
                                                    : 0.0);
    }
  }
  summarise(out);
  return out;
}

}  // namespace shard::measure
