// Small fixed-size vector and rotation types used throughout the engine.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rockcal {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;  // unit quaternion: body frame -> world frame

// Rotation vector (axis * angle, angle in [0, pi]) of a unit quaternion.
inline Vec3 rotation_vector(Quat q) {
  if (q.w() < 0) q.coeffs() = -q.coeffs();  // q and -q are the same rotation
  const double s = q.vec().norm();
  if (s < 1e-300) return Vec3::Zero();
  return (2.0 * std::atan2(s, q.w()) / s) * q.vec();
}

}  // namespace rockcal
