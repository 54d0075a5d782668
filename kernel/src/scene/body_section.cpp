#include "body_section.hpp"

#include <fmt/format.h>

#include "scene_section.hpp"

namespace shard::scene_detail {
namespace {

BodyStream read_stream(Section& s, const toml::table& t) {
  BodyStream stream;
  const double copies = s.number("copies", 0, 1, 1e7);
  if (copies != static_cast<double>(static_cast<std::size_t>(copies)))
    s.fail("copies", "must be a whole number of bodies, e.g. 6");
  if (!t.contains("copies")) s.fail("copies", "is missing: the number of copies the stream places, e.g. 6");
  stream.copies = static_cast<std::size_t>(copies);
  stream.region_min = s.vec3("region_min", Vec3::Zero());
  stream.region_max = s.vec3("region_max", Vec3::Zero());
  stream.in_region = t.contains("region_min") || t.contains("region_max");
  if (stream.in_region) {
    if (!(stream.region_min.array() <= stream.region_max.array()).all() || !t.contains("region_min") ||
        !t.contains("region_max"))
      s.fail("region_max", "needs region_min too and must not lie below it in x, y or z (the box of the copies' "
                           "centres of mass, m)");
    for (const char* key : {"start", "spacing", "jitter"})
      if (t.contains(key))
        s.fail(key, "is given with a region, which places the copies itself; use start/spacing/jitter or "
                    "region_min/region_max");
    stream.random_orientation = s.flag("random_orientation", false);
    stream.speed_scatter = s.number("speed_scatter", 0, 0, 1);
    stream.seed = static_cast<std::uint64_t>(s.number("seed", 1, 0, 9.0e15));
    s.allow("start");
    s.allow("spacing");
    s.allow("jitter");
    s.finish();
    return stream;
  }
  stream.start = s.vec3("start", Vec3::Zero());
  if (!t.contains("start"))
    s.fail("start", "is missing: the centre of mass of the first copy in m, e.g. [0, 0, 0.1] (or give "
                    "region_min and region_max)");
  stream.spacing = s.vec3("spacing", Vec3::Zero());
  if (stream.copies > 1 && stream.spacing.norm() == 0)
    s.fail("spacing", "is missing or zero: copy k goes to start + k spacing (m), e.g. [0.05, 0, 0]");
  stream.jitter = s.vec3("jitter", Vec3::Zero());
  if ((stream.jitter.array() < 0).any()) s.fail("jitter", "must not be negative: the half-width of the offset per axis, m");
  stream.random_orientation = s.flag("random_orientation", false);
  stream.speed_scatter = s.number("speed_scatter", 0, 0, 1);
  stream.seed = static_cast<std::uint64_t>(s.number("seed", 1, 0, 9.0e15));
  s.finish();
  return stream;
}

BodySpec read_body(const toml::table& t, const std::string& file, std::size_t index, const PluginHost& host) {
  Section s(&t, file, "body");
  BodySpec body;
  body.where = s.at();
  body.name = s.text("name", fmt::format("body{}", index));
  if (body.name.empty() || body.name.find('/') != std::string::npos)
    s.fail("name", fmt::format("= '{}' cannot name a body: use a non-empty name without '/', e.g. \"plate\"", body.name));
  if (t.contains("position")) body.placement.position = s.vec3("position", Vec3::Zero());
  else s.allow("position");  // still a valid key for the closest-match hint
  body.placement.rotation_axis = s.vec3("rotation_axis", Vec3::UnitZ());
  if (body.placement.rotation_axis.norm() == 0) s.fail("rotation_axis", "must not be the zero vector");
  body.placement.rotation_angle = s.number("rotation_angle", 0, -360, 360, "degrees");
  body.placement.velocity = s.vec3("velocity", Vec3::Zero());
  body.placement.angular_velocity = s.vec3("angular_velocity", Vec3::Zero());
  body.material_name = s.text("material", "");  // resolved with the materials (material_section.cpp)
  body.material_where = s.at("material");
  s.allow("generator");
  s.allow("stream");
  s.finish();

  const toml::node* generator = t.get("generator");
  if (!generator || !generator->as_table())
    throw SceneError(fmt::format("{}: [[body]] '{}' has no [body.generator] table; add one after the entry, e.g. "
                                 "[body.generator] plugin = \"stl_fill\" ...",
                                 body.where, body.name));
  body.generator = plugin_choice(generator->as_table(), file, "body.generator", PluginKind::Generator, host);

  if (const toml::node* stream = t.get("stream")) {
    if (!stream->as_table())
      throw SceneError(fmt::format("{}: [body] stream must be a table: write [body.stream] after the [[body]] entry",
                                   where(file, stream->source())));
    Section ss(stream->as_table(), file, "body.stream");
    if (body.placement.position)
      s.fail("position", "is given with a [body.stream], which places the copies from stream.start; remove one");
    body.stream = read_stream(ss, *stream->as_table());
    for (const char* key : {"rotation_angle", "rotation_axis"})
      if (body.stream->random_orientation && t.contains(key))
        s.fail(key, "is given with stream.random_orientation = true; remove one of them");
  }
  return body;
}

}  // namespace

std::vector<BodySpec> read_bodies(const toml::table& root, const std::string& file, const PluginHost& host) {
  const toml::node* generator = root.get("generator");
  const toml::node* bodies = root.get("body");
  if (generator && bodies)
    throw SceneError(fmt::format("{}: the scene has both a [generator] section and [[body]] entries (first at {}); "
                                 "use one form: move the generator into a [[body]] entry as [body.generator], or "
                                 "remove the [[body]] entries",
                                 where(file, generator->source()), where(file, bodies->source())));
  std::vector<BodySpec> out;
  if (generator) {
    if (!generator->as_table())
      throw SceneError(fmt::format("{}: generator must be a section: write [generator]", where(file, generator->source())));
    BodySpec body;
    body.name = "body0";
    body.from_generator_section = true;
    body.generator = plugin_choice(generator->as_table(), file, "generator", PluginKind::Generator, host);
    body.where = body.generator.where;
    body.material_where = body.where;
    out.push_back(std::move(body));
    return out;
  }
  if (!bodies)
    throw SceneError(fmt::format("{}: missing [generator] section (or [[body]] entries for several bodies)", file));
  const auto* array = bodies->as_array();
  if (!array || !array->is_array_of_tables())
    throw SceneError(fmt::format("{}: bodies are an array of tables: write [[body]], not [body]",
                                 where(file, bodies->source())));
  for (const auto& entry : *array) {
    BodySpec body = read_body(*entry.as_table(), file, out.size(), host);
    for (const auto& earlier : out)
      if (earlier.name == body.name) {
        const toml::node* name = entry.as_table()->get("name");
        throw SceneError(fmt::format("{}: [body] name '{}' is used by two bodies; give each [[body]] its own name",
                                     where(file, name ? name->source() : entry.source()), body.name));
      }
    out.push_back(std::move(body));
  }
  return out;
}

}  // namespace shard::scene_detail
