// A link error of the student's own making: the same helper, not static and
// not in an unnamed namespace, defined in both of lesson 02's files. It must
// cost lesson 02 only, and be shown with the linker's words.
namespace illum {

double twice_for_attack(double x) { return 2.0 * x; }

}  // namespace illum
