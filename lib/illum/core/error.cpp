#include "illum/core/error.hpp"

#include <utility>

namespace illum {

InputError::InputError(const std::string& file, const std::string& field, const std::string& value,
                       const std::string& problem)
    : std::runtime_error(file + ": field '" + field + "' = " + value + ": " + problem),
      file_(file),
      field_(field),
      value_(value) {}

NotImplemented::NotImplemented(std::string exercise, std::string hint)
    : exercise_(std::move(exercise)), hint_(std::move(hint)) {}

std::string NotImplemented::message() const { return "NotImplemented: " + exercise_ + " — " + hint_; }

}  // namespace illum
