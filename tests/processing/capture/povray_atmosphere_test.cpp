// The depth passes' copy of the author's scene: fogs made invisible, media emptied, radiosity removed, and
// nothing else touched (comments, strings, identifiers that contain the words). Expected texts are written
// by hand.
#include "processing/capture/povray_atmosphere.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace plenopath {
namespace {

TEST(PovrayAtmosphere, FogsMediaAndRadiosityAreNeutralised) {
  int changed = -1;
  EXPECT_EQ(without_atmosphere("fog { fog_type 2 distance 800 color rgb <0.7, 0.8, 0.9> fog_alt 1.3 }\n"
                               "global_settings { assumed_gamma 1 radiosity { count 130 nearest_count 5 } }\n"
                               "box { 0, 1 hollow interior { media { scattering { 1, 0.1 } density { "
                               "spherical } } } }\n",
                               &changed),
            "fog { distance 1e12 }\nglobal_settings { assumed_gamma 1  }\n"
            "box { 0, 1 hollow interior { media { } } }\n");
  EXPECT_EQ(changed, 3);
  // Declared and used: both stay valid SDL.
  EXPECT_EQ(without_atmosphere("#declare Haze = fog{distance 5}\nfog { Haze }\n", &changed),
            "#declare Haze = fog { distance 1e12 }\nfog { distance 1e12 }\n");
  EXPECT_EQ(changed, 2);
  // A comment between the word and its brace.
  EXPECT_EQ(without_atmosphere("fog /* thick */ { distance 2 }", &changed), "fog { distance 1e12 }");
  EXPECT_EQ(changed, 1);
}

TEST(PovrayAtmosphere, CommentsStringsAndIdentifiersAreLeftAlone) {
  const std::string sdl =
      "// fog { distance 1 }\n"
      "/* outer /* nested fog { } */ still a comment: media { } */\n"
      "#declare show_fog = true; #declare fogged = 1; #declare My_media = 2;\n"
      "#debug \"fog { in a string } \\\" media { }\"\n"
      "#if (show_fog) #declare Foggy = 1; #end\n"
      "text { ttf \"crystal.ttf\" \"radiosity {\" 0.1, 0 }\n";
  int changed = -1;
  EXPECT_EQ(without_atmosphere(sdl, &changed), sdl);
  EXPECT_EQ(changed, 0);
  // Braces inside a block's comments and strings do not end it early.
  EXPECT_EQ(without_atmosphere("media { // } not here\n density { \"}\" } } sphere {}", &changed),
            "media { } sphere {}");
  EXPECT_EQ(changed, 1);
  // A block that never closes is left for POV-Ray to report.
  EXPECT_EQ(without_atmosphere("fog { distance 3", &changed), "fog { distance 3");
  EXPECT_EQ(changed, 0);
}

TEST(PovrayAtmosphere, TheScenesFolderIsCopiedWithoutItsAtmosphere) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("plenopath_atmosphere_" + std::to_string(::getpid()));
  fs::create_directories(dir / "scene" / "sub");
  std::ofstream(dir / "scene" / "main.pov") << "#include \"air.inc\"\nfog { distance 3 }\n";
  std::ofstream(dir / "scene" / "air.inc") << "global_settings { radiosity { } }\n";
  std::ofstream(dir / "scene" / "notes.txt") << "fog { }";
  std::ofstream(dir / "scene" / "sub" / "deep.inc") << "fog { }";
  const AtmosphereFreeScene copy =
      copy_scene_without_atmosphere((dir / "scene" / "main.pov").string(), (dir / "copy").string());
  auto read = [](const fs::path& f) {
    std::stringstream text;
    text << std::ifstream(f).rdbuf();
    return text.str();
  };
  EXPECT_EQ(fs::path(copy.scene_file), dir / "copy" / "main.pov");
  EXPECT_EQ(copy.blocks_changed, 2);
  EXPECT_EQ(read(dir / "copy" / "main.pov"), "#include \"air.inc\"\nfog { distance 1e12 }\n");
  EXPECT_EQ(read(dir / "copy" / "air.inc"), "global_settings {  }\n");
  EXPECT_FALSE(fs::exists(dir / "copy" / "notes.txt"));  // only scene files; POV-Ray finds the rest
  EXPECT_FALSE(fs::exists(dir / "copy" / "sub"));
  EXPECT_EQ(read(dir / "scene" / "main.pov"), "#include \"air.inc\"\nfog { distance 3 }\n");  // untouched
  fs::remove_all(dir);
}

}  // namespace
}  // namespace plenopath
