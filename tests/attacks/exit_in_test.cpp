// exit(0) inside a tested function: the notes' form of the quadratic ends
// the program. The tests that call it fail, saying so; the rest run on.
#include <cstdlib>

namespace {

void attack_hook() { std::exit(0); }

}  // namespace
