#pragma once
// The commands give the values they compute to a scene (a seated pin, a calibrated modulus, a
// scaled duration) at a fixed number of significant digits: the precision these values always had,
// so the figures measured with them (docs/explanation/diagnosis.md, docs/explanation/four-point-bending.md) reproduce
// bit for bit. A DEM fracture amplifies a change in the 13th digit into the 4th digit of the
// post-peak curve; the loop's statistics then move. The value is rounded as its decimal text
// would be read back (correctly rounded both ways), and passed on typed.
#include <fmt/format.h>

#include <cstdlib>
#include <string>

#include "shard/types.hpp"

namespace shard {

inline double significant(double x, int digits) {
  const std::string text = fmt::format("{:.{}g}", x, digits);
  return std::strtod(text.c_str(), nullptr);
}

inline Vec3 significant(const Vec3& v, int digits) {
  return {significant(v.x(), digits), significant(v.y(), digits), significant(v.z(), digits)};
}

}  // namespace shard
