// The embedded player and schema agree with the C++ enums (all three come from resources/schema/enums.json:
// this checks that the build wired them, and that the player only names constants that exist), and the
// player's modules are all in player.js, in their order.
#include "processing/export/player_assets.h"

#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "model/hotspots.h"
#include "model/keyframes.h"

namespace plenopath {
namespace {

std::string asset(const std::string& name) {
  for (const EmbeddedFile& f : player_assets())
    if (name == f.name) return std::string(reinterpret_cast<const char*>(f.data), f.size);
  ADD_FAILURE() << name << " is not embedded";
  return "";
}

template <typename E>
std::vector<std::string> cpp_ids() {
  std::vector<std::string> out;
  for (const auto& n : EnumInfo<E>::names) out.push_back(n.id);
  return out;
}

// The members of `const NAME = Object.freeze({ KEY: 'id', ... });` in player.js.
std::map<std::string, std::string> js_constants(const std::string& js, const std::string& name) {
  std::map<std::string, std::string> out;
  const std::regex block("const " + name + R"( = Object\.freeze\(\{([^}]*)\}\);)");
  std::smatch m;
  if (!std::regex_search(js, m, block)) return out;
  const std::string body = m[1];
  const std::regex member(R"(([A-Z_]+): '([a-z_]*)')");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), member); it != std::sregex_iterator(); ++it)
    out[(*it)[1]] = (*it)[2];
  return out;
}

TEST(PlayerAssets, TheSchemaListsTheCppNames) {
  const nlohmann::json schema = nlohmann::json::parse(asset("tour.schema.json"));
  const nlohmann::json& spot = schema["properties"]["hotspots"]["items"]["properties"];
  EXPECT_EQ(spot["kind"]["enum"].get<std::vector<std::string>>(), cpp_ids<HotspotKind>());
  EXPECT_EQ(spot["trigger"]["enum"].get<std::vector<std::string>>(), cpp_ids<HotspotTrigger>());
  EXPECT_EQ(spot["action"]["enum"].get<std::vector<std::string>>(), cpp_ids<HotspotAction>());
  // Hand-checked against the names the files have always used.
  EXPECT_EQ(cpp_ids<HotspotAction>(), (std::vector<std::string>{"", "swap_image", "play_video", "play_sound",
                                                                "jump", "open_url", "show_text"}));
  EXPECT_EQ(cpp_ids<HotspotTrigger>(), (std::vector<std::string>{"click", "proximity"}));
  EXPECT_EQ(cpp_ids<SamplingMethod>(), (std::vector<std::string>{"uniform", "visibility", "depth"}));
}

TEST(PlayerAssets, ThePlayerHasTheCppNamesAndUsesOnlyThose) {
  const std::string js = asset("player.js");
  const std::map<std::string, std::vector<std::string>> enums = {
      {"HotspotKind", cpp_ids<HotspotKind>()},
      {"HotspotTrigger", cpp_ids<HotspotTrigger>()},
      {"HotspotAction", cpp_ids<HotspotAction>()}};
  for (const auto& [name, ids] : enums) {
    const auto constants = js_constants(js, name);
    std::set<std::string> values;
    for (const auto& [key, id] : constants) values.insert(id);
    EXPECT_EQ(values, std::set<std::string>(ids.begin(), ids.end())) << name;
    // Every NAME.KEY the player's code uses exists.
    const std::regex use(name + R"(\.([A-Z_]+))");
    int uses = 0;
    for (auto it = std::sregex_iterator(js.begin(), js.end(), use); it != std::sregex_iterator();
         ++it, ++uses)
      EXPECT_TRUE(constants.count((*it)[1])) << name << "." << (*it)[1] << " is not defined";
    if (name != "HotspotKind") {
      EXPECT_GT(uses, 0) << name << " is never used";
    }
  }
  // The names themselves appear once, in the generated constants ('click' is also a DOM event's name).
  std::vector<std::string> once = cpp_ids<HotspotAction>();
  once.erase(once.begin());  // ''
  once.push_back("proximity");
  for (const std::string& id : once) {
    const std::string quoted = "'" + id + "'";
    const std::size_t first = js.find(quoted);
    EXPECT_NE(first, std::string::npos) << id;
    EXPECT_EQ(js.find(quoted, first + 1), std::string::npos) << id << " is spelled out beside its constant";
  }
}

TEST(PlayerAssets, ThePlayerIsItsModulesInOrder) {
  const std::string js = asset("player.js");
  std::size_t at = 0;
  for (const char* module :
       {"begin.js", "enums.js", "tour_data.js", "renderer.js", "textures.js", "multires.js", "hotspots.js",
        "walk.js", "frame_probe.js", "orientation.js", "ui.js", "end.js"}) {
    const std::size_t found = js.find(std::string("// ==== ") + module + "\n", at);
    ASSERT_NE(found, std::string::npos) << module << " missing or out of order";
    at = found;
  }
  EXPECT_EQ(js.find("'use strict';\n(function () {"), js.find("'use strict';"));
  EXPECT_EQ(js.substr(js.size() - 6), "})();\n");
  for (const char* name : {"index.html", "player.css", "player.js", "tour.schema.json"})
    EXPECT_FALSE(asset(name).empty());
}

}  // namespace
}  // namespace plenopath
