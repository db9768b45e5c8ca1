// Attack: the exercise file asks the compiler what the grader keeps beside the tree (the
// witness's records, the hidden tests' objects, the build of the reference) and quotes what it
// finds in a compile error, which the student reads in the build entry.
#if __has_include("../../../grader/tests.json")
#error "GRADER-FILE-VISIBLE: grader/tests.json exists"
#endif
#if __has_include("../../../grader/hidden-objects/00_lesson01_hidden.cpp.o")
#error "GRADER-FILE-VISIBLE: a hidden object exists"
#endif
#include "../../../grader/tests.json"
