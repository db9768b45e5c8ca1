// Attack: the whole exercise file is an #include of the reference solution,
// by a relative path from exercises/01_ray_sphere/ to the autograder's
// reference/ folder (which setup.sh needs to prove the grader works).
#include "../../../reference/sphere.cpp"
