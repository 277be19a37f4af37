#include "model/json_reader.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "model/error.h"

namespace plenopath {
namespace {

const char* type_name(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::object:
      return "an object";
    case nlohmann::json::value_t::array:
      return "an array";
    case nlohmann::json::value_t::string:
      return "a string";
    case nlohmann::json::value_t::boolean:
      return "a boolean";
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned:
      return "an integer";
    case nlohmann::json::value_t::number_float:
      return "a number";
    default:
      return "an unsupported value";
  }
}

}  // namespace

JsonReader::JsonReader(const nlohmann::json& value, std::string file, std::string pointer)
    : value_(&value), file_(std::move(file)), pointer_(std::move(pointer)) {}

void JsonReader::fail(const std::string& what) const {
  throw Error(file_ + ": " + (pointer_.empty() ? std::string("/") : pointer_) + ": " + what);
}

void JsonReader::expect_object() const {
  if (!value_->is_object()) fail(std::string("expected an object, got ") + type_name(*value_));
}

JsonReader JsonReader::at(const std::string& key) const {
  expect_object();
  auto it = value_->find(key);
  if (it == value_->end()) fail("missing field '" + key + "'");
  return JsonReader(*it, file_, pointer_ + "/" + key);
}

std::optional<JsonReader> JsonReader::find(const std::string& key) const {
  expect_object();
  auto it = value_->find(key);
  if (it == value_->end() || it->is_null()) return std::nullopt;
  return JsonReader(*it, file_, pointer_ + "/" + key);
}

bool JsonReader::has(const std::string& key) const { return find(key).has_value(); }

std::size_t JsonReader::size() const {
  if (!value_->is_array()) fail(std::string("expected an array, got ") + type_name(*value_));
  return value_->size();
}

JsonReader JsonReader::at(std::size_t index) const {
  if (index >= size()) fail("index " + std::to_string(index) + " out of range");
  return JsonReader((*value_)[index], file_, pointer_ + "/" + std::to_string(index));
}

double JsonReader::number() const {
  if (!value_->is_number()) fail(std::string("expected a number, got ") + type_name(*value_));
  const double v = value_->get<double>();
  if (!std::isfinite(v)) fail("expected a finite number");
  return v;
}

int JsonReader::integer() const {
  if (value_->is_number_integer() || value_->is_number_unsigned()) {
    const auto v = value_->get<long long>();
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
      fail("integer out of range");
    return static_cast<int>(v);
  }
  fail(std::string("expected an integer, got ") + type_name(*value_));
}

bool JsonReader::boolean() const {
  if (!value_->is_boolean()) fail(std::string("expected true or false, got ") + type_name(*value_));
  return value_->get<bool>();
}

std::string JsonReader::string() const {
  if (!value_->is_string()) fail(std::string("expected a string, got ") + type_name(*value_));
  return value_->get<std::string>();
}

double JsonReader::number_or(const std::string& key, double fallback) const {
  auto v = find(key);
  return v ? v->number() : fallback;
}
int JsonReader::integer_or(const std::string& key, int fallback) const {
  auto v = find(key);
  return v ? v->integer() : fallback;
}
bool JsonReader::boolean_or(const std::string& key, bool fallback) const {
  auto v = find(key);
  return v ? v->boolean() : fallback;
}
std::string JsonReader::string_or(const std::string& key, const std::string& fallback) const {
  auto v = find(key);
  return v ? v->string() : fallback;
}

nlohmann::json read_json_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw file_error(file, "cannot open for reading (missing or unreadable)");
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw file_error(file, "read error");
  const std::string text = buffer.str();
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw file_error(file, "file is empty");
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is the 1-based offset of the error; turn it into a line number for the author.
    std::size_t line = 1;
    for (std::size_t i = 0; i < text.size() && i + 1 < e.byte; ++i)
      if (text[i] == '\n') ++line;
    const bool truncated = e.byte >= text.size();
    throw file_error(file, "invalid JSON at line " + std::to_string(line) +
                               (truncated ? " (the file looks truncated)" : ""));
  } catch (const nlohmann::json::exception& e) {
    // Not a syntax error: a number too large for a double (1e400) and the like.
    throw file_error(file, std::string("unreadable JSON: ") + e.what());
  }
}

}  // namespace plenopath
