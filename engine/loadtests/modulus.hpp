// Young's modulus from a compression curve: the stress-strain slope of the intact rising branch.
#pragma once

#include <optional>
#include <vector>

#include "engine/loadtests/result.hpp"

namespace rockcal {

// Fractions of the reference load between which the slope is fitted (ISRM-style average modulus).
constexpr double kModulusLow = 0.2, kModulusHigh = 0.5;
// A fall of this fraction below the running maximum, with bonds broken, is a failure event.
constexpr double kFailureDrop = 0.05;

// Load (from `base_load`) at the first failure event of the curve: the running maximum when the
// load first falls kFailureDrop below it with bonds broken; the peak if it never does. A small
// FCC specimen can shed its edge bonds, drop, and then harden on its frictional contacts to a
// much later peak; the elastic slope belongs to the branch before that first drop.
double first_failure_load(const std::vector<CurvePoint>& curve, double base_load, double peak_load);

// Least-squares slope of stress (Pa) against strain on the rising branch before the first failure
// event, between kModulusLow and kModulusHigh of that event's load. Loads count from `base_load`
// (the triaxial test's load once confined: its modulus is that of the deviatoric loading).
std::optional<double> prepeak_modulus(const std::vector<CurvePoint>& curve, double base_load,
                                      double peak_load, double area_m2, double length_m);

}  // namespace rockcal
