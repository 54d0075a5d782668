#include <doctest/doctest.h>

#include <string>

#include "shard/plugin_host.hpp"

using namespace shard;

TEST_CASE("the built-in plugins load from the build tree") {
  PluginHost host;
  const auto refused = host.load_directories(PluginHost::default_search_path());
  CHECK(refused.empty());
  CHECK(host.find(PluginKind::Contact, "linear_spring").info.name == "linear_spring");
  CHECK(host.find(PluginKind::Contact, "hertz_mindlin").info.kind == PluginKind::Contact);
  CHECK(host.find(PluginKind::Bond, "beam_bond").info.kind == PluginKind::Bond);
}

TEST_CASE("a plugin built against another ABI is refused with both versions and the file") {
  PluginHost host;
  const std::string file = std::string(BAD_PLUGIN_DIR) + "/shard_test_plugin_wrong_abi.so";
  CHECK_THROWS_WITH_AS(host.load_file(file),
                       doctest::Contains("plugin ABI version 999 does not match this Shard's ABI version"),
                       PluginError);
  CHECK_THROWS_WITH_AS(host.load_file(file), doctest::Contains("shard_test_plugin_wrong_abi.so"), PluginError);
}

TEST_CASE("a plugin that throws while registering is refused, and the directory scan goes on") {
  PluginHost host;
  const auto refused = host.load_directories({BAD_PLUGIN_DIR});
  REQUIRE(refused.size() == 2);
  bool saw_throw = false;
  for (const auto& r : refused) saw_throw = saw_throw || r.find("failed while registering: licence file") != std::string::npos;
  CHECK(saw_throw);
}

TEST_CASE("an unknown plugin name lists the available ones and the closest") {
  PluginHost host;
  host.load_directories(PluginHost::default_search_path());
  CHECK_THROWS_WITH_AS(host.find(PluginKind::Contact, "hertz_mindlen"), doctest::Contains("did you mean 'hertz_mindlin'"),
                       PluginError);
  CHECK_THROWS_WITH_AS(host.find(PluginKind::Contact, "nothing_like_it"), doctest::Contains("linear_spring"),
                       PluginError);
}

TEST_CASE("parameters are validated against the schema") {
  PluginHost host;
  host.load_directories(PluginHost::default_search_path());
  const auto& info = host.find(PluginKind::Contact, "hertz_mindlin").info;
  std::map<std::string, RawParam> raw;
  raw["shear_modulus"] = RawParam{-1.0, "s.toml:3:1"};
  CHECK_THROWS_WITH_AS(PluginHost::validate(info, raw, "s.toml:2:1"), doctest::Contains("s.toml:3:1: parameter 'shear_modulus'"),
                       PluginError);
  raw.clear();
  raw["sheer_modulus"] = RawParam{1e6, "s.toml:4:1"};
  CHECK_THROWS_WITH_AS(PluginHost::validate(info, raw, "s.toml:2:1"), doctest::Contains("did you mean 'shear_modulus'"),
                       PluginError);
  raw.clear();
  raw["shear_modulus"] = RawParam{std::string("soft"), "s.toml:5:1"};
  CHECK_THROWS_WITH_AS(PluginHost::validate(info, raw, "s.toml:2:1"), doctest::Contains("must be a number"), PluginError);
  raw.clear();
  const ParamSet p = PluginHost::validate(info, raw, "s.toml:2:1");
  CHECK(p.has("shear_modulus"));  // defaults filled in
}

TEST_CASE("closest_match finds near misspellings only") {
  CHECK(closest_match("youngs_modulu", {"youngs_modulus", "radius_ratio"}) == "youngs_modulus");
  CHECK(closest_match("zzz", {"youngs_modulus", "radius_ratio"}).empty());
}
