// A crash: the notes' form of the quadratic writes through a null pointer.
// Only the tests that call it may fail; the rest of the lesson runs on.
namespace {

void attack_hook() {
  volatile int* nowhere = nullptr;
  *nowhere = 1;
}

}  // namespace
