// The doctest main shared by every test program.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include "illum/core/error.hpp"

// A stub's exception is reported by name and hint, not as "unknown exception",
// so a student sees which function is still to be written.
DOCTEST_REGISTER_EXCEPTION_TRANSLATOR(const illum::NotImplemented& e) {
  return doctest::String(e.message().c_str());
}

int main(int argc, char** argv) {
  doctest::Context context(argc, argv);
  return context.run();
}
