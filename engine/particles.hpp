// The particle set: structure of arrays so the time-step loops stream through contiguous memory.
// Under domain decomposition the first `n_owned` entries are this rank's particles and the rest are
// ghosts: read-only copies of neighbours' particles near the border, refreshed every step.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "engine/vec.hpp"

namespace rockcal {

constexpr int kMaxWalls = 2;

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
  std::vector<std::int64_t> id;  // global identity: survives reordering and migration
  std::vector<std::array<Vec3, kMaxWalls>> wall_spring;  // platen friction history, m
  // 1 = on the lateral surface of a triaxial specimen: the confining pressure acts on it. Set once
  // at set-up and carried with migrating particles (ghosts do not need it).
  std::vector<std::uint8_t> confined;
  std::size_t n_owned = 0;

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
    wall_spring.push_back({Vec3::Zero(), Vec3::Zero()});
    confined.push_back(0);
    n_owned = size();
  }

  void resize(std::size_t n) {
    pos.resize(n);
    vel.resize(n);
    orient.resize(n);
    omega.resize(n);
    force.resize(n);
    torque.resize(n);
    radius.resize(n);
    mass.resize(n);
    inertia.resize(n);
    id.resize(n);
    wall_spring.resize(n);
    confined.resize(n);
  }

  // Copies particle `from` over particle `to` (same array).
  void copy(std::size_t from, std::size_t to) {
    pos[to] = pos[from];
    vel[to] = vel[from];
    orient[to] = orient[from];
    omega[to] = omega[from];
    force[to] = force[from];
    torque[to] = torque[from];
    radius[to] = radius[from];
    mass[to] = mass[from];
    inertia[to] = inertia[from];
    id[to] = id[from];
    wall_spring[to] = wall_spring[from];
    confined[to] = confined[from];
  }

  void clear_loads() {
    for (auto& f : force) f.setZero();
    for (auto& t : torque) t.setZero();
  }
};

}  // namespace rockcal
