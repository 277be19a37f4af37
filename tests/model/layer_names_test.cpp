// Layer names as CAD programs and offices write them, with the vote a person reading them would give.
#include "model/layer_names.h"

#include <gtest/gtest.h>

#include "model/floor_plan.h"

namespace plenopath {
namespace {

struct NamedVote {
  const char* name;
  int vote;
};

void expect_votes(const std::vector<NamedVote>& table) {
  for (const NamedVote& row : table) {
    std::string reason;
    EXPECT_EQ(occluder_vote_from_name(row.name, &reason), row.vote) << row.name << " (" << reason << ")";
    EXPECT_FALSE(reason.empty()) << row.name;
  }
}

TEST(LayerNames, AiaNcs) {
  expect_votes({
      {"A-WALL", 1},       {"A-WALL-FULL", 1},  {"A-WALL-EXST", 1},  {"A-WALL-NEWW", 1},  {"I-WALL", 1},
      {"S-WALL", 1},       {"S-COLS", 1},       {"A-COLS", 1},       {"A-Wall", 1},       {"a-wall-full", 1},
      {"A-WALL-PRHT", 0},  {"A-WALL-DEMO", 0},  {"A-WALL-PATT", -1}, {"A-WALL-IDEN", -1}, {"A-WALL-CNTR", -1},
      {"A-DOOR", -1},      {"A-DOOR-IDEN", -1}, {"A-GLAZ", -1},      {"A-GLAZ-CWMG", -1}, {"A-FLOR-STRS", -1},
      {"A-FLOR-CASE", -1}, {"A-FLOR-RAIL", -1}, {"A-FURN", -1},      {"A-ANNO-TEXT", -1}, {"A-ANNO-DIMS", -1},
      {"A-DIMS", -1},      {"A-GRID", -1},      {"S-GRID", -1},      {"A-AREA", -1},      {"A-AREA-IDEN", -1},
      {"A-HATCH", -1},     {"A-PATT", -1},      {"A-CLNG", -1},      {"S-BEAM", -1},      {"E-LITE", -1},
      {"M-HVAC-DUCT", -1}, {"P-FIXT", -1},      {"E-POWR", -1},      {"A-EQPM", -1},
  });
}

TEST(LayerNames, Iso13567) {
  // Agent (2), element (6), presentation (2): CI/SfB two-digit codes, DIN 276 and NS 3451 three-digit ones.
  expect_votes({
      {"A-21----E-", 1},   // CI/SfB (21) external walls
      {"A-22----E-", 1},   // CI/SfB (22) internal walls
      {"S-28----E-", 1},   // CI/SfB (28) frames
      {"A-31----E-", -1},  // CI/SfB (31) external wall openings
      {"A-32----E-", -1},  // CI/SfB (32) internal doors
      {"A-82----E-", -1},  // CI/SfB (82) loose furniture
      {"A-23----E-", 0},   // CI/SfB (23) floors
      {"A-21----T-", -1},  // text of the walls
      {"A-21----H-", -1},  // hatching of the walls
      {"A-21----D-", -1},  // dimensions of the walls
      {"A-331---E-", 1},   // DIN 276 load-bearing external walls
      {"A-333---E-", 1},   // DIN 276 external columns
      {"A-342---E-", 1},   // DIN 276 non-load-bearing internal walls
      {"A-344---E-", -1},  // DIN 276 internal doors and windows
      {"A--2310-E", 1},    // NS 3451 231 load-bearing external walls
      {"A-222---E-", 1},   // NS 3451 222 columns
      {"A-234---E-", -1},  // NS 3451 windows, doors
      {"A-24100-E-N", 1},  // NS 3451 241 internal walls, status N (new)
  });
}

TEST(LayerNames, CommonEnglishAndSoftwareDefaults) {
  expect_votes({
      {"WALLS", 1},
      {"Walls", 1},
      {"wall", 1},
      {"WALL_1", 1},
      {"Exterior Walls", 1},
      {"Partition", 1},
      {"PARTITIONS", 1},
      {"Columns", 1},
      {"COLUMN", 1},
      {"PILLARS", 1},
      {"Structure", 1},
      {"STRUCTURAL", 1},
      {"Core", 1},
      {"Facade", 1},
      {"S-COL", 1},
      {"Structural - Bearing", 1},
      {"Interior - Partition", 1},
      {"WALLHATCH", -1},
      {"0", 0},
      {"", 0},
      {"Defpoints", -1},
      {"Layer1", 0},
      {"Misc", 0},
      {"COLOR", 0},
      {"COLLAB", 0},
      {"Colour 3", 0},
      {"WALLPAPER", -1},
      {"WALL-HATCH", -1},
      {"WALL_DIM", -1},
      {"Wall-Text", -1},
      {"WallText", -1},
      {"DOORS", -1},
      {"Door", -1},
      {"Windows", -1},
      {"FURNITURE", -1},
      {"TEXT", -1},
      {"Dimensions", -1},
      {"DIM", -1},
      {"Hatch", -1},
      {"GRID", -1},
      {"Glass wall", -1},
      {"Curtain Wall", -1},
      {"Stairs", -1},
      {"VIEWPORT", -1},
      {"Title Block", -1},
      {"Room Names", -1},
      {"Partial Walls", 0},
  });
}

TEST(LayerNames, German) {
  expect_votes({
      {"Wand", 1},       {"Wände", 1},        {"WÄNDE", 1},          {"Waende", 1},      {"Wand (neu)", 1},
      {"Außenwand", 1},  {"AUSSENWAENDE", 1}, {"Innenwände", 1},     {"Trennwand", 1},   {"Mauerwerk", 1},
      {"Stütze", 1},     {"Stützen", 1},      {"STUETZEN", 1},       {"Tragwerk", 1},    {"Beton", 1},
      {"Stahlbeton", 1}, {"Struktur", 1},     {"Wand (Abbruch)", 0}, {"Tür", -1},        {"Türen", -1},
      {"Innentür", -1},  {"Fenster", -1},     {"Möbel", -1},         {"Möblierung", -1}, {"Bemaßung", -1},
      {"Text", -1},      {"Schraffur", -1},   {"Wandschraffur", -1}, {"Achsen", -1},     {"Treppe", -1},
      {"Leinwand", 0},
  });
}

TEST(LayerNames, FrenchSpanishItalianDutchPortugueseRussian) {
  expect_votes({
      // French
      {"MUR", 1},
      {"Murs", 1},
      {"Cloisons", 1},
      {"Poteaux", 1},
      {"Voiles", 1},
      {"Mur porteur", 1},
      {"Maçonnerie", 1},
      {"Portes", -1},
      {"Fenêtres", -1},
      {"FENETRE", -1},
      {"Mobilier", -1},
      {"Cotation", -1},
      {"Texte", -1},
      {"Hachures", -1},
      {"Mur rideau", -1},
      // Spanish
      {"Muros", 1},
      {"MURO", 1},
      {"Pared", 1},
      {"Paredes", 1},
      {"Tabiques", 1},
      {"Columnas", 1},
      {"Pilares", 1},
      {"Estructura", 1},
      {"Puertas", -1},
      {"Ventanas", -1},
      {"Mobiliario", -1},
      {"Cotas", -1},
      {"Textos", -1},
      {"Planta baja", 0},
      // Italian
      {"Muri", 1},
      {"Pareti", 1},
      {"Pilastri", 1},
      {"Tramezzi", 1},
      {"Muratura", 1},
      {"Porte", -1},
      {"Finestre", -1},
      {"Arredi", -1},
      {"Quote", -1},
      // Dutch
      {"Wanden", 1},
      {"Muur", 1},
      {"Binnenwand", 1},
      {"Kolommen", 1},
      {"Gevel", 1},
      {"Deuren", -1},
      {"Ramen", -1},
      {"Meubilair", -1},
      {"Maatvoering", -1},
      {"Tekst", -1},
      // Portuguese, Russian
      {"Paredes externas", 1},
      {"Alvenaria", 1},
      {"Janelas", -1},
      {"Стены", 1},
      {"СТЕНЫ", 1},
      {"Колонны", 1},
      {"Двери", -1},
      {"Окна", -1},
      {"Мебель", -1},
      {"Размеры", -1},
  });
}

TEST(LayerNames, ChineseTArchJapaneseKorean) {
  expect_votes({
      // Chinese and 天正/TArch defaults
      {"墙", 1},
      {"墙体", 1},
      {"外墙", 1},
      {"柱", 1},
      {"柱子", 1},
      {"门", -1},
      {"窗", -1},
      {"门窗", -1},
      {"家具", -1},
      {"标注", -1},
      {"文字", -1},
      {"填充", -1},
      {"墙体填充", -1},
      {"幕墙", -1},
      {"轴线", -1},
      {"WALL", 1},
      {"COLUMN", 1},
      {"DOOR_FIRE", -1},
      {"WINDOW", -1},
      {"WINDOW_TEXT", -1},
      {"DIM_LEAD", -1},
      {"DIM_SYMB", -1},
      {"DIM_ELEV", -1},
      {"PUB_TEXT", -1},
      {"PUB_HATCH", -1},
      {"PUB_DIM", -1},
      {"AXIS", -1},
      {"STAIR", -1},
      {"CURTWALL", -1},
      {"WALL-MOVE", 1},
      // Japanese
      {"壁", 1},
      {"外壁", 1},
      {"間仕切壁", 1},
      {"柱", 1},
      {"建具", -1},
      {"扉", -1},
      {"窓", -1},
      {"家具", -1},
      {"寸法", -1},
      {"文字", -1},
      {"壁紙", -1},
      {"通り芯", -1},
      // Korean
      {"벽", 1},
      {"기둥", 1},
      {"문", -1},
      {"창호", -1},
  });
}

TEST(LayerNames, XrefBoundNamesAreJudgedByTheirOwnPart) {
  expect_votes({
      {"ARCH$0$A-WALL", 1},
      {"ARCH|A-WALL", 1},
      {"ARCH$0$A-DOOR", -1},
      {"WALLS$0$TEXT", -1},
      {"base-plan$12$Wände", 1},
      {"Site|ARCH$0$S-COLS", 1},
      {"TEXT|A-WALL-FULL", 1},
      {"ARCH$0$0", 0},
      {"$0$", 0},
      {"|", 0},
  });
}

TEST(LayerNames, OddBytesAreSafe) {
  // Invalid UTF-8 and control bytes say nothing, and never throw.
  EXPECT_EQ(occluder_vote_from_name(std::string("\xff\xfe\x80", 3)), 0);
  // cp1252 "Wände" not yet converted to UTF-8: the stray byte splits it into "W" and "nde".
  EXPECT_EQ(occluder_vote_from_name(std::string("W\xe4nde", 5)), 0);
  EXPECT_EQ(occluder_vote_from_name(std::string("A-WALL\x01", 7)), 1);
}

TEST(LayerNames, MentionsOfWallsUnderAPattern) {
  for (const char* name : {"A-WALL-PATT", "Wandschraffur", "A-21----H-", "墙体填充", "WALL-HATCH", "A-WALL"})
    EXPECT_TRUE(name_mentions_occluder(name)) << name;
  for (const char* name : {"A-ANNO-PATT", "HATCH", "0", "A-31----H-", "Schraffur", "COLOR"})
    EXPECT_FALSE(name_mentions_occluder(name)) << name;
}

TEST(LayerNames, GuessIsTheVote) {
  for (const char* name : {"A-WALL", "Wand (neu)", "墙", "ARCH$0$A-WALL", "A-21----E-"})
    EXPECT_TRUE(guess_layer_is_occluder(name)) << name;
  for (const char* name : {"0", "A-WALL-PRHT", "A-DOOR", "WALLPAPER", "COLOR"})
    EXPECT_FALSE(guess_layer_is_occluder(name)) << name;
}

}  // namespace
}  // namespace plenopath
