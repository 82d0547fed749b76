// The scaling module (eq. 4) reproduces every derived number of the seed paper's model set-up.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "engine/packing/fcc.hpp"
#include "engine/units.hpp"

using namespace rockcal;

namespace {

std::map<std::string, std::string> read_oracle() {
  const std::string path = std::string(ROCKCAL_SEED_DATA) + "/seed_model_scaling.csv";
  std::ifstream in(path);
  EXPECT_TRUE(in) << "missing " << path;
  std::map<std::string, std::string> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("quantity,", 0) == 0) continue;
    std::stringstream ss(line);
    std::string key, value;
    std::getline(ss, key, ',');
    std::getline(ss, value, ',');
    out[key] = value;
  }
  return out;
}

double num(const std::map<std::string, std::string>& m, const std::string& key) {
  auto it = m.find(key);
  EXPECT_NE(it, m.end()) << key;
  return it == m.end() ? 0.0 : std::stod(it->second);
}

// Relative agreement to the paper's printed precision.
void expect_close(double actual, double printed, double rel, const std::string& what) {
  EXPECT_NEAR(actual / printed, 1.0, rel)
      << what << ": computed " << actual << ", paper " << printed;
}

}  // namespace

TEST(Scaling, ReproducesTheSeedPapersModelSetUp) {
  const auto oracle = read_oracle();
  ASSERT_FALSE(oracle.empty());
  const LabMaterial lab{12.33e9, 0.2, 2711.6, 0.001};
  const ModelChoice model{8000.0, 1.0, 1.0};
  // The paper fixed the model height at 139 for the 147.05 mm specimen: x2/x1 = H2/H1.
  const double h1 = 0.14705, h2 = num(oracle, "H2_m");
  const Scaling s = make_scaling(lab, model, h2 / h1);

  expect_close(s.kr_lab_n_m, num(oracle, "K_r1_N_per_m"), 5e-4, "K_r1");
  expect_close(stiffness_from_kr(1.0, 0.2, 1.0).ks_n_m, num(oracle, "K_s1_over_K_r1"), 1e-6,
               "K_s/K_r");
  EXPECT_GE(s.length, 940.0);  // the paper quotes 950-1000; its own numbers follow from 945.3
  EXPECT_LE(s.length, 1000.0);
  expect_close(s.mass, num(oracle, "m2_over_m1"), 5e-4, "m2/m1");
  expect_close(s.time, num(oracle, "t2_over_t1"), 5e-4, "t2/t1");
  expect_close(s.velocity, num(oracle, "V2_over_V1"), 5e-4, "V2/V1");
  expect_close(s.velocity_to_model(4.2167e-6), num(oracle, "V2_m_per_s"), 5e-4, "V2");
  expect_close(s.force_to_model(311000.0), num(oracle, "F2_uct_n"), 5e-4, "F2");
  expect_close(s.length_to_model(h1), h2, 1e-9, "H2");
  // Round trips.
  EXPECT_NEAR(s.force_to_lab(s.force_to_model(51900.0)), 51900.0, 1e-6);
  EXPECT_NEAR(s.stress_to_lab(s.stress_to_model(133.5e6)), 133.5e6, 1e-3);

  // The rate the paper actually used, 8e-4, is about 5000 times the mapped lab rate.
  const double speedup = num(oracle, "V2_used_m_per_s") / num(oracle, "V2_m_per_s");
  EXPECT_GT(speedup, 4500.0);
  EXPECT_LT(speedup, 5000.0);

  // Its full-size UCT sample: D2 = 49, H2 = 139, R = 1 held 44394 particles.
  const auto centres = fcc_centres(Cylinder{num(oracle, "D2_m"), h2}, 1.0);
  // The paper does not document its cut; ours lands 2.9% below (see packing/fcc.hpp).
  expect_close(static_cast<double>(centres.size()), num(oracle, "particles"), 0.04, "particles");
}

TEST(Scaling, GrainForGrainLengthRatioByDefault) {
  const Scaling s = make_scaling({12.33e9, 0.2, 2711.6, 0.001}, {8000.0, 1.0, 1.0});
  EXPECT_DOUBLE_EQ(s.length, 1000.0);
  EXPECT_NEAR(s.stress, s.force / 1e6, 1e-15);
}

TEST(Scaling, ARefinementKeepsTheMaterialsModulusAndStresses) {
  // The diagnosis's finer models: particles 1.25x smaller. K_r follows eq. 3 at the same Young's
  // modulus, and a bond's strength over its cross-section (~ R^2) stays: the same stress.
  const Refinement fine{1.25};
  const double E = 1e4, nu = 0.2, R = 1.0;
  EXPECT_DOUBLE_EQ(fine.radius(R), 0.8);
  EXPECT_NEAR(fine.kr(kr_from_youngs_modulus(E, nu, R)), kr_from_youngs_modulus(E, nu, 0.8),
              1e-9 * kr_from_youngs_modulus(E, nu, R));
  EXPECT_NEAR(fine.strength(64.0) / (0.8 * 0.8), 64.0 / (R * R), 1e-12);
}
