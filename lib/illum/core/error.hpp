#pragma once
// The errors illum throws.
//
// * std::invalid_argument: a precondition of a function was broken by its
//   caller (a non-unit ray direction, a negative radius).
// * InputError: a file a user wrote is wrong; the message names the file,
//   the field and the value.
// * NotImplemented: an exercise stub was called. It derives from nothing, not
//   even std::exception, so that no test expecting a real error type (for
//   instance CHECK_THROWS_AS(..., std::invalid_argument)) can pass on a stub.
#include <stdexcept>
#include <string>

namespace illum {

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& field, const std::string& value,
             const std::string& problem);

  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }
  const std::string& value() const { return value_; }

 private:
  std::string file_, field_, value_;
};

class NotImplemented {
 public:
  NotImplemented(std::string exercise, std::string hint);
  const std::string& exercise() const { return exercise_; }
  const std::string& hint() const { return hint_; }
  // "NotImplemented: <exercise> — <hint>"
  std::string message() const;

 private:
  std::string exercise_, hint_;
};

// Throws std::invalid_argument with the message when the condition is false.
inline void require(bool condition, const char* message) {
  if (!condition) throw std::invalid_argument(message);
}

}  // namespace illum
