#pragma once
// The batch loop every contact law shares, written once for any lane type (shard/lanes/lanes.hpp): the law
// gives the normal force and the tangential spring's stiffness and dashpot; this loop adds the
// incremental tangential spring with Coulomb friction (docs/explanation/physics.md, "Forces") and the contact effect
// policies (contact_effects.hpp), switched on at compile time so that a law without effects
// carries no trace of them.
//
// Tangential spring: its extension xi (3 history doubles) is a capped spring-dashpot
// (capped_spring, turn_onto_plane below) stretched by v_t dt, F_t = -S_t xi - c_t v_t, |F_t| <= mu F_n.
//
// Rolling resistance (policy rolling_resistance, docs/reference/effects.md): the same capped spring-dashpot
// acts on the relative rolling rotation, k_r = S_t R*^2 and c_r = c_t R*^2 (the tangential
// element seen at the lever R*, so both have one damping ratio), capped at mu_r R* F_n (the
// elastic-plastic spring-dashpot model, "model C" of Ai et al., Powder Technol. 206, 2011). Its
// angle is 3 more history doubles, after the tangential spring's.
//
// Materials (docs/reference/materials.md): a law's constants form a small dense table, one row per pair of
// materials, and each block of lanes gathers its contacts' rows by ContactArrays::material_pair
// (null with one material: row 0 broadcast once, as before there were materials). No per-pair
// call, and the same IEEE operations per lane as the scalar instance.
#include <cstddef>
#include <cstdint>
#include <numbers>

#include "shard/lanes/xsimd_lanes.hpp"

namespace shard::contact {

inline constexpr std::size_t kTangentialHistorySize = 3;
inline constexpr std::size_t kRollingHistorySize = 6;  // tangential spring, then rolling angle

// The kernel's ContactBatch as plain arrays (x, y, z interleaved per contact), so that a source
// compiled for one instruction set sees no Eigen type.
struct ContactArrays {
  std::size_t count = 0;
  double dt = 0;
  const std::int32_t* j = nullptr;  // < 0: a wall
  const double* normal = nullptr;
  const double* velocity = nullptr;
  const double* overlap = nullptr;
  const double* r_eff = nullptr;
  const double* m_eff = nullptr;
  double* history = nullptr;
  double* force = nullptr;
  double* energy = nullptr;
  const std::int32_t* material_pair = nullptr;  // per contact, the row of the law table; null: row 0
  const double* omega_rel = nullptr;  // omega_i - omega_j, rad/s (read by rolling resistance only)
  double* couple = nullptr;           // pure couple on i, N m (written by rolling resistance only)
};

// What a law computes from the normal geometry of its lanes.
template <class T>
struct NormalPart {
  T force;                 // F_n >= 0, N
  T energy;                // elastic energy of the normal spring, J
  T tangential_stiffness;  // S_t, N/m
  T tangential_damping;    // c_t, N s/m
};

// The effect policies composed into the loop (contact_effects.hpp) and their sizes.
struct EffectSwitches {
  bool cohesion = false;
  bool support_friction = false;
  bool rolling_resistance = false;
};
struct EffectSizes {
  double cohesion_stress = 0;         // sigma_c, Pa
  double support_friction_ratio = 1;  // r_w: mu_w = r_w mu of the contact's pair, 1
  // mu_r per row of the law table (a pair of materials), 1: the rolling torque's cap over R* F_n.
  // Read only when rolling resistance is on.
  const double* rolling_friction = nullptr;
};

// A spring-dashpot with a Coulomb-like cap, the tangential element of every contact and, at the
// lever R*, its rolling element: the spring's extension s (turned onto the contact plane, then
// stretched by the rate), F = -S s - c rate, capped at |F| <= limit; a sliding element's spring is
// reset to hold the capped force, -F / S, so sticking resumes from the cap without a jump.
template <class T>
struct CappedSpring {
  T fx, fy, fz;  // the transmitted force (or couple)
  T sx, sy, sz;  // the spring's extension after the step
};

// The spring kept by a contact, turned onto the current contact plane (normal n) keeping its
// length: removing the normal part alone would shrink the spring and leak elastic energy on
// every rotation.
template <class T>
void turn_onto_plane(T& hx, T& hy, T& hz, const T& nx, const T& ny, const T& nz) {
  using namespace lanes;
  const T zero(0.0);
  const T h_n = dot3(hx, hy, hz, nx, ny, nz);
  const T px = hx - h_n * nx, py = hy - h_n * ny, pz = hz - h_n * nz;
  const T old_length = sqrt(dot3(hx, hy, hz, hx, hy, hz));
  const T new_length = sqrt(dot3(px, py, pz, px, py, pz));
  const auto flat = new_length == zero;
  const T scale = old_length / new_length;
  hx = select(flat, zero, px * scale);
  hy = select(flat, zero, py * scale);
  hz = select(flat, zero, pz * scale);
}

template <class T>
CappedSpring<T> capped_spring(const T& stiffness, const T& damping, const T& limit, const T& ex, const T& ey,
                              const T& ez, const T& rx, const T& ry, const T& rz) {
  using namespace lanes;
  const T minus_s = negate(stiffness);
  const T fx = minus_s * ex - damping * rx, fy = minus_s * ey - damping * ry, fz = minus_s * ez - damping * rz;
  const T magnitude = sqrt(dot3(fx, fy, fz, fx, fy, fz));
  const auto sticks = magnitude <= limit;
  const T cap = limit / magnitude;
  const T cx = fx * cap, cy = fy * cap, cz = fz * cap;
  return {select(sticks, fx, cx),
          select(sticks, fy, cy),
          select(sticks, fz, cz),
          select(sticks, ex, negate(cx) / stiffness),
          select(sticks, ey, negate(cy) / stiffness),
          select(sticks, ez, negate(cz) / stiffness)};
}

// Law: one row of constants, `double constant[kConstants]`, of which constant[kFriction] is mu,
// and `template <class T> static NormalPart<T> normal(const T* c, delta, R, m, v_n)` reading the
// row as lanes c[0 .. kConstants). (No non-template member functions and no std:: calls: see
// lanes.hpp on per-instruction-set symbols.) `laws` is the table, a.material_pair its rows.
template <class T, bool Cohesion, bool SupportFriction, bool Rolling, class Law>
void contact_lanes(const ContactArrays& a, const Law* laws, const EffectSizes& effects) {
  using namespace lanes;
  using L = Lanes<T>;
  constexpr std::size_t N = L::width;
  constexpr std::size_t K = Law::kConstants;
  const T zero(0.0);
  const T dt(a.dt);
  [[maybe_unused]] const T ratio_wall(effects.support_friction_ratio);
  constexpr bool uses_walls = Cohesion || SupportFriction;
  // The law's constants as lanes: one pair's broadcast once, or each lane's own row (gather_rows).
  T one_pair[K];
  for (std::size_t f = 0; f < K; ++f) one_pair[f] = T(laws[0].constant[f]);
  T per_lane[K];
  alignas(64) double gathered[K][N];
  const auto gather_rows = [&](const std::int32_t* rows) -> const T* {
    for (std::size_t l = 0; l < N; ++l)
      for (std::size_t f = 0; f < K; ++f) gathered[f][l] = laws[rows[l]].constant[f];
    for (std::size_t f = 0; f < K; ++f) per_lane[f] = L::load(gathered[f]);
    return per_lane;
  };
  // Rolling resistance's mu_r per lane, from the same rows.
  [[maybe_unused]] const auto rolling_friction_of = [&](const std::int32_t* rows) -> T {
    if (rows == nullptr) return T(effects.rolling_friction[0]);
    alignas(64) double mu_r[N];
    for (std::size_t l = 0; l < N; ++l) mu_r[l] = effects.rolling_friction[rows[l]];
    return L::load(mu_r);
  };

  // One block of N contacts from arrays laid out as the kernel's (vectors x, y, z interleaved),
  // either the batch's own or the padded copy of its last, partial block.
  const auto block = [&](const double* normal, const double* velocity, double* history, const double* overlap,
                         const double* r_eff, const double* m_eff, const double* wall_flag, double* force,
                         double* energy_out, const T* row, [[maybe_unused]] const double* omega,
                         [[maybe_unused]] double* rolling_angle, [[maybe_unused]] double* couple,
                         [[maybe_unused]] const T& mu_r) {
    // A local copy: the stores below cannot alias it, so its lanes stay in registers.
    T constants[K];
    for (std::size_t f = 0; f < K; ++f) constants[f] = row[f];
    T nx, ny, nz, vx, vy, vz, hx, hy, hz;
    load3(normal, nx, ny, nz);
    load3(velocity, vx, vy, vz);
    load3(history, hx, hy, hz);
    const T delta = L::load(overlap), R = L::load(r_eff), m = L::load(m_eff);
    [[maybe_unused]] const auto wall = L::load(wall_flag) != zero;

    // Normal: the law's spring and dashpot; v.n < 0 while approaching.
    const T v_n = dot3(vx, vy, vz, nx, ny, nz);
    const NormalPart<T> normal_part = Law::normal(constants, delta, R, m, v_n);
    const T mu = constants[Law::kFriction];

    // Tangential spring turned onto the contact plane, keeping its length, then stretched.
    const T tx = vx - v_n * nx, ty = vy - v_n * ny, tz = vz - v_n * nz;
    turn_onto_plane(hx, hy, hz, nx, ny, nz);
    const T xi_x = hx + tx * dt, xi_y = hy + ty * dt, xi_z = hz + tz * dt;

    // Spring and dashpot, capped by Coulomb (support_friction: supports and pins have their own mu).
    const T s_t = normal_part.tangential_stiffness, c_t = normal_part.tangential_damping;
    T limit;
    if constexpr (SupportFriction)
      limit = select(wall, ratio_wall * mu, mu) * normal_part.force;
    else
      limit = mu * normal_part.force;
    const CappedSpring<T> t = capped_spring(s_t, c_t, limit, xi_x, xi_y, xi_z, tx, ty, tz);
    const T &sx = t.sx, &sy = t.sy, &sz = t.sz;

    T force_x = normal_part.force * nx + t.fx;
    T force_y = normal_part.force * ny + t.fy;
    T force_z = normal_part.force * nz + t.fz;
    T energy = normal_part.energy + T(0.5) * s_t * dot3(sx, sy, sz, sx, sy, sz);
    if constexpr (Rolling) {
      // The rolling part of the relative spin (its normal part, twisting, is not resisted) winds
      // the rolling spring; couple -k_r theta - c_r omega_roll on i, capped at mu_r R* F_n.
      T wx, wy, wz, ax, ay, az;
      load3(omega, wx, wy, wz);
      load3(rolling_angle, ax, ay, az);
      const T w_n = dot3(wx, wy, wz, nx, ny, nz);
      const T rx = wx - w_n * nx, ry = wy - w_n * ny, rz = wz - w_n * nz;
      turn_onto_plane(ax, ay, az, nx, ny, nz);
      const T lever = R * R;
      const T k_r = s_t * lever, c_r = c_t * lever;
      const CappedSpring<T> r = capped_spring(k_r, c_r, mu_r * R * normal_part.force, ax + rx * dt, ay + ry * dt,
                                              az + rz * dt, rx, ry, rz);
      store3(couple, r.fx, r.fy, r.fz);
      store3(rolling_angle, r.sx, r.sy, r.sz);
      energy = energy + T(0.5) * k_r * dot3(r.sx, r.sy, r.sz, r.sx, r.sy, r.sz);
    }
    if constexpr (Cohesion) {
      // Between particles only (not at walls): a pull sigma_c pi R* delta along -n on i while they
      // touch, with the potential -sigma_c pi R* delta^2 / 2 (contact_effects.hpp).
      // A zero pull (sigma_c = 0, the neutral value) leaves every bit: x - 0 n would turn a -0
      // force component into +0.
      const T sigma(effects.cohesion_stress);
      const T pull = sigma * (T(std::numbers::pi) * R * delta);
      const auto none = pull == zero;
      force_x = select(wall, force_x, select(none, force_x, force_x - pull * nx));
      force_y = select(wall, force_y, select(none, force_y, force_y - pull * ny));
      force_z = select(wall, force_z, select(none, force_z, force_z - pull * nz));
      energy = select(wall, energy, select(none, energy, energy + T(-0.5) * sigma * T(std::numbers::pi) * R * delta * delta));
    }
    store3(force, force_x, force_y, force_z);
    store3(history, sx, sy, sz);
    L::store(energy_out, energy);
  };

  alignas(64) double wall_flag[N];
  for (std::size_t l = 0; l < N; ++l) wall_flag[l] = 0.0;
  const T no_rolling(0.0);
  std::size_t k0 = 0;
  // Whole blocks straight from the batch; with rolling resistance (a history of 6 doubles per
  // contact) each block goes through the padded copy below instead.
  if constexpr (!Rolling)
    for (; k0 + N <= a.count; k0 += N) {
      if constexpr (uses_walls)
        for (std::size_t l = 0; l < N; ++l) wall_flag[l] = a.j[k0 + l] < 0 ? 1.0 : 0.0;
      block(a.normal + 3 * k0, a.velocity + 3 * k0, a.history + 3 * k0, a.overlap + k0, a.r_eff + k0, a.m_eff + k0,
            wall_flag, a.force + 3 * k0, a.energy + k0, a.material_pair ? gather_rows(a.material_pair + k0) : one_pair,
            nullptr, nullptr, nullptr, no_rolling);
    }
  // A block copied out of the batch (the partial last one padded with a harmless contact whose
  // results are not kept), run, and copied back.
  constexpr std::size_t H = Rolling ? kRollingHistorySize : kTangentialHistorySize;
  alignas(64) double normal[3 * N], velocity[3 * N], history[3 * N], force[3 * N];
  alignas(64) double overlap[N], r_eff[N], m_eff[N], energy[N];
  [[maybe_unused]] alignas(64) double omega[3 * N], rolling_angle[3 * N], couple[3 * N];
  std::int32_t rows[N];
  for (; k0 < a.count; k0 += N) {
    const std::size_t lanes = a.count - k0 < N ? a.count - k0 : N;
    for (std::size_t l = 0; l < N; ++l) {
      const bool real = l < lanes;
      const std::size_t k = k0 + (real ? l : 0);
      for (std::size_t c = 0; c < 3; ++c) {
        normal[3 * l + c] = real ? a.normal[3 * k + c] : (c == 0 ? 1.0 : 0.0);
        velocity[3 * l + c] = real ? a.velocity[3 * k + c] : 0.0;
        history[3 * l + c] = real ? a.history[H * k + c] : 0.0;
        if constexpr (Rolling) {
          omega[3 * l + c] = real ? a.omega_rel[3 * k + c] : 0.0;
          rolling_angle[3 * l + c] = real ? a.history[H * k + 3 + c] : 0.0;
        }
      }
      overlap[l] = real ? a.overlap[k] : 1.0;
      r_eff[l] = real ? a.r_eff[k] : 1.0;
      m_eff[l] = real ? a.m_eff[k] : 1.0;
      wall_flag[l] = real && a.j[k] < 0 ? 1.0 : 0.0;
      rows[l] = real && a.material_pair ? a.material_pair[k] : 0;
    }
    T mu_r = no_rolling;
    if constexpr (Rolling) mu_r = rolling_friction_of(a.material_pair ? rows : nullptr);
    block(normal, velocity, history, overlap, r_eff, m_eff, wall_flag, force, energy,
          a.material_pair ? gather_rows(rows) : one_pair, omega, rolling_angle, couple, mu_r);
    for (std::size_t l = 0; l < lanes; ++l) {
      for (std::size_t c = 0; c < 3; ++c) {
        a.force[3 * (k0 + l) + c] = force[3 * l + c];
        a.history[H * (k0 + l) + c] = history[3 * l + c];
        if constexpr (Rolling) {
          a.couple[3 * (k0 + l) + c] = couple[3 * l + c];
          a.history[H * (k0 + l) + 3 + c] = rolling_angle[3 * l + c];
        }
      }
      a.energy[k0 + l] = energy[l];
    }
  }
}

// A law's batch loop for one lane type and effect selection.
template <class Law>
using LawKernel = void (*)(const ContactArrays&, const Law*, const EffectSizes&);

template <class T, bool Rolling, class Law>
LawKernel<Law> kernel_with_rolling(EffectSwitches on) {
  if (on.cohesion && on.support_friction) return &contact_lanes<T, true, true, Rolling, Law>;
  if (on.cohesion) return &contact_lanes<T, true, false, Rolling, Law>;
  if (on.support_friction) return &contact_lanes<T, false, true, Rolling, Law>;
  return &contact_lanes<T, false, false, Rolling, Law>;
}

template <class T, class Law>
LawKernel<Law> kernel_for(EffectSwitches on) {
  return on.rolling_resistance ? kernel_with_rolling<T, true, Law>(on) : kernel_with_rolling<T, false, Law>(on);
}

}  // namespace shard::contact
