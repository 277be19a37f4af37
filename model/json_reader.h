#pragma once
// Reads JSON documents with errors that name the file and the JSON path of the bad value,
// e.g. "tour.plenopath: /path/frames/12/x: expected a number, got a string".
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace plenopath {

class JsonReader {
 public:
  JsonReader(const nlohmann::json& value, std::string file, std::string pointer = "");

  // Required object member; throws Error naming the path when it is missing.
  JsonReader at(const std::string& key) const;
  // Optional object member.
  std::optional<JsonReader> find(const std::string& key) const;
  bool has(const std::string& key) const;
  // Array element; the array's size via size().
  JsonReader at(std::size_t index) const;
  std::size_t size() const;  // throws unless this is an array

  double number() const;
  int integer() const;
  bool boolean() const;
  std::string string() const;

  // Shorthands for members: required, and with a default when absent.
  double number(const std::string& key) const { return at(key).number(); }
  int integer(const std::string& key) const { return at(key).integer(); }
  bool boolean(const std::string& key) const { return at(key).boolean(); }
  std::string string(const std::string& key) const { return at(key).string(); }
  double number_or(const std::string& key, double fallback) const;
  int integer_or(const std::string& key, int fallback) const;
  bool boolean_or(const std::string& key, bool fallback) const;
  std::string string_or(const std::string& key, const std::string& fallback) const;

  const nlohmann::json& value() const { return *value_; }
  const std::string& pointer() const { return pointer_; }
  const std::string& file() const { return file_; }
  [[noreturn]] void fail(const std::string& what) const;

 private:
  void expect_object() const;
  const nlohmann::json* value_;
  std::string file_;
  std::string pointer_;
};

// Parses a whole file; a missing or unreadable file, or invalid JSON, throws Error naming the file.
nlohmann::json read_json_file(const std::string& file);

}  // namespace plenopath
