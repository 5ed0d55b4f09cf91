// Materials in OpenPBR's terms (sss/bssrdf/subsurface_appearance.h): a subsurface colour and a
// radius become σ_a and σ_s whose standard-dipole total is the colour — checked against the
// closed form of tests/support/dipole_totals.h, an implementation of its own — and the round trips
// both ways give back what went in.
#include "sss/bssrdf/subsurface_appearance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "support/dipole_totals.h"

namespace tallow::sss {
namespace {

TEST(SubsurfaceAppearance, TheMaterialsDipoleTotalIsTheColourAndItsMeanFreePathTheRadius) {
  for (const float eta : {1.0f, 1.3f, 1.5f})
    for (const glm::vec3 color : {glm::vec3(0.8f, 0.5f, 0.2f), glm::vec3(0.0f, 0.01f, 0.999f), glm::vec3(1.0f)}) {
      SubsurfaceAppearance a;
      a.color = color;
      a.radiusMm = 2.5f;
      a.radiusScale = {1.0f, 0.5f, 0.25f};
      a.eta = eta;
      a.g = glm::vec3(0.3f);
      const Material m = materialFromAppearance(a);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(test::jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta), color[c], 2e-6)
            << "band " << c << ", eta " << eta;
        const double sigmaTp = m.sigma_a[c] + m.sigma_s[c] * (1.0 - m.g[c]);
        EXPECT_NEAR(1.0 / sigmaTp, 2.5 * a.radiusScale[c], 1e-5) << "band " << c;
        EXPECT_GE(m.sigma_a[c], 0.0f);
      }
    }
}

TEST(SubsurfaceAppearance, RoundTripsBothWays) {
  // Appearance → material → appearance, and a measured-like material → appearance → material.
  SubsurfaceAppearance a;
  a.color = {0.7f, 0.45f, 0.12f};
  a.radiusMm = 4.0f;
  a.radiusScale = {1.0f, 0.6f, 0.3f};
  a.eta = 1.4f;
  const SubsurfaceAppearance back = appearanceOf(materialFromAppearance(a));
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(back.color[c], a.color[c], 1e-6f);
    EXPECT_NEAR(back.radiusMm * back.radiusScale[c], a.radiusMm * a.radiusScale[c], 1e-5f);
  }
  Material marble;  // Jensen et al. 2001's marble, σ in mm⁻¹
  marble.sigma_s = {2.19f, 2.62f, 3.00f};
  marble.sigma_a = {0.0021f, 0.0041f, 0.0071f};
  marble.eta = 1.5f;
  const Material again = materialFromAppearance(appearanceOf(marble));
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(again.sigma_s[c] / marble.sigma_s[c], 1.0, 1e-4) << "band " << c;
    EXPECT_NEAR(again.sigma_a[c] / marble.sigma_a[c], 1.0, 1e-3) << "band " << c;
  }
}

TEST(SubsurfaceAppearance, ValuesOutOfRangeAreRefusedWithOneLine) {
  SubsurfaceAppearance a;
  a.radiusMm = 0.0f;
  EXPECT_THROW(materialFromAppearance(a), std::invalid_argument);
  a.radiusMm = 1.0f;
  a.radiusScale = {1.0f, -1.0f, 1.0f};
  EXPECT_THROW(materialFromAppearance(a), std::invalid_argument);
  a.radiusScale = glm::vec3(1.0f);
  a.color = {0.5f, 1.5f, 0.5f};
  EXPECT_THROW(materialFromAppearance(a), std::invalid_argument);
  a.color = glm::vec3(0.5f);
  a.g = glm::vec3(1.0f);
  EXPECT_THROW(materialFromAppearance(a), std::invalid_argument);
}

}  // namespace
}  // namespace tallow::sss
