#pragma once
// A wall's prescribed motion as an exact function of the time since the start. A constant
// velocity (no ramp, no table) is the default and keeps the wall's displacement as the sum of
// its steps, as it always was; a ramp or a table gives the displacement and velocity at every
// time from the profile itself, so a restarted run (which carries the time) continues bit for
// bit and no step error accumulates.
#include <string>
#include <vector>

#include "shard/types.hpp"

namespace shard {

enum class WallRamp {
  None,         // the full velocity from the first step
  OneMinusCos,  // v(t) = V (1 - cos(pi t / T)) / 2 for t < T: no jump in acceleration at the end
  Linear,       // v(t) = V t / T for t < T: constant acceleration
};

// "none", "1-cos", "linear"; the inverse of ramp_name. Returns false for anything else.
bool parse_wall_ramp(const std::string& text, WallRamp& ramp);
const char* ramp_name(WallRamp ramp);

// A table of the wall's motion along `direction`: strictly increasing times from 0, with either
// the displacement (m, taken relative to the first row) or the velocity (m/s), piecewise linear
// between rows. After the last row the wall keeps the last segment's velocity (a displacement
// table) or the last velocity (a velocity table). A rotation table is the same with the angle
// (rad) or the angular velocity (rad/s) about the wall's rotation axis; `direction` is unused.
struct WallTable {
  std::string file;                // where it was read from (messages)
  bool gives_velocity = false;     // false: the value column is a displacement (an angle)
  Vec3 direction = Vec3::UnitZ();  // unit vector
  std::vector<double> time;
  std::vector<double> value;
  std::vector<double> travel;  // displacement at each row (the velocity column integrated)
};

struct WallMotion {
  Vec3 velocity = Vec3::Zero();  // the full velocity after the ramp (no table), m/s
  WallRamp ramp = WallRamp::None;
  double ramp_time = 0;  // s, > 0 with a ramp
  WallTable table;       // used when it has rows
  // s: the wall rests where it starts until then, and its profile (constant velocity, ramp or
  // table, spin included) runs from then on as it would from t = 0: a packing settles under
  // gravity before a loading pin moves.
  double start_time = 0;

  // Rotation about the line through `spin_centre` along the unit `spin_axis` (right-hand rule);
  // the line moves with the translation. The angle is a function of time for every profile
  // (constant: omega t), so it never accumulates step error and a restart needs no angle.
  bool spins = false;
  Vec3 spin_centre = Vec3::Zero();  // m, at displacement zero
  Vec3 spin_axis = Vec3::UnitZ();
  double angular_speed = 0;  // rad/s after the ramp (no spin table); `ramp` shapes it like velocity
  WallTable spin_table;      // angle or angular velocity over time, used when it has rows

  // True when the displacement is a function of time (a ramp or a table), false for the
  // constant velocity that is integrated step by step.
  bool is_profile() const { return start_time > 0 || ramp != WallRamp::None || !table.time.empty(); }
  // Displacement since the start and velocity at time t >= 0.
  Vec3 displacement_at(double t) const;
  Vec3 velocity_at(double t) const;
  // Angle (rad) turned since the start and angular speed (rad/s) about spin_axis at time t >= 0;
  // zero without a spin.
  double angle_at(double t) const;
  double angular_speed_at(double t) const;
};

// Checks the rows and fills `travel`; throws std::invalid_argument naming the table's file and
// the row (1-based, counting the header as row 1) that is wrong.
void prepare_wall_table(WallTable& table);

}  // namespace shard
