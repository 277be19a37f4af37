#include "processing/capture/povray_atmosphere.h"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/error.h"

namespace plenopath {

namespace {

bool identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Past a comment or a string starting at `i` (or `i` itself when there is none there).
std::size_t skip_comment_or_string(const std::string& s, std::size_t i) {
  if (s.compare(i, 2, "//") == 0) {
    const std::size_t end = s.find('\n', i);
    return end == std::string::npos ? s.size() : end;
  }
  if (s.compare(i, 2, "/*") == 0) {  // POV-Ray's block comments nest
    int level = 0;
    while (i < s.size()) {
      if (s.compare(i, 2, "/*") == 0) {
        ++level;
        i += 2;
      } else if (s.compare(i, 2, "*/") == 0) {
        i += 2;
        if (--level == 0) return i;
      } else {
        ++i;
      }
    }
    return s.size();
  }
  if (s[i] == '"') {
    ++i;
    while (i < s.size() && s[i] != '"' && s[i] != '\n') i += s[i] == '\\' ? 2 : 1;
    return std::min(s.size(), i + 1);
  }
  return i;
}

// Past spaces and comments from `i`.
std::size_t skip_space(const std::string& s, std::size_t i) {
  while (i < s.size()) {
    if (std::isspace(static_cast<unsigned char>(s[i]))) {
      ++i;
    } else if (s.compare(i, 2, "//") == 0 || s.compare(i, 2, "/*") == 0) {
      i = skip_comment_or_string(s, i);
    } else {
      break;
    }
  }
  return i;
}

// The index just past the brace that closes the one at `open`, or npos when it never closes.
std::size_t block_end(const std::string& s, std::size_t open) {
  int level = 0;
  std::size_t i = open;
  while (i < s.size()) {
    const std::size_t skipped = skip_comment_or_string(s, i);
    if (skipped != i) {
      i = skipped;
      continue;
    }
    if (s[i] == '{') ++level;
    if (s[i] == '}' && --level == 0) return i + 1;
    ++i;
  }
  return std::string::npos;
}

}  // namespace

std::string without_atmosphere(const std::string& sdl, int* changed) {
  static const struct {
    const char* keyword;
    const char* replacement;
  } kBlocks[] = {{"fog", "fog { distance 1e12 }"}, {"media", "media { }"}, {"radiosity", ""}};
  std::string out;
  out.reserve(sdl.size());
  int count = 0;
  std::size_t i = 0;
  while (i < sdl.size()) {
    const std::size_t skipped = skip_comment_or_string(sdl, i);
    if (skipped != i) {
      out.append(sdl, i, skipped - i);
      i = skipped;
      continue;
    }
    bool replaced = false;
    if (std::isalpha(static_cast<unsigned char>(sdl[i])) && (i == 0 || !identifier_char(sdl[i - 1]))) {
      for (const auto& block : kBlocks) {
        const std::size_t length = std::char_traits<char>::length(block.keyword);
        if (sdl.compare(i, length, block.keyword) != 0 ||
            (i + length < sdl.size() && identifier_char(sdl[i + length])))
          continue;
        const std::size_t open = skip_space(sdl, i + length);
        if (open >= sdl.size() || sdl[open] != '{') continue;
        const std::size_t end = block_end(sdl, open);
        if (end == std::string::npos) continue;
        out += block.replacement;
        i = end;
        ++count;
        replaced = true;
        break;
      }
    }
    if (!replaced) {
      // Copy the rest of a word at once, so a keyword inside an identifier (show_fog) is never matched.
      std::size_t j = i + 1;
      if (identifier_char(sdl[i]))
        while (j < sdl.size() && identifier_char(sdl[j])) ++j;
      out.append(sdl, i, j - i);
      i = j;
    }
  }
  if (changed) *changed = count;
  return out;
}

AtmosphereFreeScene copy_scene_without_atmosphere(const std::string& scene_file,
                                                  const std::string& copy_dir) {
  namespace fs = std::filesystem;
  const fs::path scene = fs::absolute(scene_file);
  fs::create_directories(copy_dir);
  AtmosphereFreeScene result;
  auto copy = [&](const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw Error("POV-Ray scene: cannot read " + file.string());
    std::stringstream text;
    text << in.rdbuf();
    int changed = 0;
    const std::string clean = without_atmosphere(text.str(), &changed);
    result.blocks_changed += changed;
    const fs::path target = fs::path(copy_dir) / file.filename();
    std::ofstream out(target, std::ios::binary);
    out << clean;
    if (!out) throw Error("POV-Ray: cannot write " + target.string());
    return target;
  };
  for (const fs::directory_entry& entry : fs::directory_iterator(scene.parent_path())) {
    const std::string extension = entry.path().extension().string();
    if (entry.is_regular_file() && entry.path() != scene && (extension == ".inc" || extension == ".pov"))
      copy(entry.path());
  }
  result.scene_file = copy(scene).string();
  return result;
}

}  // namespace plenopath
