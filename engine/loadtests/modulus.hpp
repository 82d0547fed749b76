// Young's modulus from a compression curve: the stress-strain slope of the intact rising branch.
#pragma once

#include <cstddef>
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

// The curve rows every pre-peak slope is fitted over: the rising branch before the first
// failure event's load is first reached (rows before `end`), with loads (from the base load)
// between kModulusLow and kModulusHigh of that event's load.
struct ModulusWindow {
  double base_load = 0.0, low_n = 0.0, high_n = 0.0;
  std::size_t end = 0;
  bool contains(const std::vector<CurvePoint>& curve, std::size_t row) const {
    const double load = curve[row].load_n - base_load;
    return row < end && load >= low_n && load <= high_n;
  }
};
ModulusWindow modulus_window(const std::vector<CurvePoint>& curve, double base_load,
                             double peak_load);

// Least-squares line through (x, y) points: its slope once three points with distinct x are in.
struct LineFit {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  void add(double x, double y);
  std::optional<double> slope() const;
};

// Least-squares slope of stress (Pa) against strain (platen closure over the loaded length) over
// the modulus window. Loads count from `base_load` (the triaxial test's load once confined: its
// modulus is that of the deviatoric loading).
std::optional<double> prepeak_modulus(const std::vector<CurvePoint>& curve, double base_load,
                                      double peak_load, double area_m2, double length_m);

}  // namespace rockcal
