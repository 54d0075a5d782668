#pragma once
// Contrast diagnosis across measurement sets (docs/explanation/diagnosis.md "Lab data: contrasts across sets").
//
// A lab's beams are never Shard's model: grain size, contact and bond laws, fixture and preload
// all differ, so the best base model leaves a structured residual (the form error) before any
// effect is missing. Labs test several batches or conditions with one fixture; the form error is
// then common to the sets and cancels in their differences, while an effect that differs between
// sets does not. So the question asked of each set is "how does it differ from the reference, and
// which library effect makes the model differ in the same way?".
//
// Components. Each curve (a measured specimen or a simulated replicate) is reduced to eight
// numbers that are comparable between a lab's beam and the model: logarithms of stiffness, peak
// force, peak displacement and work to peak (relative changes, free of the form error's scale),
// the nonlinearity before the peak, the post-peak ductility ln(w_parted / w_peak), and the
// logarithms of force and displacement at crack initiation (features.hpp: crack_initiation). A
// brittle test's force maximum comes during unstable fracture, up to ~65 % above the force at
// initiation, so a batch whose initiation moves can keep its F_max: only the initiation shows it. A force
// read at a fixed displacement past the peak was tried and dropped: it is a step in where the
// beam parts, and on foreign truth it alone pulled a machine-compliance fit to half the truth.
//
// Noise. The specimens of one set scatter together (a stronger beam is stronger everywhere), so
// the components are correlated. Their covariance Sigma is pooled over all sets (each specimen
// about its own set's mean: one fixture, one lab, the same scatter structure; nu = sum(n_s) - K
// degrees of freedom), shrunk by 10 % towards its diagonal so that a few specimens still give an
// invertible matrix. A contrast d = mean_s - mean_r then has covariance Sigma (1/n_s + 1/n_r),
// plus the simulated contrast's own scatter over the packing seeds (diagonal).
//
// "No difference" is Hotelling's T^2 = d' W d with W the inverse covariance:
// (nu - p + 1) / (nu m) T^2 ~ F(m, nu - p + 1) when the set does not differ, p the components of
// one rate (m = p at one rate; a set at q rates stacks q blocks on the one estimate, m = q p).
//
// An effect e changes the model by t_e (its simulated contrast at the trial size, per packing
// seed against the base on the same seed: common random numbers). Its size is the generalised
// least-squares a = t'W d / t'W t kept in the effect's physical range; what remains is
// chi^2_e = (d - a t)' W (d - a t); the drop chi^2_0 - chi^2_e is judged by Rao's test of the
// information one more direction adds (added_direction_p), Bonferroni over the effects tried.
#include <stdexcept>
#include <string>
#include <vector>

#include "shard/measure/curve.hpp"
#include "shard/measure/diagnosis.hpp"

namespace shard::measure {

// The scales that make curves of two sources comparable (the contrast curves of the report).
struct ContrastScale {
  double w_ref = 0;  // m, mean displacement at peak
  double f_ref = 0;  // N, mean peak force
};
ContrastScale contrast_scale(const std::vector<Curve>& curves);

// The load range of a contrast's elastic line (its stiffness, and the nonlinearity measured from
// it): one range in newtons for every curve a study's contrasts compare, measured and simulated,
// as a chord modulus is taken between fixed loads. A range that follows each curve's own peak climbs a
// curved rising branch with the peak: on the default beam, whose rise stiffens with the load, a
// bond softening that raised F_max 30 % raised that slope 14 % (the same slope between fixed
// loads: 0 %), a stiffness change no lab's softening shows.
struct StiffnessBand {
  double low = 0, high = 0;  // N; high 0: each curve's own 10-60 % of its F_max
};
// 10-40 % of the reference's mean F_max (ContrastScale::f_ref): below 60 % of the peak of a
// batch down to two thirds of the reference's strength.
StiffnessBand stiffness_band(const ContrastScale& reference);

const std::vector<std::string>& contrast_component_names();
// contrast_components' error for a curve with no rise to a peak: the figure that is not positive.
// A measured curve's message points at the sign convention; a simulated one's caller says which
// model gave it (ContrastStudy::simulate).
class CurveWithoutRise : public std::invalid_argument {
 public:
  CurveWithoutRise(std::string curve, std::string figure, double value);
  std::string curve, figure;
  double value = 0;
};
// The same for a simulated curve at `rate` (m/s), in the words of a model run.
std::string simulated_without_rise(const CurveWithoutRise& e, double rate);
// The components of one curve; throws CurveWithoutRise when it has no rise to a peak. A curve whose peak
// lies below the band's top / 0.6 has its line taken over the band scaled down to 60 % of its
// own peak.
std::vector<double> contrast_components(const Curve& c, const StiffnessBand& band = {});

// The rows' mean, component by component.
std::vector<double> component_mean(const std::vector<std::vector<double>>& rows);
// The rows' median, component by component (of an even count: the mean of the middle two).
std::vector<double> median_of(const std::vector<std::vector<double>>& rows);

// Within-set covariance pooled over groups of rows (one group per set), shrunk towards its
// diagonal by `shrinkage`; `dof` receives sum(n) - groups.
std::vector<std::vector<double>> pooled_covariance(const std::vector<std::vector<std::vector<double>>>& groups,
                                                   double shrinkage, double& dof);

// The noise a contrast is judged against: a covariance of `dimension` components (one rate's)
// estimated with `dof` degrees of freedom, the pooled specimen scatter. A set tested at several
// rates stacks a block of `dimension` components per rate on that one estimate.
struct ScatterEstimate {
  double dof = 0;
  double dimension = 0;
};

// P(F > (nu - p + 1)/(nu k) T^2) for F ~ F(k, nu - p + 1): Hotelling's T^2 test of k components
// whose covariance is an estimate of dimension p with nu degrees of freedom (k = p: exact). With
// k = q p (q rates on one estimate) the same F keeps the statistic's mean q p nu / (nu - p - 1)
// and errs on the safe side in its tail (simulated: 3.9 % below 0.05 at p 8, q 2, nu 15-60);
// chi^2(k) there, the estimate ignored, called over 95 % of such null sets different. Falls
// back to chi^2(k) when nu - p + 1 < 1 (fewer specimens than components).
double hotelling_p(double t_square, double k, double nu, double p);

// The T^2 that hotelling_p reads as `level`: the smallest difference the test sees at that level.
// Against chi^2_k's quantile (the scatter known) it says how much power an estimate of few degrees
// of freedom leaves: at nu 30, p 8, k 8 the 5 % point is 24.8 against 15.5; at nu 9, k 16, 1400
// against 26.3.
double hotelling_critical(double level, double k, double nu, double p);

// P(F > (nu - p + 1) drop / (nu + after)) for F ~ F(1, nu - p + 1): Rao's test of the
// information one more fixed direction adds to a Hotelling T^2, `drop` the fall of T^2 it brings
// and `after` what is left, the covariance an estimate of dimension p (the components not yet
// fitted) with nu degrees of freedom. Exact at one rate. The drop alone against F(1, nu - p + 1)
// ignores that the estimate's error enters the drop too: on null sets of p = 8 it called 5 %
// (nu 27) to 12 % (nu 15) of chance directions significant at 0.01, and at two rates 23 %.
double added_direction_p(double drop, double after, double nu, double p);

struct ContrastFit {
  std::string name;
  double scale = 0;        // a, in trial sizes from neutral (clamped to [scale_min, scale_max])
  double u_scale = 0;      // its standard uncertainty 1 / sqrt(t'W t)
  bool at_bound = false;   // the unclamped a lay outside the physical range
  double chi_square = 0;   // chi^2_e = (d - a t)' W (d - a t)
  double chi_square_form = 0;  // the same with the form tolerance in the covariance: what p_after reads
  double drop = 0;         // chi^2_0 - chi^2_e
  double p_drop = 1;       // added_direction_p(drop, chi_square, nu, p)
  double p_after = 1;      // hotelling_p of chi_square_form: m - 1 components, p - 1 estimated
  bool identifiable = true;  // EffectSignature::identifiable: false, never the verdict (a rival at most)
};

struct ContrastOptions {
  double no_difference_p = 0.05;   // T^2 test: the set does not differ above this p ...
  double significant_p = 0.01;     // ... and no effect's drop beats this p over the n effects
  double drop_p = 0.05;            // a named effect's drop must beat this p over the n effects
  double remaining_p = 0.05;       // and leave a remainder compatible with noise
  double rival_chi_square = 2.0;   // effects within this of the best are rivals
  // The library's effect and the lab's are the same physics in different forms (another bond
  // law, packing, fixture), so the lab's contrast matches the simulated one only to within a
  // share of it: the remainder test adds (form_tolerance x a t_i)^2 to each component's variance.
  // 0 demands the library's shape exactly; on foreign truth whose preload-zeroed curves leave a
  // noise floor of 4 % contrast NRMSE, it called compliance, softening and Weibull sets
  // "unexplained" although their effect removed 93-98 % of T^2 (docs/explanation/diagnosis.md).
  double form_tolerance = 0.2;
  // A name must also reproduce the contrast as a curve, not only its summary components: the
  // named model's simulated contrast curve within curve_floor_factor times the curve's noise
  // floor (ContrastStudy::CurveContrast::floor), and at least min_share of T^2 explained.
  // Otherwise the set reads "unexplained difference" with its closest effect and share.
  double curve_floor_factor = 1.5;
  double min_share = 0.5;
  // A closest effect whose remainder fails the component test is still named when its curve
  // agrees and it explains at least this share of T^2: the components at and after the peak carry
  // the fracture's form (a lab's crack runs unstably, overshooting its initiation), which the
  // curve rule leaves out on purpose. On the default-size foreign sets the right names took
  // 87-98 % of T^2; a wrong closest effect (weibull_strength for a settled self-weight) took 88 %.
  double curve_name_share = 0.85;
  // Names need a base that reproduces the reference: at most this NRMSE of form error between the
  // fitted base's curves and the reference's (BaseCalibration::form_error). On the default-size
  // foreign draws the bases that left 4.2-8.7 % gave no wrong name; one that left 11.5 % (a fit
  // that did not converge, stiffness -26 %) named a softening set "bond_softening +
  // machine_compliance", one that left 16 % (6 mm unbreakable zones) named a high-friction set
  // compression_asymmetry.
  double base_nrmse_limit = 0.10;
  // A pair is tried only beside a closest effect that took at least this share of T^2 on its own.
  // The pair search is stepwise: it keeps the closest and adds a second. A closest that takes
  // about half may stand in for an effect the library lacks, and a second then patches what it
  // misses. On the default-size foreign draws the right pairs' closest took 86-91 % of T^2; the two
  // wrong pairs' (a self-weight set read as roller friction + asymmetry, a Weibull set as Weibull
  // + roller friction) 55 % and 64 %.
  double pair_first_share = 0.75;
  // ... and when its model reproduces the peak force: the curve rule reads the rising branch only,
  // which one effect of two reproduces up to its own peak while the measured curve climbs on. A
  // peak force the named effect leaves where the data do not is a second cause, not the crack's
  // form: every peak-force component must lie within this many standard uncertainties of the
  // model's, widened by form_tolerance x the model's own change. On four foreign draws the right
  // curve names lay within 1.25 of them; a compliance and softening batch's frame alone at 15.6.
  double curve_name_peak_sigmas = 4.0;
  // ... and the rising branch's own components, its stiffness and nonlinearity, within this many:
  // the curve rule's NRMSE averages the rising branch, so a closest effect with the wrong shape
  // there (a frame's spring for a seating toe that bends the curve the other way) can pass it
  // while missing the nonlinearity by many standard uncertainties. Looser than the peak force's,
  // as the codes' seating and zeroing bend the start of the curve differently: on four foreign
  // draws the right curve names lay within 4.8 of them, a frame's spring for a seating toe at
  // 13.7-17.3.
  double curve_name_rising_sigmas = 8.0;
  // Sets whose specimen scatter is exceptional carry their own instead of joining the pool
  // (group_scatter.hpp), at this p over the sets; 0 pools every set. Off by default: on the
  // tiny-beam foreign sets the Weibull set (95 x the others' variance) left the pool and the
  // asymmetry set's remainder, measured against the narrower pool, fell to p 0.047 (named
  // before); on the default-size foreign draw it names the self-weight set and keeps a
  // frictionless-roller set (272 x) from swamping every other contrast.
  double own_scatter_p = 0;
  // A rate-independent name for a strength difference on a set tested at several rates needs the
  // set's rate dependence resolved against subcritical crack growth of this exponent n
  // (rate_sensitivity.hpp). Glass, ceramics, rock and cement-based materials lie at n 10-50; 20
  // stands for a typical brittle solid, and a larger n (weaker rate dependence) asks for more
  // specimens before such a name.
  double subcritical_exponent = 20;
  // Effects tried for the Bonferroni corrections (0: those passed). A confirmation that decides
  // on the simulated refits of the top few still pays for every effect the ranking looked at.
  std::size_t tried = 0;
};

struct ContrastDecision {
  double chi_square = 0;  // T^2 of the contrast
  double p_value = 1;     // Hotelling
  std::vector<ContrastFit> fits;  // best (lowest chi^2_e) first
  std::string verdict;            // kNoDifference, the effect's name, or kUnexplainedDifference
  std::vector<std::string> rivals;
  // With no effect named: the best fit that would have been named but cannot be told apart at the
  // rates of this contrast (a rate effect when set and reference were tested at one rate).
  std::string unidentifiable;
};

inline constexpr const char* kNoDifference = "no difference";
inline constexpr const char* kUnexplainedDifference = "unexplained difference";

// `difference` d, its inverse covariance `weight` (m x m), the effects' simulated contrasts t_e
// (EffectSignature::signature, same components) with their admissible scales, and the scatter
// estimate the weight was made from.
// The fits other than `named` whose drop beats `level` and whose chi^2 lies within
// rival_chi_square of the named one's: effects these data cannot tell from it.
std::vector<std::string> rivals_of(const std::vector<ContrastFit>& fits, const ContrastFit& named, double level,
                                   const ContrastOptions& options);

ContrastDecision decide_contrast(const std::vector<double>& difference, const std::vector<std::vector<double>>& weight,
                                 const std::vector<EffectSignature>& effects, const ScatterEstimate& noise,
                                 const ContrastOptions& options = {});

// Two effects at once: when the best single effect takes a significant share of
// a set's difference but leaves a remainder beyond noise, the next is sought as a pair with it.
// The pair's sizes are the two-column generalised least squares of d on (t_first, t_second), each
// kept in its range (a size at a bound is held there and the other refit); the second is judged
// by what it adds: the drop from the first's own chi^2, by Rao's test like a single effect's with
// the first's direction already fitted, Bonferroni over the seconds tried; the remainder gets the
// form tolerance of both effects' contrast and m - 2 components.
struct ContrastPairFit {
  std::string first, second;
  double scale_first = 0, scale_second = 0;      // in the signatures' trial sizes from neutral
  double u_scale_first = 0, u_scale_second = 0;  // marginal standard uncertainties
  bool at_bound = false;                         // either size was held at its range's bound
  double chi_square = 0;       // (d - a t1 - b t2)' W (d - a t1 - b t2)
  double chi_square_form = 0;  // with the form tolerance of a t1 + b t2
  double drop = 0;             // the first's own chi^2 minus the pair's
  double p_drop = 1;           // added_direction_p(drop, chi_square, nu, p - 1)
  double p_after = 1;          // hotelling_p of chi_square_form: m - 2 components, p - 2 estimated
  // That the pair's run moves the model from the first effect's run by no more than the packing
  // seeds scatter it (seed_consistency_p); 0 for a linear fit, which no seed has run.
  double p_seeds = 0;
};

// `first_chi_square`: the first effect's own chi^2 (its single fit), from which the drop counts.
ContrastPairFit fit_contrast_pair(const std::vector<double>& difference, const std::vector<std::vector<double>>& weight,
                                  const EffectSignature& first, const EffectSignature& second, double first_chi_square,
                                  const ScatterEstimate& noise, const ContrastOptions& options = {});

// A pair fit simulated at its sizes: `combined` is the model's contrast with both effects on at
// once (not the sum of the two: effects interact). Scales are carried from `sized`.
ContrastPairFit judge_simulated_pair(const std::vector<double>& difference,
                                     const std::vector<std::vector<double>>& weight, const std::vector<double>& combined,
                                     ContrastPairFit sized, double first_chi_square, const ScatterEstimate& noise,
                                     const ContrastOptions& options = {});

// Whether one model moves another's contrast towards the measured one on every packing seed alike.
// `moves`: per seed, the moved model's components minus the other's (common seeds); each is
// projected on what the other leaves of the measured contrast, `residual`, in the metric `weight`
// (r' W D_s, the part of the move that lowers chi^2); returned is the one-sided p of their mean
// under Student's t with seeds - 1 degrees of freedom. A brittle model's fracture components are
// drawn anew by any change of the model, however slight: a second effect at a twelfth of its trial
// step then lowers chi^2 by chance on some seeds and raises it on others. 1 for fewer than two
// seeds; 0 when every seed moves it alike and towards the residual.
double seed_consistency_p(const std::vector<double>& residual, const std::vector<std::vector<double>>& weight,
                          const std::vector<std::vector<double>>& moves);
// The same in the unit metric (standardised residuals: the single-set diagnosis's).
double seed_consistency_p(const std::vector<double>& residual, const std::vector<std::vector<double>>& moves);

// Whether a set's closest single effect may start a pair: its own drop significant over the
// `effects` of the library, identifiable, and at least pair_first_share of the set's T^2.
bool starts_a_pair(const ContrastFit& closest, double t_square, std::size_t effects,
                   const ContrastOptions& options = {});

// The pair is named when the first effect's own drop was significant (the caller's condition),
// the second's drop beats drop_p over `seconds_tried`, the remainder is compatible with noise, and
// the packing seeds agree on the pair's move (p_seeds below drop_p).
bool pair_is_named(const ContrastPairFit& pair, std::size_t seconds_tried, const ContrastOptions& options = {});

// Inverse of a symmetric positive-definite matrix (throws when it is not).
std::vector<std::vector<double>> spd_inverse(const std::vector<std::vector<double>>& a);

}  // namespace shard::measure
