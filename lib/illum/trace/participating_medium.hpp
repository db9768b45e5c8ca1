#pragma once
// The transport equation along a ray (lesson 06, §1, eq. 6.2), in a slab of
// homogeneous medium, integrated step by step and compared with its closed
// form. With in-scattering off, the equation along the ray is
//   dI/ds = −K_t·I + K_a·I_e,
// whose solution after a thickness d is
//   I(d) = I₀·e^(−K_t·d) + (K_a·I_e / K_t)·(1 − e^(−K_t·d))     (eq. 6.3)
// and, with emission off too, Beer–Lambert's I₀·e^(−K_t·d).
namespace illum {

struct Slab {
  double extinction = 1.0;  // K_t > 0, per unit length
  double emission = 0.0;    // K_a·I_e ≥ 0, radiance added per unit length
  double thickness = 1.0;   // d > 0
};

// The knob of the marching: the method and the number of steps.
enum class MarchMethod { euler, midpoint };
const char* to_string(MarchMethod method);

// I after crossing the slab, marching `steps` equal steps (steps ≥ 1).
// Euler's error falls as 1/steps, the midpoint rule's as 1/steps².
double march_through_slab(const Slab& slab, double incoming, int steps, MarchMethod method);

// The closed form (eq. 6.3).
double slab_closed_form(const Slab& slab, double incoming);

}  // namespace illum
