#include "illum/io/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "illum/core/error.hpp"
#include "illum/io/json_text_check.hpp"
#include "illum/io/nearest_name.hpp"
#include "illum/system/input_file.hpp"

#include <nlohmann/json.hpp>

namespace illum {

struct JsonReader::Document {
  std::string file;
  nlohmann::json root;
};

const std::string& JsonReader::file() const { return doc_->file; }

JsonReader::JsonReader(std::shared_ptr<const Document> doc, const nlohmann::json* node, std::string path)
    : doc_(std::move(doc)), node_(node), path_(std::move(path)) {}

void JsonReader::check_text(std::string_view text, const std::string& file_name) {
  check_json_text(text, file_name, max_depth);
}

JsonReader JsonReader::parse_text(const std::string& text, const std::string& file_name) {
  check_text(text, file_name);
  auto doc = std::make_shared<Document>();
  doc->file = file_name;
  try {
    doc->root = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // syntax errors, and numbers such as 1e999 that overflow
    throw InputError(file_name, "(file)", "(not JSON)", std::string("cannot parse JSON: ") + e.what());
  }
  const nlohmann::json* root = &doc->root;
  return JsonReader(std::move(doc), root, "");
}

JsonReader JsonReader::parse_file(const std::filesystem::path& file) {
  std::string text;
  try {
    text = read_input_file(file, "JSON file", max_file_bytes);
  } catch (const InputFileError& e) {
    throw InputError(file.string(), "(file)", file.string(), e.what());
  }
  return parse_text(text, file.string());
}

void JsonReader::fail(const std::string& problem) const {
  std::string value = node_->dump();
  if (value.size() > 80) value = value.substr(0, 77) + "...";
  throw InputError(file(), path_.empty() ? "(root)" : path_, value, problem);
}

bool JsonReader::has(const std::string& key) const { return node_->is_object() && node_->contains(key); }

JsonReader JsonReader::at(const std::string& key) const {
  if (!node_->is_object()) fail("expected an object with a field '" + key + "'");
  const auto it = node_->find(key);
  const std::string child = path_.empty() ? key : path_ + "." + key;
  if (it == node_->end()) throw InputError(file(), child, "(missing)", "this field is required");
  return JsonReader(doc_, &*it, child);
}

JsonReader JsonReader::at(std::size_t index) const {
  if (!node_->is_array() || index >= node_->size())
    fail("expected an array with an element " + std::to_string(index));
  return JsonReader(doc_, &(*node_)[index], path_ + "[" + std::to_string(index) + "]");
}

std::size_t JsonReader::size() const {
  if (!node_->is_array()) fail("expected an array");
  return node_->size();
}

double JsonReader::number() const {
  // nlohmann-json reads NaN and Infinity only as strings or null; both are refused here.
  if (!node_->is_number()) fail("expected a number");
  const double x = node_->get<double>();
  if (!std::isfinite(x)) fail("the number must be finite");
  return x;
}

double JsonReader::positive_number() const {
  const double x = number();
  if (!(x > 0)) fail("must be positive");
  return x;
}

int JsonReader::integer(int lo, int hi) const {
  if (!node_->is_number_integer()) fail("expected an integer");
  const auto x = node_->get<long long>();
  if (x < lo || x > hi) fail("must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return static_cast<int>(x);
}

std::string JsonReader::string() const {
  if (!node_->is_string()) fail("expected a string");
  return node_->get<std::string>();
}

bool JsonReader::boolean() const {
  if (!node_->is_boolean()) fail("expected true or false");
  return node_->get<bool>();
}

Vec3 JsonReader::vec3() const {
  if (!node_->is_array() || node_->size() != 3) fail("expected three numbers [x, y, z]");
  return {at(0).number(), at(1).number(), at(2).number()};
}

Vec3 JsonReader::vec3_in(double lo, double hi) const {
  const Vec3 v = vec3();
  for (int k = 0; k < 3; ++k)
    if (!(v[k] >= lo && v[k] < hi))
      at(static_cast<std::size_t>(k))
          .fail("must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + ")");
  return v;
}

Vec3 JsonReader::color() const {
  const Vec3 v = vec3();
  for (int k = 0; k < 3; ++k)
    if (!(v[k] >= 0.0 && v[k] <= 1.0))
      at(static_cast<std::size_t>(k)).fail("a colour factor must lie in [0, 1]");
  return v;
}

std::vector<std::string> JsonReader::keys() const {
  if (!node_->is_object()) fail("expected an object");
  std::vector<std::string> out;
  for (const auto& item : node_->items()) out.push_back(item.key());
  return out;
}

void JsonReader::only_fields(std::initializer_list<std::string_view> known) const {
  if (!node_->is_object()) fail("expected an object");
  for (const auto& item : node_->items()) {
    if (std::find(known.begin(), known.end(), item.key()) != known.end()) continue;
    // ostringstream rather than string '+': GCC 12 warns falsely (-Wrestrict) on the latter.
    std::ostringstream problem;
    problem << "unknown field '" << item.key() << "'";
    if (const std::string near = nearest_name(item.key(), std::vector<std::string_view>(known));
        !near.empty()) {
      problem << "; did you mean '" << near << "'?";
    } else {
      problem << "; known fields:";
      for (std::string_view k : known) problem << ' ' << k;
    }
    at(item.key()).fail(problem.str());
  }
}

}  // namespace illum
