#include "model/layer_names.h"

#include <cctype>
#include <cstdint>
#include <vector>

namespace plenopath {
namespace {

// ---------------------------------------------------------------------------------------------------------
// Normalising a name: UTF-8 decoded, Latin letters folded to lower-case ASCII without accents (ä -> a,
// ß -> ss, œ -> oe), Cyrillic to lower case, CJK and kana kept as they are. Anything that is not a letter or
// digit separates words, and so do lower->upper case steps ("WallText") and letter<->digit steps ("WALL2").

enum class CharKind { separator, digit, latin, other_letter };

void append_utf8(char32_t c, std::string* out) {
  if (c < 0x80) {
    out->push_back(static_cast<char>(c));
  } else if (c < 0x800) {
    out->push_back(static_cast<char>(0xC0 | (c >> 6)));
    out->push_back(static_cast<char>(0x80 | (c & 0x3F)));
  } else if (c < 0x10000) {
    out->push_back(static_cast<char>(0xE0 | (c >> 12)));
    out->push_back(static_cast<char>(0x80 | ((c >> 6) & 0x3F)));
    out->push_back(static_cast<char>(0x80 | (c & 0x3F)));
  } else {
    out->push_back(static_cast<char>(0xF0 | (c >> 18)));
    out->push_back(static_cast<char>(0x80 | ((c >> 12) & 0x3F)));
    out->push_back(static_cast<char>(0x80 | ((c >> 6) & 0x3F)));
    out->push_back(static_cast<char>(0x80 | (c & 0x3F)));
  }
}

// Code points of `s`; a byte that does not start a valid sequence becomes U+FFFD (a separator).
std::vector<char32_t> decode_utf8(const std::string& s) {
  std::vector<char32_t> out;
  out.reserve(s.size());
  std::size_t i = 0;
  while (i < s.size()) {
    const unsigned char b = static_cast<unsigned char>(s[i]);
    const int extra = b < 0x80 ? 0 : (b >> 5) == 0x6 ? 1 : (b >> 4) == 0xE ? 2 : (b >> 3) == 0x1E ? 3 : -1;
    char32_t c = extra == 0 ? b : extra == 1 ? (b & 0x1F) : extra == 2 ? (b & 0x0F) : (b & 0x07);
    bool ok = extra >= 0 && i + static_cast<std::size_t>(extra) < s.size();
    for (int k = 1; ok && k <= extra; ++k) {
      const unsigned char cb = static_cast<unsigned char>(s[i + k]);
      ok = (cb & 0xC0) == 0x80;
      c = (c << 6) | (cb & 0x3F);
    }
    if (!ok) {
      out.push_back(0xFFFD);
      ++i;
    } else {
      out.push_back(c);
      i += 1 + static_cast<std::size_t>(extra);
    }
  }
  return out;
}

// Latin-1 Supplement and Latin Extended-A letters without their accents, in lower case; nullptr otherwise.
const char* fold_latin(char32_t c) {
  static const char* const latin1[64] = {
      "a", "a", "a", "a", "a", "a", "ae", "c",     "e", "e", "e", "e", "i", "i", "i",  "i",   // C0-CF
      "d", "n", "o", "o", "o", "o", "o",  nullptr, "o", "u", "u", "u", "u", "y", "th", "ss",  // D0-DF
      "a", "a", "a", "a", "a", "a", "ae", "c",     "e", "e", "e", "e", "i", "i", "i",  "i",   // E0-EF
      "d", "n", "o", "o", "o", "o", "o",  nullptr, "o", "u", "u", "u", "u", "y", "th", "y"};  // F0-FF
  if (c >= 0xC0 && c <= 0xFF) return latin1[c - 0xC0];
  if (c >= 0x100 && c <= 0x17F) {
    if (c == 0x132 || c == 0x133) return "ij";
    if (c == 0x152 || c == 0x153) return "oe";
    // Base letter of each code point U+0100..U+017F ('?' = the two handled above).
    static const char base[] =
        "aaaaaaccccccccddddeeeeeeeeeegggggggghhhhiiiiiiiiii??jjkkkllllllllllnnnnnnnnnoooooo??rrrrrrssssssss"
        "ttttttuuuuuuuuuuuuwwyyyzzzzzzs";
    static_assert(sizeof(base) - 1 == 128, "one letter per code point");
    static const char* const letters[26] = {"a", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k", "l", "m",
                                            "n", "o", "p", "q", "r", "s", "t", "u", "v", "w", "x", "y", "z"};
    const char l = base[c - 0x100];
    if (l >= 'a' && l <= 'z') return letters[l - 'a'];
  }
  return nullptr;
}

bool is_cjk_or_kana_or_hangul(char32_t c) {
  return (c >= 0x3040 && c <= 0x30FF) ||  // hiragana, katakana
         (c >= 0x3400 && c <= 0x4DBF) ||  // CJK extension A
         (c >= 0x4E00 && c <= 0x9FFF) ||  // CJK unified ideographs
         (c >= 0xAC00 && c <= 0xD7AF) ||  // Hangul syllables
         (c >= 0xF900 && c <= 0xFAFF) ||  // CJK compatibility ideographs
         (c >= 0xFF66 && c <= 0xFF9F);    // half-width katakana
}

// Words of the name, folded. CJK text stays one word per run (those scripts do not separate words).
std::vector<std::string> words_of(const std::string& name) {
  std::vector<std::string> words;
  std::string current;
  CharKind previous = CharKind::separator;
  bool previous_lower = false;
  auto flush = [&]() {
    if (!current.empty()) words.push_back(current);
    current.clear();
  };
  for (char32_t c : decode_utf8(name)) {
    CharKind kind = CharKind::separator;
    std::string folded;
    bool upper = false, lower = false;
    if (c < 0x80) {
      const unsigned char b = static_cast<unsigned char>(c);
      if (std::isdigit(b)) {
        kind = CharKind::digit;
        folded.push_back(static_cast<char>(b));
      } else if (std::isalpha(b)) {
        kind = CharKind::latin;
        upper = std::isupper(b) != 0;
        lower = !upper;
        folded.push_back(static_cast<char>(std::tolower(b)));
      }
    } else if (const char* f = fold_latin(c)) {
      kind = CharKind::latin;
      upper = c < 0xDF;  // Latin-1 capitals; Latin Extended-A counts as lower case (no case steps)
      lower = !upper;
      folded = f;
    } else if (c >= 0x410 && c <= 0x44F) {  // Cyrillic А-я (and Ё/ё below)
      kind = CharKind::other_letter;
      append_utf8(c < 0x430 ? c + 0x20 : c, &folded);
    } else if (c == 0x401 || c == 0x451) {
      kind = CharKind::other_letter;
      append_utf8(0x435, &folded);  // ё -> е
    } else if (is_cjk_or_kana_or_hangul(c)) {
      kind = CharKind::other_letter;
      append_utf8(c, &folded);
    }
    if (kind == CharKind::separator) {
      flush();
    } else {
      const bool case_step =
          previous == CharKind::latin && kind == CharKind::latin && previous_lower && upper;
      const bool kind_step = previous != CharKind::separator && previous != kind;
      if (case_step || kind_step) flush();
      current += folded;
    }
    previous = kind;
    previous_lower = lower;
  }
  flush();
  return words;
}

// ---------------------------------------------------------------------------------------------------------
// The vocabulary. Keys are folded (lower case, no accents). `exact`: the whole word; `prefix`: the word
// starts with the key ("partitions"); `contains`: anywhere in the word, for languages that compound
// ("Außenwand", "Wandschraffur", "外墙"); `suffix`: the word ends with it ("Innentür").

enum class Match { exact, prefix, contains, suffix };

struct Term {
  const char* key;
  Match match;
  int vote;  // +1 blocks sight, -1 does not, 0 neutralises a +1 (partial height, demolition)
  const char* reason;
  const char* unless;  // the term does not count in a word that contains this ("struktur" for "tur")
};

constexpr Match E = Match::exact, P = Match::prefix, C = Match::contains, S = Match::suffix;

const std::vector<Term>& vocabulary() {
  static const std::vector<Term> terms = {
      // English (and AIA/NCS major groups)
      {"wall", E, 1, "English 'wall'", nullptr},
      {"walls", E, 1, "English 'walls'", nullptr},
      {"walling", E, 1, "English 'walling'", nullptr},
      {"partition", P, 1, "English 'partition'", nullptr},
      {"col", E, 1, "abbreviation 'col' (columns)", nullptr},
      {"cols", E, 1, "AIA 'COLS' (columns)", nullptr},
      {"colu", E, 1, "abbreviation 'colu' (columns)", nullptr},
      {"column", P, 1, "English 'column'", nullptr},
      {"pillar", P, 1, "English 'pillar'", nullptr},
      {"pier", E, 1, "English 'pier'", nullptr},
      {"piers", E, 1, "English 'piers'", nullptr},
      {"struct", P, 1, "English 'structure'", nullptr},
      {"strc", E, 1, "abbreviation 'strc' (structure)", nullptr},
      {"core", E, 1, "English 'core'", nullptr},
      {"cores", E, 1, "English 'cores'", nullptr},
      {"facade", P, 1, "English 'facade'", nullptr},
      {"masonry", E, 1, "English 'masonry'", nullptr},
      {"concrete", E, 1, "English 'concrete'", nullptr},
      {"brick", P, 1, "English 'brick'", nullptr},
      {"blockwork", E, 1, "English 'blockwork'", nullptr},
      {"door", P, -1, "English 'door' (does not block sight)", nullptr},
      {"dr", E, -1, "abbreviation 'dr' (doors)", nullptr},
      {"window", P, -1, "English 'window'", nullptr},
      {"wndw", E, -1, "abbreviation 'wndw' (windows)", nullptr},
      {"glaz", P, -1, "AIA 'GLAZ' (glazing)", nullptr},
      {"glass", P, -1, "English 'glass'", nullptr},
      {"curtain", P, -1, "English 'curtain' (curtain wall: glazing)", nullptr},
      {"curtwall", E, -1, "TArch 'CURTWALL' (curtain wall: glazing)", nullptr},
      {"opening", P, -1, "English 'opening'", nullptr},
      {"opng", E, -1, "abbreviation 'opng' (openings)", nullptr},
      {"furn", P, -1, "English 'furniture'", nullptr},
      {"equip", P, -1, "English 'equipment'", nullptr},
      {"eqpm", E, -1, "AIA 'EQPM' (equipment)", nullptr},
      {"fixt", P, -1, "English 'fixtures'", nullptr},
      {"casework", E, -1, "English 'casework'", nullptr},
      {"case", E, -1, "AIA 'CASE' (casework)", nullptr},
      {"millwork", E, -1, "English 'millwork'", nullptr},
      {"appl", P, -1, "English 'appliances'", nullptr},
      {"text", C, -1, "English 'text'", nullptr},
      {"txt", E, -1, "abbreviation 'txt' (text)", nullptr},
      {"note", P, -1, "English 'notes'", nullptr},
      {"anno", P, -1, "AIA 'ANNO' (annotation)", nullptr},
      {"label", P, -1, "English 'label'", nullptr},
      {"legend", P, -1, "English 'legend'", nullptr},
      {"dim", E, -1, "abbreviation 'dim' (dimensions)", nullptr},
      {"dims", E, -1, "AIA 'DIMS' (dimensions)", nullptr},
      {"dimen", P, -1, "English 'dimensions'", nullptr},
      {"hatch", P, -1, "English 'hatch'", nullptr},
      {"htch", E, -1, "abbreviation 'htch' (hatch)", nullptr},
      {"patt", P, -1, "AIA 'PATT' (hatch patterns)", nullptr},
      {"fill", E, -1, "English 'fill' (hatch)", nullptr},
      {"poche", E, -1, "'poche' (hatch)", nullptr},
      {"grid", P, -1, "English 'grid'", nullptr},
      {"axis", E, -1, "English 'axis'", nullptr},
      {"axes", E, -1, "English 'axes'", nullptr},
      {"area", E, -1, "AIA 'AREA' (areas)", nullptr},
      {"areas", E, -1, "English 'areas'", nullptr},
      {"room", P, -1, "English 'room' (names and outlines)", nullptr},
      {"space", E, -1, "English 'space' (room outlines)", nullptr},
      {"iden", E, -1, "AIA 'IDEN' (identification tags)", nullptr},
      {"tag", E, -1, "English 'tag'", nullptr},
      {"tags", E, -1, "English 'tags'", nullptr},
      {"symb", P, -1, "English 'symbols'", nullptr},
      {"title", P, -1, "English 'title'", nullptr},
      {"titl", E, -1, "AIA 'TITL' (title block)", nullptr},
      {"border", P, -1, "English 'border'", nullptr},
      {"viewport", P, -1, "English 'viewport'", nullptr},
      {"vport", P, -1, "AutoCAD viewports", nullptr},
      {"defpoints", E, -1, "AutoCAD 'Defpoints' (never plotted)", nullptr},
      {"nplt", E, -1, "AIA 'NPLT' (not plotted)", nullptr},
      {"elev", E, -1, "AIA 'ELEV' (elevation marks)", nullptr},
      {"sect", P, -1, "English 'section' marks", nullptr},
      {"detl", E, -1, "AIA 'DETL' (details)", nullptr},
      {"detail", P, -1, "English 'detail'", nullptr},
      {"stair", P, -1, "English 'stairs'", nullptr},
      {"strs", E, -1, "AIA 'STRS' (stairs)", nullptr},
      {"rail", P, -1, "English 'railing'", nullptr},
      {"handrail", P, -1, "English 'handrail'", nullptr},
      {"flor", E, -1, "AIA 'FLOR' (floor features: stairs, casework, railings)", nullptr},
      {"clng", E, -1, "AIA 'CLNG' (ceiling)", nullptr},
      {"ceiling", P, -1, "English 'ceiling'", nullptr},
      {"ovhd", E, -1, "AIA 'OVHD' (overhead)", nullptr},
      {"overhead", E, -1, "English 'overhead'", nullptr},
      {"beam", E, -1, "English 'beam' (overhead)", nullptr},
      {"beams", E, -1, "English 'beams' (overhead)", nullptr},
      {"hidden", E, -1, "English 'hidden'", nullptr},
      {"cntr", E, -1, "AIA 'CNTR' (centre lines)", nullptr},
      {"center", P, -1, "English 'centre line'", nullptr},
      {"centre", P, -1, "English 'centre line'", nullptr},
      {"light", E, -1, "English 'lighting'", nullptr},
      {"lighting", E, -1, "English 'lighting'", nullptr},
      {"lite", E, -1, "AIA 'LITE' (lighting)", nullptr},
      {"elec", P, -1, "English 'electrical'", nullptr},
      {"hvac", E, -1, "HVAC", nullptr},
      {"duct", P, -1, "English 'ducts'", nullptr},
      {"pipe", P, -1, "English 'pipes'", nullptr},
      {"plumb", P, -1, "English 'plumbing'", nullptr},
      {"sanitary", E, -1, "English 'sanitary'", nullptr},
      {"revis", P, -1, "English 'revisions'", nullptr},
      {"revs", E, -1, "AIA 'REVS' (revisions)", nullptr},
      {"cloud", P, -1, "revision clouds", nullptr},
      {"logo", E, -1, "English 'logo'", nullptr},
      {"stamp", E, -1, "English 'stamp'", nullptr},
      {"wallpaper", E, -1, "English 'wallpaper' (a finish)", nullptr},
      {"finish", P, -1, "English 'finishes'", nullptr},
      {"planting", E, -1, "English 'planting'", nullptr},
      {"plnt", E, -1, "abbreviation 'plnt' (planting)", nullptr},
      {"tree", P, -1, "English 'trees'", nullptr},
      {"prht", E, 0, "AIA 'PRHT' (partial-height walls may not block sight)", nullptr},
      {"partial", E, 0, "English 'partial' (partial-height walls may not block sight)", nullptr},
      {"demo", P, 0, "English 'demolition' (walls to be removed)", nullptr},
      // German
      {"wand", C, 1, "German 'Wand'", "leinwand"},
      {"waende", C, 1, "German 'Wände'", nullptr},
      {"wande", C, 1, "German 'Wände'", nullptr},
      {"mauer", C, 1, "German 'Mauer'", nullptr},
      {"stutze", C, 1, "German 'Stütze'", nullptr},
      {"stuetze", C, 1, "German 'Stütze'", nullptr},
      {"saule", C, 1, "German 'Säule'", nullptr},
      {"pfeiler", C, 1, "German 'Pfeiler'", nullptr},
      {"tragwerk", C, 1, "German 'Tragwerk'", nullptr},
      {"tragend", C, 1, "German 'tragend'", nullptr},
      {"beton", C, 1, "'Beton' (concrete)", nullptr},
      {"struktur", P, 1, "German 'Struktur'", nullptr},
      {"tur", S, -1, "German 'Tür' (door)", "ktur"},
      {"turen", S, -1, "German 'Türen' (doors)", "ktur"},
      {"tuer", C, -1, "German 'Tür' (door)", nullptr},
      {"fenster", C, -1, "German 'Fenster' (window)", nullptr},
      {"mobel", C, -1, "German 'Möbel' (furniture)", nullptr},
      {"moebel", C, -1, "German 'Möbel' (furniture)", nullptr},
      {"moblier", C, -1, "German 'Möblierung' (furniture)", nullptr},
      {"moeblier", C, -1, "German 'Möblierung' (furniture)", nullptr},
      {"einrichtung", C, -1, "German 'Einrichtung' (furnishing)", nullptr},
      {"ausstattung", C, -1, "German 'Ausstattung' (furnishing)", nullptr},
      {"bemassung", C, -1, "German 'Bemaßung' (dimensions)", nullptr},
      {"vermassung", C, -1, "German 'Vermaßung' (dimensions)", nullptr},
      {"masskette", C, -1, "German 'Maßkette' (dimensions)", nullptr},
      {"beschriftung", C, -1, "German 'Beschriftung' (text)", nullptr},
      {"schrift", E, -1, "German 'Schrift' (text)", nullptr},
      {"schraffur", C, -1, "German 'Schraffur' (hatch)", nullptr},
      {"achse", P, -1, "German 'Achse' (grid axes)", nullptr},
      {"raster", E, -1, "German 'Raster' (grid)", nullptr},
      {"raum", E, -1, "German 'Raum' (room outlines)", nullptr},
      {"raumstempel", E, -1, "German 'Raumstempel' (room tags)", nullptr},
      {"treppe", C, -1, "German 'Treppe' (stairs)", nullptr},
      {"gelander", C, -1, "German 'Geländer' (railing)", nullptr},
      {"sanitar", C, -1, "German 'Sanitär'", nullptr},
      {"offnung", C, -1, "German 'Öffnung' (opening)", nullptr},
      {"oeffnung", C, -1, "German 'Öffnung' (opening)", nullptr},
      {"vorhang", C, -1, "German 'Vorhangfassade' (glazing)", nullptr},
      {"abbruch", C, 0, "German 'Abbruch' (walls to be removed)", nullptr},
      {"ruckbau", C, 0, "German 'Rückbau' (walls to be removed)", nullptr},
      {"rueckbau", C, 0, "German 'Rückbau' (walls to be removed)", nullptr},
      // French
      {"mur", E, 1, "French 'mur'", nullptr},
      {"murs", E, 1, "French 'murs'", nullptr},
      {"cloison", P, 1, "French 'cloison'", nullptr},
      {"poteau", P, 1, "French 'poteau'", nullptr},
      {"pilier", P, 1, "French 'pilier'", nullptr},
      {"voile", E, 1, "French 'voile' (concrete wall)", nullptr},
      {"voiles", E, 1, "French 'voiles' (concrete walls)", nullptr},
      {"refend", P, 1, "French 'refend'", nullptr},
      {"maconnerie", P, 1, "French 'maçonnerie'", nullptr},
      {"colonne", P, 1, "French/Italian 'colonne'", nullptr},
      {"porte", E, -1, "French/Italian 'porte' (doors)", nullptr},
      {"portes", E, -1, "French 'portes' (doors)", nullptr},
      {"fenetre", P, -1, "French 'fenêtre' (window)", nullptr},
      {"baie", P, -1, "French 'baie' (opening)", nullptr},
      {"ouverture", P, -1, "French 'ouverture' (opening)", nullptr},
      {"menuiserie", P, -1, "French 'menuiserie' (doors and windows)", nullptr},
      {"vitr", P, -1, "French 'vitrage' (glazing)", nullptr},
      {"rideau", E, -1, "French 'mur rideau' (glazing)", nullptr},
      {"mobilier", P, -1, "French 'mobilier' (furniture)", nullptr},
      {"meuble", P, -1, "French 'meuble' (furniture)", nullptr},
      {"cotation", P, -1, "French 'cotation' (dimensions)", nullptr},
      {"cote", E, -1, "French 'cote' (dimension)", nullptr},
      {"cotes", E, -1, "French 'cotes' (dimensions)", nullptr},
      {"texte", P, -1, "French 'texte'", nullptr},
      {"hachur", P, -1, "French 'hachures' (hatch)", nullptr},
      {"escalier", P, -1, "French 'escalier' (stairs)", nullptr},
      {"axe", E, -1, "French 'axe' (grid axis)", nullptr},
      // Spanish and Portuguese
      {"muro", E, 1, "Spanish/Italian 'muro'", nullptr},
      {"muros", E, 1, "Spanish 'muros'", nullptr},
      {"pared", P, 1, "Spanish/Portuguese 'pared(e)'", nullptr},
      {"tabique", P, 1, "Spanish 'tabique'", nullptr},
      {"columna", P, 1, "Spanish 'columna'", nullptr},
      {"pilar", E, 1, "Spanish 'pilar'", nullptr},
      {"pilares", E, 1, "Spanish 'pilares'", nullptr},
      {"estructur", P, 1, "Spanish 'estructura'", nullptr},
      {"mamposter", P, 1, "Spanish 'mampostería'", nullptr},
      {"hormigon", E, 1, "Spanish 'hormigón' (concrete)", nullptr},
      {"alvenaria", E, 1, "Portuguese 'alvenaria' (masonry)", nullptr},
      {"puerta", P, -1, "Spanish 'puerta' (door)", nullptr},
      {"ventana", P, -1, "Spanish 'ventana' (window)", nullptr},
      {"janela", P, -1, "Portuguese 'janela' (window)", nullptr},
      {"carpinteria", P, -1, "Spanish 'carpintería' (doors and windows)", nullptr},
      {"vidrio", P, -1, "Spanish 'vidrio' (glass)", nullptr},
      {"cortina", E, -1, "Spanish 'muro cortina' (glazing)", nullptr},
      {"mobiliario", P, -1, "Spanish 'mobiliario' (furniture)", nullptr},
      {"mueble", P, -1, "Spanish 'mueble' (furniture)", nullptr},
      {"cota", E, -1, "Spanish 'cota' (dimension)", nullptr},
      {"cotas", E, -1, "Spanish 'cotas' (dimensions)", nullptr},
      {"acotacion", P, -1, "Spanish 'acotación' (dimensions)", nullptr},
      {"texto", P, -1, "Spanish 'texto'", nullptr},
      {"sombread", P, -1, "Spanish 'sombreado' (hatch)", nullptr},
      {"rayado", E, -1, "Spanish 'rayado' (hatch)", nullptr},
      {"trama", E, -1, "Spanish 'trama' (hatch)", nullptr},
      {"escalera", P, -1, "Spanish 'escalera' (stairs)", nullptr},
      {"eje", E, -1, "Spanish 'eje' (grid axis)", nullptr},
      {"ejes", E, -1, "Spanish 'ejes' (grid axes)", nullptr},
      // Italian
      {"muri", E, 1, "Italian 'muri'", nullptr},
      {"parete", E, 1, "Italian 'parete'", nullptr},
      {"pareti", E, 1, "Italian 'pareti'", nullptr},
      {"tramezz", P, 1, "Italian 'tramezzo' (partition)", nullptr},
      {"pilastr", P, 1, "Italian 'pilastro'", nullptr},
      {"colonna", P, 1, "Italian 'colonna'", nullptr},
      {"muratur", P, 1, "Italian 'muratura' (masonry)", nullptr},
      {"struttur", P, 1, "Italian 'struttura'", nullptr},
      {"porta", E, -1, "Italian 'porta' (door)", nullptr},
      {"finestr", P, -1, "Italian 'finestra' (window)", nullptr},
      {"infiss", P, -1, "Italian 'infissi' (doors and windows)", nullptr},
      {"serrament", P, -1, "Italian 'serramenti' (doors and windows)", nullptr},
      {"vetr", P, -1, "Italian 'vetro' (glass)", nullptr},
      {"arred", P, -1, "Italian 'arredo' (furniture)", nullptr},
      {"mobili", E, -1, "Italian 'mobili' (furniture)", nullptr},
      {"quota", E, -1, "Italian 'quota' (dimension)", nullptr},
      {"quote", E, -1, "Italian 'quote' (dimensions)", nullptr},
      {"testo", E, -1, "Italian 'testo'", nullptr},
      {"testi", E, -1, "Italian 'testi'", nullptr},
      {"tratteggi", P, -1, "Italian 'tratteggio' (hatch)", nullptr},
      {"retino", P, -1, "Italian 'retino' (hatch)", nullptr},
      {"scala", E, -1, "Italian 'scala' (stairs)", nullptr},
      // Dutch
      {"wanden", E, 1, "Dutch 'wanden'", nullptr},
      {"muur", C, 1, "Dutch 'muur'", nullptr},
      {"muren", E, 1, "Dutch 'muren'", nullptr},
      {"kolom", P, 1, "Dutch 'kolom'", nullptr},
      {"gevel", P, 1, "Dutch 'gevel' (facade)", nullptr},
      {"constructie", C, 1, "Dutch 'constructie' (structure)", nullptr},
      {"deur", P, -1, "Dutch 'deur' (door)", nullptr},
      {"raam", E, -1, "Dutch 'raam' (window)", nullptr},
      {"ramen", E, -1, "Dutch 'ramen' (windows)", nullptr},
      {"kozijn", P, -1, "Dutch 'kozijn' (door and window frames)", nullptr},
      {"glas", E, -1, "Dutch/German 'glas' (glass)", nullptr},
      {"meubel", P, -1, "Dutch 'meubel' (furniture)", nullptr},
      {"meubilair", E, -1, "Dutch 'meubilair' (furniture)", nullptr},
      {"maatvoer", P, -1, "Dutch 'maatvoering' (dimensions)", nullptr},
      {"tekst", P, -1, "Dutch 'tekst'", nullptr},
      {"arcer", P, -1, "Dutch 'arcering' (hatch)", nullptr},
      {"stramien", P, -1, "Dutch 'stramien' (grid)", nullptr},
      {"trap", E, -1, "Dutch 'trap' (stairs)", nullptr},
      // Russian
      {"стен", P, 1, "Russian 'стена' (wall)", nullptr},
      {"перегородк", P, 1, "Russian 'перегородка' (partition)", nullptr},
      {"колонн", P, 1, "Russian 'колонна' (column)", nullptr},
      {"конструкц", P, 1, "Russian 'конструкции' (structure)", nullptr},
      {"двер", P, -1, "Russian 'дверь' (door)", nullptr},
      {"окн", P, -1, "Russian 'окно' (window)", nullptr},
      {"окон", P, -1, "Russian 'окна' (windows)", nullptr},
      {"мебел", P, -1, "Russian 'мебель' (furniture)", nullptr},
      {"размер", P, -1, "Russian 'размеры' (dimensions)", nullptr},
      {"текст", P, -1, "Russian 'текст'", nullptr},
      {"штрих", P, -1, "Russian 'штриховка' (hatch)", nullptr},
      // Chinese (simplified and traditional) and Japanese; 柱 and 家具 are shared
      {"幕墙", C, -1, "Chinese '幕墙' (curtain wall: glazing)", nullptr},
      {"墙", C, 1, "Chinese '墙' (wall)", nullptr},
      {"牆", C, 1, "Chinese '牆' (wall)", nullptr},
      {"柱", C, 1, "Chinese/Japanese '柱' (column)", nullptr},
      {"结构", C, 1, "Chinese '结构' (structure)", nullptr},
      {"結構", C, 1, "Chinese '結構' (structure)", nullptr},
      {"门", C, -1, "Chinese '门' (door)", nullptr},
      {"門", C, -1, "Chinese '門' (door)", nullptr},
      {"窗", C, -1, "Chinese/Japanese '窗/窓' (window)", nullptr},
      {"窓", C, -1, "Japanese '窓' (window)", nullptr},
      {"家具", C, -1, "Chinese/Japanese '家具' (furniture)", nullptr},
      {"标注", C, -1, "Chinese '标注' (dimensions)", nullptr},
      {"標註", C, -1, "Chinese '標註' (dimensions)", nullptr},
      {"尺寸", C, -1, "Chinese '尺寸' (dimensions)", nullptr},
      {"文字", C, -1, "Chinese/Japanese '文字' (text)", nullptr},
      {"文本", C, -1, "Chinese '文本' (text)", nullptr},
      {"注释", C, -1, "Chinese '注释' (annotation)", nullptr},
      {"填充", C, -1, "Chinese '填充' (hatch)", nullptr},
      {"图案", C, -1, "Chinese '图案' (hatch pattern)", nullptr},
      {"轴", C, -1, "Chinese '轴' (grid axes)", nullptr},
      {"楼梯", C, -1, "Chinese '楼梯' (stairs)", nullptr},
      {"栏杆", C, -1, "Chinese '栏杆' (railing)", nullptr},
      {"洁具", C, -1, "Chinese '洁具' (sanitary fittings)", nullptr},
      {"设备", C, -1, "Chinese '设备' (equipment)", nullptr},
      {"图框", C, -1, "Chinese '图框' (drawing frame)", nullptr},
      {"房间", C, -1, "Chinese '房间' (rooms)", nullptr},
      {"壁紙", C, -1, "Japanese '壁紙' (wallpaper)", nullptr},
      {"壁", C, 1, "Japanese '壁' (wall)", nullptr},
      {"間仕切", C, 1, "Japanese '間仕切' (partition)", nullptr},
      {"構造", C, 1, "Japanese '構造' (structure)", nullptr},
      {"躯体", C, 1, "Japanese '躯体' (structural frame)", nullptr},
      {"建具", C, -1, "Japanese '建具' (doors and windows)", nullptr},
      {"扉", C, -1, "Japanese '扉' (door)", nullptr},
      {"ドア", C, -1, "Japanese 'ドア' (door)", nullptr},
      {"什器", C, -1, "Japanese '什器' (fixtures and furniture)", nullptr},
      {"寸法", C, -1, "Japanese '寸法' (dimensions)", nullptr},
      {"ハッチ", C, -1, "Japanese 'ハッチ' (hatch)", nullptr},
      {"通り芯", C, -1, "Japanese '通り芯' (grid lines)", nullptr},
      {"通芯", C, -1, "Japanese '通芯' (grid lines)", nullptr},
      {"階段", C, -1, "Japanese '階段' (stairs)", nullptr},
      {"設備", C, -1, "Japanese '設備' (equipment)", nullptr},
      {"ガラス", C, -1, "Japanese 'ガラス' (glass)", nullptr},
      // Korean
      {"벽", C, 1, "Korean '벽' (wall)", nullptr},
      {"기둥", C, 1, "Korean '기둥' (column)", nullptr},
      {"문", C, -1, "Korean '문' (door)", nullptr},
      {"창", C, -1, "Korean '창' (window)", nullptr},
      {"가구", C, -1, "Korean '가구' (furniture)", nullptr},
      {"치수", C, -1, "Korean '치수' (dimensions)", nullptr},
      {"해치", C, -1, "Korean '해치' (hatch)", nullptr},
  };
  return terms;
}

bool starts_with(const std::string& s, const std::string& p) { return s.compare(0, p.size(), p) == 0; }
bool ends_with(const std::string& s, const std::string& p) {
  return s.size() >= p.size() && s.compare(s.size() - p.size(), p.size(), p) == 0;
}

bool term_matches(const Term& t, const std::string& word) {
  const std::string key = t.key;
  if (t.unless && word.find(t.unless) != std::string::npos) return false;
  switch (t.match) {
    case Match::exact:
      return word == key;
    case Match::prefix:
      return starts_with(word, key);
    case Match::suffix:
      return ends_with(word, key);
    case Match::contains:
      return word.find(key) != std::string::npos;
  }
  return false;
}

// Terms found in one word; a glued ASCII word with no hit of its own is tried as two words ("WALLHATCH").
std::vector<const Term*> terms_in_word(const std::string& word) {
  std::vector<const Term*> hits;
  for (const Term& t : vocabulary())
    if (term_matches(t, word)) hits.push_back(&t);
  if (!hits.empty() || word.size() < 6 || static_cast<unsigned char>(word[0]) >= 0x80) return hits;
  for (std::size_t cut = 3; cut + 3 <= word.size(); ++cut) {
    const std::string left = word.substr(0, cut), right = word.substr(cut);
    std::vector<const Term*> l, r;
    for (const Term& t : vocabulary()) {
      if (t.match == Match::contains) continue;  // those were tried on the whole word
      if (t.match == Match::exact && term_matches(t, left)) l.push_back(&t);
      if ((t.match == Match::exact || t.match == Match::prefix) && term_matches(t, right)) r.push_back(&t);
    }
    if (!l.empty() && !r.empty()) {
      hits.insert(hits.end(), l.begin(), l.end());
      hits.insert(hits.end(), r.begin(), r.end());
      return hits;
    }
  }
  return hits;
}

// ---------------------------------------------------------------------------------------------------------
// xref-bound names: "XREF$0$A-WALL" (bound), "XREF|A-WALL" (attached). The layer's own part is the last.
std::string own_part(const std::string& name) {
  std::string rest = name;
  const std::size_t bar = rest.rfind('|');
  if (bar != std::string::npos) rest = rest.substr(bar + 1);
  // The last "$<digits>$" marks a bind prefix.
  for (std::size_t end = rest.size(); end > 0;) {
    const std::size_t close = rest.rfind('$', end - 1);
    if (close == std::string::npos || close == 0) break;
    std::size_t open = close;
    while (open > 0 && std::isdigit(static_cast<unsigned char>(rest[open - 1]))) --open;
    if (open < close && open > 0 && rest[open - 1] == '$') return rest.substr(close + 1);
    end = close;
  }
  return rest;
}

// ---------------------------------------------------------------------------------------------------------
// ISO 13567: agent (2 characters), element (6), presentation (2), optional fields after. The standard
// leaves the element table to each country: CI/SfB (UK, NL-SfB, Scandinavia: (21) external walls, (22)
// internal walls, (28) frames, (31)/(32) openings, (7-) fittings, (8-) loose furniture), DIN 276 (Germany:
// 331/332 external walls, 333 external columns, 334 external doors and windows, 341/342 internal walls, 343
// internal columns, 344 internal doors and windows), NS 3451 (Norway: 222 columns, 231/232 external walls,
// 233 glass facades, 234 windows and doors, 241-243 internal walls, 244 doors). Two digits are read as
// CI/SfB, three or more by the table whose use of the leading digit leaves no doubt.
// Returns true when the name has the ISO 13567 shape (and sets vote/reason; vote may be 0).
bool iso13567_vote(const std::string& name, int* vote, std::string* reason) {
  if (name.size() < 8 || name.size() > 40) return false;
  for (char ch : name)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_')) return false;
  auto up = [](char ch) { return static_cast<char>(std::toupper(static_cast<unsigned char>(ch))); };
  if (!std::isalpha(static_cast<unsigned char>(name[0]))) return false;
  if (!(std::isalnum(static_cast<unsigned char>(name[1])) || name[1] == '-' || name[1] == '_')) return false;
  const std::string element = name.substr(2, 6);
  std::size_t k = 0;
  while (k < element.size() && (element[k] == '-' || element[k] == '_')) ++k;
  std::string digits;
  while (k < element.size() && std::isdigit(static_cast<unsigned char>(element[k]))) digits += element[k++];
  if (digits.size() < 2) return false;
  for (; k < element.size(); ++k)
    if (!(std::isalnum(static_cast<unsigned char>(element[k])) || element[k] == '-' || element[k] == '_'))
      return false;
  const char presentation = name.size() > 8 ? up(name[8]) : '-';
  const std::string code = "ISO 13567 element " + digits;
  auto set = [&](int v, const std::string& why) {
    *vote = v;
    if (reason) *reason = why;
    return true;
  };
  switch (presentation) {
    case 'T':
      return set(-1, "ISO 13567 presentation T (text)");
    case 'H':
      return set(-1, "ISO 13567 presentation H (hatching)");
    case 'D':
      return set(-1, "ISO 13567 presentation D (dimensions)");
    case 'J':
      return set(-1, "ISO 13567 presentation J (section marks)");
    case 'K':
      return set(-1, "ISO 13567 presentation K (revision marks)");
    case 'G':
      return set(-1, "ISO 13567 presentation G (grid)");
    case 'U':
      return set(-1, "ISO 13567 presentation U (construction lines)");
    case 'B':
      return set(-1, "ISO 13567 presentation B (border)");
    case 'V':
      return set(-1, "ISO 13567 presentation V (title and notes)");
    case 'I':
      return set(-1, "ISO 13567 presentation I (tables)");
    default:
      break;
  }
  const std::string two = digits.substr(0, 2), three = digits.size() >= 3 ? digits.substr(0, 3) : "";
  if (digits[0] == '7') return set(-1, code + " (CI/SfB fittings)");
  if (digits[0] == '8') return set(-1, code + " (CI/SfB loose furniture and equipment)");
  if (digits.size() == 2) {
    if (two == "21") return set(1, code + " (CI/SfB external walls)");
    if (two == "22") return set(1, code + " (CI/SfB internal walls, partitions)");
    if (two == "28") return set(1, code + " (CI/SfB building frames, columns)");
    if (two == "31" || two == "32") return set(-1, code + " (CI/SfB wall openings: windows, doors)");
    return set(0, code + " (CI/SfB, not a wall)");
  }
  if (digits[0] == '3') {  // DIN 276 cost groups (CI/SfB (3-) subdivisions are openings)
    if (three == "331" || three == "332" || three == "337") return set(1, code + " (DIN 276 external walls)");
    if (three == "333") return set(1, code + " (DIN 276 external columns)");
    if (three == "341" || three == "342" || three == "346") return set(1, code + " (DIN 276 internal walls)");
    if (three == "343") return set(1, code + " (DIN 276 internal columns)");
    if (three == "334" || three == "344" || three == "362")
      return set(-1, code + " (DIN 276 doors and windows)");
    if (two == "31" || two == "32") return set(-1, code + " (CI/SfB wall openings)");
    return set(0, code + " (DIN 276, not a wall)");
  }
  if (digits[0] == '6') return set(-1, code + " (DIN 276 furnishing)");
  if (two == "21") return set(1, code + " (CI/SfB external walls)");
  if (two == "22") return set(1, code + " (CI/SfB internal walls; NS 3451 load-bearing frame, columns)");
  if (three == "231" || three == "232") return set(1, code + " (NS 3451 external walls)");
  if (three == "241" || three == "242" || three == "243") return set(1, code + " (NS 3451 internal walls)");
  if (three == "233") return set(-1, code + " (NS 3451 glass facades)");
  if (three == "234" || three == "244") return set(-1, code + " (NS 3451 windows and doors)");
  return set(0, code + " (no wall in the usual element tables)");
}

// AIA/NCS: discipline (1-2 letters), major group (4 letters). Services disciplines draw over the plan.
bool aia_services_layer(const std::string& name) {
  std::size_t dash = name.find('-');
  if (dash == std::string::npos || dash == 0 || dash > 2) return false;
  for (std::size_t i = 0; i < dash; ++i)
    if (!std::isalpha(static_cast<unsigned char>(name[i]))) return false;
  std::size_t end = name.find('-', dash + 1);
  if (end == std::string::npos) end = name.size();
  if (end - dash - 1 != 4) return false;
  for (std::size_t i = dash + 1; i < end; ++i)
    if (!std::isalpha(static_cast<unsigned char>(name[i]))) return false;
  const char d = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
  return d == 'E' || d == 'M' || d == 'P' || d == 'F' || d == 'T';
}

}  // namespace

int occluder_vote_from_name(const std::string& layer_name, std::string* reason) {
  auto say = [&](int v, const std::string& why) {
    if (reason) *reason = why;
    return v;
  };
  const std::string name = own_part(layer_name);
  if (name.empty() || name == "0") return say(0, "layer 0 says nothing");

  int vote = 0;
  std::string why;
  if (iso13567_vote(name, &vote, &why)) return say(vote, why);

  const Term* positive = nullptr;
  const Term* negative = nullptr;
  const Term* neutral = nullptr;
  for (const std::string& word : words_of(name))
    for (const Term* t : terms_in_word(word)) {
      if (t->vote > 0 && !positive) positive = t;
      if (t->vote < 0 && !negative) negative = t;
      if (t->vote == 0 && !neutral) neutral = t;
    }
  // A wall's annotation or pattern ("WALL-HATCH", "Wandschraffur") is annotation, not a wall.
  if (negative) return say(-1, negative->reason);
  if (positive && neutral) return say(0, neutral->reason);
  if (positive) return say(1, positive->reason);
  if (aia_services_layer(name)) return say(-1, "AIA services layer (electrical, mechanical, plumbing, fire)");
  return say(0, "the name says nothing");
}

bool name_mentions_occluder(const std::string& layer_name) {
  std::string name = own_part(layer_name);
  if (name.empty() || name == "0") return false;
  int vote = 0;
  std::string why;
  if (name.size() > 8) name[8] = 'E';  // ISO 13567: the element, whatever the presentation (H: hatching)
  if (iso13567_vote(name, &vote, &why)) return vote > 0;
  for (const std::string& word : words_of(name))
    for (const Term* t : terms_in_word(word))
      if (t->vote > 0) return true;
  return false;
}

}  // namespace plenopath
