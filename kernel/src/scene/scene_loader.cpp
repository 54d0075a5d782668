#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <toml++/toml.h>

#include "shard/geometry/stl.hpp"
#include "shard/scene.hpp"
#include "body_section.hpp"
#include "material_section.hpp"
#include "scene_override_toml.hpp"
#include "scene_section.hpp"
#include "wall_table_reader.hpp"

namespace shard {
namespace {

using scene_detail::plugin_choice;
using scene_detail::read_bodies;
using scene_detail::Section;
using scene_detail::where;

// A wall's motion or rotation table, its errors also naming the scene key that gave it.
WallTable read_table(const Section& s, const std::string& key, const std::string& file,
                     const std::filesystem::path& dir, WallTableKind kind) {
  const auto path = std::filesystem::path(file).is_absolute() ? std::filesystem::path(file) : dir / file;
  try {
    return read_wall_table(path, kind);
  } catch (const SceneError& e) {
    throw SceneError(fmt::format("{} (read for [wall] {} at {})", e.what(), key, s.at(key)));
  }
}

// Rotation about an axis (wall_motion.hpp): `rotation_axis` through `rotation_point` with a constant
// `angular_velocity` [rad/s] or `rpm` (shaped by the wall's `ramp` like `velocity`), or a
// `rotation_table` of the angle or angular velocity over time.
void read_wall_spin(Section& s, const toml::table& t, const std::filesystem::path& dir, Wall& w) {
  const Vec3 axis = s.vec3("rotation_axis", Vec3::Zero());
  const Vec3 point = s.vec3("rotation_point", w.point);
  const double omega = s.number("angular_velocity", 0, -1e300, 1e300, "rad/s");
  const double rpm = s.number("rpm", 0, -1e300, 1e300, "revolutions per minute");
  const std::string table = s.text("rotation_table", "");
  if (!t.contains("rotation_axis")) {
    for (const char* key : {"angular_velocity", "rpm", "rotation_table", "rotation_point"})
      if (t.contains(key))
        s.fail(key, "needs rotation_axis, the direction of the line the wall turns about (right-hand rule), e.g. "
                    "rotation_axis = [0, 1, 0]");
    return;
  }
  if (axis.norm() == 0)
    s.fail("rotation_axis", "must not be the zero vector: give the direction the wall turns about, e.g. [0, 1, 0]");
  const int speeds = t.contains("angular_velocity") + t.contains("rpm") + t.contains("rotation_table");
  if (speeds == 0)
    s.fail("rotation_axis", "is given without a speed: add angular_velocity [rad/s], rpm, or a rotation_table");
  if (speeds > 1)
    s.fail(t.contains("rotation_table") ? "rotation_table" : "rpm",
           "is one of angular_velocity, rpm and rotation_table, which all set the rotation; give one of them");
  if (w.shape == WallShape::Mesh && !t.contains("rotation_point"))
    s.fail("rotation_axis", "of a mesh wall needs rotation_point, a point on the axis in the mesh's coordinates "
                            "(after scale and offset), e.g. the drum's centre");
  w.motion.spins = true;
  w.motion.spin_axis = axis.normalized();
  w.motion.spin_centre = point;
  w.motion.angular_speed = t.contains("rpm") ? rpm * 2.0 * std::numbers::pi / 60.0 : omega;
  if (table.empty()) return;
  if (w.motion.ramp != WallRamp::None && !t.contains("velocity"))
    s.fail("ramp", "is given with a rotation_table and no velocity; a table holds its own ramp");
  w.motion.spin_table = read_table(s, "rotation_table", table, dir, WallTableKind::Rotation);
}

// A conveyor belt: the surface slides over the fixed geometry at `surface_velocity`, or at
// `belt_speed` along `belt_direction`.
void read_wall_belt(Section& s, const toml::table& t, Wall& w) {
  const Vec3 surface = s.vec3("surface_velocity", Vec3::Zero());
  const double speed = s.number("belt_speed", 0, -1e300, 1e300, "m/s");
  const Vec3 direction = s.vec3("belt_direction", Vec3::Zero());
  const bool by_vector = t.contains("surface_velocity"), by_speed = t.contains("belt_speed");
  if (!by_vector && !by_speed) {
    if (t.contains("belt_direction")) s.fail("belt_direction", "is given without belt_speed [m/s]");
    return;
  }
  const std::string key = by_vector ? "surface_velocity" : "belt_speed";
  if (by_vector && (by_speed || t.contains("belt_direction")))
    s.fail("surface_velocity", "is given with belt_speed or belt_direction, which say the same; give one form");
  if (w.shape == WallShape::Cylinder)
    s.fail(key, "has no meaning on a cylinder, whose surface cannot slide along itself as a flat belt does: make it "
                "a turning roller instead, rotation_axis = its axis and angular_velocity = belt speed / radius");
  if (by_speed) {
    if (direction.norm() == 0)
      s.fail("belt_direction", "is missing or zero: the belt runs along it, e.g. belt_direction = [1, 0, 0]");
    w.surface_velocity = speed * direction.normalized();
  } else {
    w.surface_velocity = surface;
  }
  if (w.shape == WallShape::Plane) {
    const double across = w.surface_velocity.dot(w.axis.normalized());
    if (std::abs(across) > 1e-9 * w.surface_velocity.norm())
      s.fail(t.contains("belt_direction") ? "belt_direction" : key,
             fmt::format("has {} m/s along the plane's normal; a belt's surface moves within the plane: give a "
                         "direction perpendicular to the normal",
                         across));
  }
}

// The wall's motion profile (wall_motion.hpp): `velocity` with an optional `ramp` over
// `ramp_time`, or a `motion_table` along `direction`, from `start_time` on.
void read_wall_motion(Section& s, const toml::table& t, const std::filesystem::path& dir, Wall& w) {
  w.motion.velocity = w.velocity;
  w.motion.start_time = s.number("start_time", 0, 0, 1e300, "s");
  const std::string ramp = s.text("ramp", "none");
  if (!parse_wall_ramp(ramp, w.motion.ramp))
    s.fail("ramp", fmt::format("= '{}' is not a ramp; use \"1-cos\", \"linear\" or \"none\"", ramp));
  w.motion.ramp_time = s.number("ramp_time", 0, 0, 1e300, "s");
  if (w.motion.ramp != WallRamp::None && !(w.motion.ramp_time > 0))
    s.fail("ramp", fmt::format("= '{}' needs ramp_time, the time in s to reach the velocity", ramp));
  // ramp = "none" with a ramp_time switches a ramp off (what an override can do); a ramp_time
  // alone is a forgotten ramp.
  if (!t.contains("ramp") && t.contains("ramp_time"))
    s.fail("ramp_time", "is set without a ramp; add ramp = \"1-cos\" or \"linear\", or remove it");
  const std::string table = s.text("motion_table", "");
  const Vec3 direction = s.vec3("direction", Vec3::Zero());
  if (table.empty()) {
    if (t.contains("direction")) s.fail("direction", "is the direction of a motion_table; without one, velocity gives it");
    return;
  }
  if (t.contains("velocity"))
    s.fail("velocity", "is given with a motion_table, which sets the velocity itself; remove one of them");
  if (w.motion.ramp != WallRamp::None) s.fail("ramp", "is given with a motion_table; a table holds its own ramp");
  if (direction.norm() == 0) s.fail("direction", "is missing or zero: a motion_table moves the wall along it, e.g. [0, 0, -1]");
  w.motion.table = read_table(s, "motion_table", table, dir, WallTableKind::Translation);
  w.motion.table.direction = direction.normalized();
  // The scene-level velocity is the table's mean over its rows (what the loading rate reads).
  w.velocity = w.motion.table.travel.back() / w.motion.table.time.back() * w.motion.table.direction;
  w.motion.velocity = w.velocity;
}

Wall read_wall(const toml::table& t, const std::string& file, const std::filesystem::path& dir, std::size_t index,
               scene_detail::WallMaterial& material) {
  Section s(&t, file, "wall");
  Wall w;
  material = {s.text("material", ""), s.at("material")};
  w.name = s.text("name", fmt::format("wall{}", index));
  // The name becomes an HDF5 group of the run file (series/walls/<name>).
  if (w.name.empty() || w.name.find('/') != std::string::npos || w.name == "." || w.name == "..")
    s.fail("name", fmt::format("= '{}' cannot name a wall: use a non-empty name without '/', e.g. \"pin_left\"",
                               w.name));
  const std::string shape = s.text("shape", "");
  w.velocity = s.vec3("velocity", Vec3::Zero());
  if (shape == "plane") {
    w.shape = WallShape::Plane;
    w.point = s.vec3("point", Vec3::Zero());
    w.axis = s.vec3("normal", Vec3::UnitZ());
    if (w.axis.norm() == 0) s.fail("normal", "must not be the zero vector");
  } else if (shape == "cylinder") {
    w.shape = WallShape::Cylinder;
    w.point = s.vec3("point", Vec3::Zero());
    w.axis = s.vec3("axis", Vec3::UnitY());
    if (w.axis.norm() == 0) s.fail("axis", "must not be the zero vector");
    w.radius = s.number("radius", 0, 0, 1e300, "m");
    w.length = s.number("length", 0, 0, 1e300, "m");
    if (w.radius <= 0) s.fail("radius", "must be a positive length in m");
    if (w.length <= 0) s.fail("length", "must be a positive length in m");
  } else if (shape == "mesh") {
    w.shape = WallShape::Mesh;
    const std::string f = s.text("file", "");
    if (f.empty()) s.fail("file", "is missing: a mesh wall needs an STL file");
    const double scale = s.number("scale", 1.0, 1e-12, 1e12);
    const Vec3 offset = s.vec3("offset", Vec3::Zero());
    const auto path = std::filesystem::path(f).is_absolute() ? std::filesystem::path(f) : dir / f;
    try {
      const geometry::TriangleMesh mesh = geometry::read_stl(path, scale);
      for (const auto& face : mesh.faces)
        w.triangles.push_back(std::array<Vec3, 3>{Vec3(mesh.vertices[static_cast<std::size_t>(face[0])] + offset),
                                                  Vec3(mesh.vertices[static_cast<std::size_t>(face[1])] + offset),
                                                  Vec3(mesh.vertices[static_cast<std::size_t>(face[2])] + offset)});
    } catch (const std::exception& e) {
      throw SceneError(fmt::format("{}: {}", s.at("file"), e.what()));
    }
  } else {
    s.fail("shape", fmt::format("= '{}' is not a wall shape; use \"plane\", \"cylinder\" or \"mesh\"", shape));
  }
  w.unbreakable_zone = s.number("unbreakable_zone", 0, -1e300, 1e300, "m");
  if (w.unbreakable_zone < 0)
    s.fail("unbreakable_zone", "must be a distance >= 0 in m from the wall's surface, e.g. 0.01 (two grain "
                               "diameters under a roller); 0 or leaving it out: every bond may break");
  read_wall_motion(s, t, dir, w);
  read_wall_spin(s, t, dir, w);
  read_wall_belt(s, t, w);
  s.finish();
  return w;
}

// [stop] rest_speed and rest_time: the run ends once every particle's speed stayed below
// rest_speed for rest_time (driver/src/stop_rules.cpp, RestStop). Both or neither.
void read_rest_rule(Section& stop, Scene& scene) {
  const double absent = std::numeric_limits<double>::quiet_NaN();
  const double speed = stop.number("rest_speed", absent, -1e300, 1e300, "m/s");
  const double time = stop.number("rest_time", absent, -1e300, 1e300, "s");
  if (std::isnan(speed) && std::isnan(time)) return;
  if (std::isnan(speed))
    stop.fail("rest_time", "needs rest_speed too: the speed [m/s] every particle must stay below for rest_time, "
                           "e.g. rest_speed = 0.01");
  if (!(speed > 0))
    stop.fail("rest_speed", fmt::format("= {} must be positive: the speed [m/s] below which a particle counts as at "
                                        "rest, e.g. 0.01 (leave rest_speed and rest_time out to run to duration)",
                                        speed));
  if (std::isnan(time))
    stop.fail("rest_speed", "needs rest_time too: how long [s] every particle must stay below it before the run "
                            "ends, e.g. rest_time = 0.05");
  if (!(time > 0))
    stop.fail("rest_time", fmt::format("= {} must be positive: how long [s] every particle must stay below "
                                       "rest_speed, e.g. 0.05",
                                       time));
  if (time >= scene.duration)
    stop.fail("rest_time", fmt::format("= {} s is not shorter than [simulation] duration = {} s: the run could never "
                                       "come to rest before it ends; lower rest_time or raise duration",
                                       time, scene.duration));
  scene.stop.rest_speed = speed;
  scene.stop.rest_time = time;
}

}  // namespace

std::string describe(const ParamSet& params) {
  std::string out;
  for (const auto& [name, value] : params.all()) {
    std::string v = std::visit(
        [](const auto& x) -> std::string {
          using T = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<T, double>) return fmt::format("{}", x);
          else if constexpr (std::is_same_v<T, bool>) return x ? "true" : "false";
          else if constexpr (std::is_same_v<T, std::string>) return x;
          else return fmt::format("[{}, {}, {}]", x[0], x[1], x[2]);
        },
        value);
    out += (out.empty() ? "" : "; ") + name + "=" + v;
  }
  return out;
}

Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                 const PluginHost& host) {
  return load_scene(file, host, parse_overrides(overrides));
}

Scene load_scene_text(const std::string& text, const std::filesystem::path& file_path,
                      const std::vector<std::string>& overrides, const PluginHost& host) {
  return load_scene_text(text, file_path, host, parse_overrides(overrides));
}

Scene load_scene(const std::filesystem::path& file, const PluginHost& host, const SceneOverrides& overrides) {
  std::ifstream in(file);
  if (!in)
    throw SceneError(fmt::format("{}: cannot open the scene file; check the path (scenes/ has examples)",
                                 file.string()));
  std::stringstream ss;
  ss << in.rdbuf();
  return load_scene_text(ss.str(), file, host, overrides);
}

namespace {

// toml++ 3.3 enters its key parser after a table header's "[" or "[[" without checking the next
// character ("[?x]", "[[[", "[[="): a debug build aborts, a release build has undefined behaviour
// (found by fuzzing: tests/fuzz/fuzz_scene.cpp; fixed upstream after 3.3). Such a header is
// refused here first. A line of a multi-line array value starting with "[" followed by anything
// but a key character ("[ ]", "[+1") is refused too: no Shard key takes such a value.
void refuse_malformed_headers(const std::string& text, const std::string& file) {
  std::size_t line = 1;
  for (std::size_t start = 0; start < text.size(); ++line) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    // Skipped like toml++ does before a header: blanks, and (conservatively) every non-ASCII byte,
    // which covers a UTF-8 byte-order mark and Unicode blanks.
    std::size_t k = start;
    while (k < end && (text[k] == ' ' || text[k] == '\t' || static_cast<unsigned char>(text[k]) >= 0x80)) ++k;
    if (k < end && text[k] == '[') {
      const std::size_t after = text.compare(k, 2, "[[") == 0 ? k + 2 : k + 1;
      const std::size_t c = text.find_first_not_of(" \t", after);
      const char next = c < end ? text[c] : '\n';
      const bool key_start = std::isalnum(static_cast<unsigned char>(next)) || next == '_' || next == '-' ||
                             next == '"' || next == '\'';
      if (!key_start)
        throw SceneError(fmt::format("{}:{}:{}: TOML syntax error: '[' must be followed by a section name, as in "
                                     "[simulation] or [[wall]]",
                                     file, line, k - start + 1));
    }
    start = end + 1;
  }
}

// toml++ 3.3's is_non_ascii_horizontal_whitespace reaches TOML_UNREACHABLE (undefined behaviour)
// for code points in U+00A1..U+0499, U+2C5E..U+3057 (but U+3000) and U+FB26..U+FEFE -- accented
// letters, degree and micro signs, CJK commas -- wherever the parser tests them for blanks (found
// by fuzzing). Comments are not tested that way, so there they stay allowed; elsewhere they are
// refused before parsing.
bool unsafe_for_toml(unsigned cp) {
  return (cp >= 0xA1u && cp <= 0x499u) || (cp >= 0x2C5Eu && cp <= 0x3057u && cp != 0x3000u) ||
         (cp >= 0xFB26u && cp <= 0xFEFEu);
}

// Where a '#' starts a comment, TOML's string forms must be followed exactly (a '#' inside a
// string is text): basic "..." and multi-line """...""" strings with backslash escapes, literal
// '...' and multi-line '''...''' strings without. Unclosed strings stay open to the line end (single
// line) or to the end of the text (multi-line), so in doubt a character counts as outside a
// comment and is checked: the error is only ever "refused", never undefined behaviour.
enum class TomlLexeme { plain, comment, basic, literal, multiline_basic, multiline_literal };

// What the lexer made of one byte (not a newline): inside a comment (not checked), or else how
// many further ASCII bytes of a token it consumed.
struct LexStep {
  bool comment = false;
  std::size_t skip = 0;
};

// The lexer's state after the byte at k, by TOML's string and comment forms (see TomlLexeme).
LexStep advance_lexeme(const std::string& text, std::size_t k, TomlLexeme& state) {
  const auto starts = [&](const char* token) { return text.compare(k, std::strlen(token), token) == 0; };
  // A backslash consumes the next byte when it is ASCII (so \" does not close the string); a
  // non-ASCII byte after it is still decoded and checked.
  const auto escaped_ascii = [&]() -> std::size_t {
    return k + 1 < text.size() && text[k + 1] != '\n' && static_cast<unsigned char>(text[k + 1]) < 0x80u ? 1 : 0;
  };
  const char ch = text[k];
  LexStep step;
  switch (state) {
    case TomlLexeme::comment:
      step.comment = true;
      break;
    case TomlLexeme::plain:
      if (ch == '#') {
        state = TomlLexeme::comment;
        step.comment = true;
      } else if (starts("\"\"\"")) {
        state = TomlLexeme::multiline_basic;
        step.skip = 2;
      } else if (starts("'''")) {
        state = TomlLexeme::multiline_literal;
        step.skip = 2;
      } else if (ch == '"') {
        state = TomlLexeme::basic;
      } else if (ch == '\'') {
        state = TomlLexeme::literal;
      }
      break;
    case TomlLexeme::basic:
      if (ch == '\\') step.skip = escaped_ascii();
      else if (ch == '"') state = TomlLexeme::plain;
      break;
    case TomlLexeme::literal:
      if (ch == '\'') state = TomlLexeme::plain;
      break;
    case TomlLexeme::multiline_basic:
      if (ch == '\\') {
        step.skip = escaped_ascii();
      } else if (starts("\"\"\"")) {
        state = TomlLexeme::plain;
        step.skip = 2;
      }
      break;
    case TomlLexeme::multiline_literal:
      if (starts("'''")) {
        state = TomlLexeme::plain;
        step.skip = 2;
      }
      break;
  }
  return step;
}

// The code point of the two- or three-byte UTF-8 sequence starting at k; 0 for any other byte
// sequence (none of the code points toml++ misreads takes four bytes).
unsigned code_point_at(const std::string& text, std::size_t k) {
  const auto b0 = static_cast<unsigned char>(text[k]);
  const auto cont = [&](std::size_t i) {
    return i < text.size() && (static_cast<unsigned char>(text[i]) & 0xC0u) == 0x80u;
  };
  if ((b0 & 0xE0u) == 0xC0u && cont(k + 1)) return ((b0 & 0x1Fu) << 6) | (static_cast<unsigned char>(text[k + 1]) & 0x3Fu);
  if ((b0 & 0xF0u) == 0xE0u && cont(k + 1) && cont(k + 2))
    return ((b0 & 0x0Fu) << 12) | ((static_cast<unsigned char>(text[k + 1]) & 0x3Fu) << 6) |
           (static_cast<unsigned char>(text[k + 2]) & 0x3Fu);
  return 0;
}

void refuse_unreadable_characters(const std::string& text, const std::string& file) {
  std::size_t line = 1, line_start = 0;
  TomlLexeme state = TomlLexeme::plain;
  for (std::size_t k = 0; k < text.size(); ++k) {
    if (text[k] == '\n') {
      ++line;
      line_start = k + 1;
      if (state != TomlLexeme::multiline_basic && state != TomlLexeme::multiline_literal) state = TomlLexeme::plain;
      continue;
    }
    const LexStep step = advance_lexeme(text, k, state);
    if (step.comment) continue;
    if (static_cast<unsigned char>(text[k]) < 0x80u) {
      k += step.skip;
      continue;
    }
    const unsigned cp = code_point_at(text, k);
    if (unsafe_for_toml(cp))
      throw SceneError(fmt::format("{}:{}:{}: the character U+{:04X} cannot be read safely by the TOML library "
                                   "(toml++ 3.3) outside a comment; write it in ASCII or move it into a # comment",
                                   file, line, k - line_start + 1, cp));
  }
}

// The scene text as TOML with the --set overrides applied; text the TOML library would misread
// is refused first, naming its line.
toml::table parse_scene_toml(const std::string& text, const std::string& file, const SceneOverrides& overrides) {
  refuse_malformed_headers(text, file);
  refuse_unreadable_characters(text, file);
  toml::table root;
  try {
    root = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    throw SceneError(fmt::format("{}: TOML syntax error: {}", where(file, e.source()), e.description()));
  }
  for (const auto& o : overrides) apply_override(root, o);
  return root;
}

void refuse_unknown_sections(const toml::table& root, const std::string& file) {
  static const std::vector<std::string> sections = {"simulation", "material", "output", "generator", "contact",
                                                    "bond",       "wall",     "stop",   "analysis", "grip",
                                                    "body",       "material_pair"};
  for (auto&& [k, v] : root) {
    const std::string key(k.str());
    if (std::find(sections.begin(), sections.end(), key) != sections.end()) continue;
    const std::string hint = closest_match(key, sections);
    throw SceneError(fmt::format("{}: unknown section '{}'{}; valid: {}", where(file, v.source()), key,
                                 hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint),
                                 fmt::join(sections, ", ")));
  }
}

void read_simulation_section(const toml::table& root, const std::string& file, Scene& scene) {
  Section sim(root["simulation"].as_table(), file, "simulation");
  if (!sim.present()) throw SceneError(fmt::format("{}: missing [simulation] section (duration, dt, seed)", file));
  scene.dt = sim.number_or_auto("dt");
  scene.duration = sim.number("duration", 0, 0, 1e300, "s");
  if (scene.duration <= 0) sim.fail("duration", "is missing or zero: the simulated time span in s");
  scene.seed = static_cast<std::uint64_t>(sim.number("seed", 1, 0, 9.0e15));
  scene.gravity = sim.vec3("gravity", Vec3::Zero());
  scene.skin = sim.number("skin", 0, 0, 1e300, "m");
  scene.global_damping = sim.number("global_damping", 0, 0, 0.99);
  scene.settle_time = sim.number("settle_time", 0, 0, 1e300, "s");
  scene.settle_damping = sim.number("settle_damping", 0.5, 0, 0.99);
  scene.breakage = sim.flag("breakage", true);
  scene.bonded_contacts = sim.flag("bonded_contacts", true);
  sim.finish();
}

// [output] and [analysis]; the intervals default to fractions of the duration, so [simulation] is read first.
void read_output_sections(const toml::table& root, const std::string& file, Scene& scene) {
  Section out(root["output"].as_table(), file, "output");
  scene.output_file = out.text("file", "run.h5");
  // A bare .h5 name: the .xmf index and the checkpoint are named after it in the same folder.
  if (scene.output_file.find('/') != std::string::npos || std::filesystem::path(scene.output_file).extension() != ".h5")
    out.fail("file", fmt::format("= '{}' is not a run file name: use a file name ending in .h5, e.g. \"run.h5\" (the "
                                 "folder is chosen with --out)",
                                 scene.output_file));
  scene.frame_interval = out.number("frame_interval", 0, 0, 1e300, "s");
  scene.series_interval = out.number("series_interval", 0, 0, 1e300, "s");
  out.finish();
  if (scene.frame_interval <= 0) scene.frame_interval = scene.duration / 50;
  if (scene.series_interval <= 0) scene.series_interval = scene.duration / 2000;

  Section analysis(root["analysis"].as_table(), file, "analysis");
  scene.fragments_every = static_cast<int>(analysis.number("fragments_every", 1, 0, 1e9));
  analysis.finish();
}

// The [contact] and [bond] plugins chosen, with their parameters.
void read_plugin_sections(const toml::table& root, const std::string& file, const PluginHost& host, Scene& scene) {
  if (root["contact"].as_table())
    scene.contact = plugin_choice(root["contact"].as_table(), file, "contact", PluginKind::Contact, host);
  if (const auto* bond = root["bond"].as_table()) {
    // One switch turns breakage off for the whole scene: [simulation] breakage. The bond
    // plugin's own flag of the same name is no scene key (two switches could disagree).
    if (const toml::node* flag = bond->get("breakage"))
      throw SceneError(fmt::format("{}: [bond] breakage is not a scene key; breakage has one switch, [simulation] "
                                   "breakage = false (or --set simulation.breakage=false)",
                                   where(file, flag->source())));
    scene.bond = plugin_choice(bond, file, "bond", PluginKind::Bond, host);
  }
}

// The [[wall]] entries into scene.walls; returns the material each names, parallel to scene.walls
// (read with the materials later, which need the walls).
std::vector<scene_detail::WallMaterial> read_walls(const toml::table& root, const std::string& file, Scene& scene) {
  std::vector<scene_detail::WallMaterial> wall_materials;
  if (const auto* walls = root["wall"].as_array()) {
    std::size_t k = 0;
    for (const auto& w : *walls) {
      const auto* t = w.as_table();
      if (!t) throw SceneError(fmt::format("{}: [[wall]] entries must be tables", where(file, w.source())));
      Wall wall = read_wall(*t, file, scene.dir, k++, wall_materials.emplace_back());
      // Each wall has its own series in the run file, found by name (and --set wall.NAME.key).
      for (const auto& earlier : scene.walls)
        if (earlier.name == wall.name) {
          const toml::node* name = t->get("name");
          throw SceneError(fmt::format("{}: [wall] name '{}' is used by two walls; give each [[wall]] its own name",
                                       where(file, name ? name->source() : t->source()), wall.name));
        }
      scene.walls.push_back(std::move(wall));
    }
  } else if (root.contains("wall")) {
    throw SceneError(fmt::format("{}: walls are an array of tables: write [[wall]], not [wall]",
                                 where(file, root["wall"].node()->source())));
  }
  return wall_materials;
}

void read_grips(const toml::table& root, const std::string& file, Scene& scene) {
  if (const auto* grips = root["grip"].as_array()) {
    for (const auto& g : *grips) {
      const auto* t = g.as_table();
      if (!t) throw SceneError(fmt::format("{}: [[grip]] entries must be tables", where(file, g.source())));
      Section gs(t, file, "grip");
      Grip grip;
      grip.name = gs.text("name", fmt::format("grip{}", scene.grips.size()));
      grip.min_corner = gs.vec3("min_corner", Vec3::Zero());
      grip.max_corner = gs.vec3("max_corner", Vec3::Zero());
      grip.velocity = gs.vec3("velocity", Vec3::Zero());
      if (!(grip.min_corner.array() < grip.max_corner.array()).all())
        gs.fail("max_corner", "must exceed min_corner in x, y and z (the box of gripped particle centres, m)");
      gs.finish();
      scene.grips.push_back(grip);
    }
  } else if (root.contains("grip")) {
    throw SceneError(fmt::format("{}: grips are an array of tables: write [[grip]], not [grip]",
                                 where(file, root["grip"].node()->source())));
  }
}

// [stop]: its load walls must be walls of the scene, so the walls are read first.
void read_stop_section(const toml::table& root, const std::string& file, Scene& scene) {
  Section stop(root["stop"].as_table(), file, "stop");
  scene.stop.load_walls = stop.strings("load_walls");
  scene.stop.load_direction = stop.vec3("load_direction", -Vec3::UnitZ());
  if (scene.stop.load_direction.norm() == 0) stop.fail("load_direction", "must not be the zero vector");
  scene.stop.load_direction.normalize();
  scene.stop.after_peak_fraction = stop.number("after_peak_fraction", 0, 0, 1);
  scene.stop.max_displacement = stop.number("max_displacement", 0, 0, 1e300, "m");
  read_rest_rule(stop, scene);
  stop.finish();
  for (const auto& name : scene.stop.load_walls) {
    bool found = false;
    std::vector<std::string> names;
    for (const auto& w : scene.walls) {
      names.push_back(w.name);
      found = found || w.name == name;
    }
    if (!found) {
      const std::string hint = closest_match(name, names);
      throw SceneError(fmt::format("{}: [stop] load_walls names '{}', which is no [[wall]]{}", stop.at("load_walls"),
                                   name, hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint)));
    }
  }
}

}  // namespace

Scene load_scene_text(const std::string& text, const std::filesystem::path& file_path, const PluginHost& host,
                      const SceneOverrides& overrides) {
  const std::string file = file_path.string();
  const toml::table root = parse_scene_toml(text, file, overrides);
  refuse_unknown_sections(root, file);

  Scene scene;
  scene.file = file_path;
  scene.dir = file_path.has_parent_path() ? file_path.parent_path() : std::filesystem::path(".");
  std::ostringstream resolved;
  resolved << root;
  scene.resolved_text = resolved.str();

  // The order of the sections is the order of the checks: each reads what the earlier ones filled.
  read_simulation_section(root, file, scene);
  read_output_sections(root, file, scene);
  scene.bodies = read_bodies(root, file, host);
  read_plugin_sections(root, file, host, scene);
  const std::vector<scene_detail::WallMaterial> wall_materials = read_walls(root, file, scene);
  read_grips(root, file, scene);
  scene_detail::check_material_overrides(overrides, host, scene);
  scene_detail::read_materials(root, file, host, wall_materials, scene);
  read_stop_section(root, file, scene);
  return scene;
}

}  // namespace shard
