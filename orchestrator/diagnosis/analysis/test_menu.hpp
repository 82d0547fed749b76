// The lab tests a diagnosis may propose next: conditions a dataset observation can have, derived
// from the dataset's own specimen, that the dataset does not already have. A squat (H/D = 1) and a
// slender (H/D = 3) UCT, the UCT's Young's modulus and peak strain, a disc of half and of double
// thickness, the UCT and the disc at 4x the platen speed, and triaxial tests at 0.1, 0.3 and 0.6
// of the dataset's UCS.
#pragma once

#include <string>
#include <vector>

#include "orchestrator/diagnosis/analysis/observations.hpp"

namespace rockcal::diagnosis {

struct MenuTest {
  Target target;            // id "menu-...", role held_out, value 0 (not measured), model units
  std::string description;  // "a squat UCT (H/D = 1)"
};

// The platen speed of the menu's fast tests, as a multiple of the specimen's.
inline constexpr double kMenuSpeedFactor = 4.0;

// The confinements of the menu's triaxial tests, as fractions of the dataset's UCS.
inline constexpr double kMenuConfinements[] = {0.1, 0.3, 0.6};

// The menu for a dataset's targets (model units). The specimen is the first calibration UCT's (else
// any UCT's or triaxial's, else the first observation's diameter with H = 2 D), the disc the first
// BTT's (else that diameter, t = D / 2), the UCS from the first UCT peak load or strength (no
// triaxial without one); every test runs at the specimen's platen speed. A test the dataset has
// (same test, observable and conditions; a confinement within 10% of one it has) is left out.
// A triaxial takes the observable of the dataset's triaxials (peak load unless they give strength).
// A target's sigma is 0 here: the next test borrows its noise (next_test.hpp).
std::vector<MenuTest> test_menu(const std::vector<Target>& targets);

// The targets followed by the menu's: the conditions a next-test batch runs on.
std::vector<Target> with_menu(std::vector<Target> targets, const std::vector<MenuTest>& menu);

}  // namespace rockcal::diagnosis
