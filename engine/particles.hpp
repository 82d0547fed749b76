// The particle set: structure of arrays so the time-step loops stream through contiguous memory.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/vec.hpp"

namespace rockcal {

struct Particles {
  std::vector<Vec3> pos;         // m
  std::vector<Vec3> vel;         // m/s
  std::vector<Quat> orient;      // body -> world
  std::vector<Vec3> omega;       // angular velocity in the world frame, rad/s
  std::vector<Vec3> force;       // N, accumulated each step
  std::vector<Vec3> torque;      // N m, accumulated each step
  std::vector<double> radius;    // m
  std::vector<double> mass;      // kg
  std::vector<double> inertia;   // kg m^2 (spheres: isotropic)
  std::vector<std::int64_t> id;  // stable identity (survives reordering and, later, migration)

  std::size_t size() const { return pos.size(); }

  void add(const Vec3& x, double r, double m, double i, std::int64_t pid) {
    pos.push_back(x);
    vel.push_back(Vec3::Zero());
    orient.push_back(Quat::Identity());
    omega.push_back(Vec3::Zero());
    force.push_back(Vec3::Zero());
    torque.push_back(Vec3::Zero());
    radius.push_back(r);
    mass.push_back(m);
    inertia.push_back(i);
    id.push_back(pid);
  }

  void clear_loads() {
    for (auto& f : force) f.setZero();
    for (auto& t : torque) t.setZero();
  }
};

}  // namespace rockcal
