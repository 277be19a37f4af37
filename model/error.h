#pragma once
// The one exception type that crosses layers. Its message is meant for the author: it names the file and
// what is wrong. Code that the GUI calls throws this (never aborts) so the editor can show it.
#include <stdexcept>
#include <string>

namespace plenopath {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// "FILE: what" — the standard shape of a message about a file.
inline Error file_error(const std::string& file, const std::string& what) {
  return Error(file + ": " + what);
}

}  // namespace plenopath
