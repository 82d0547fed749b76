// Cauchy-Born check: eq. 3's stiffnesses give E and nu exactly for [100] loading of FCC, so the
// elastic test on the interior of a specimen must recover the input within 3%.
#include <gtest/gtest.h>

#include "engine/loadtests/driver.hpp"
#include "engine/units.hpp"

using namespace rockcal;

TEST(ElasticFcc, RecoversYoungsModulusAndPoissonRatio) {
  for (double nu : {0.2, 0.25}) {
    JobSpec s;
    s.test = TestKind::elastic;
    s.sample.diameter_m = 20;
    s.sample.height_m = 40;
    s.material.youngs_modulus_pa = 6000.0;
    s.material.nu = nu;
    const TestResult r = run_test(s);
    ASSERT_TRUE(r.youngs_modulus_pa && r.poisson_ratio);
    EXPECT_EQ(r.broken_bonds, 0);
    EXPECT_EQ(r.stop_reason, "settled");
    EXPECT_NEAR(*r.youngs_modulus_pa / 6000.0, 1.0, 0.03) << "nu " << nu;
    EXPECT_NEAR(*r.poisson_ratio / nu, 1.0, 0.03) << "nu " << nu;
    RecordProperty("E_error_nu_" + std::to_string(nu),
                   std::to_string(*r.youngs_modulus_pa / 6000.0 - 1.0));
    RecordProperty("nu_error_nu_" + std::to_string(nu),
                   std::to_string(*r.poisson_ratio / nu - 1.0));
  }
}
