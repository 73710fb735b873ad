// The built-in vocal tract against the built-in tongue at rest (before gravity): every surface
// faces the tongue from its gap, whatever the tongue's refinement, and is a valid obstacle.
#include "model/vocal_tract.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "model/default_tongue.hpp"

namespace tongue::model {
namespace {

TEST(VocalTract, EachSurfaceFacesTheRestTongueFromItsGap) {
  const VocalTractGaps gaps;
  const auto tract = make_vocal_tract(gaps);
  ASSERT_EQ(tract.size(), 4u);
  // The smallest gap of each surface (the palate's is 2 mm at the ridge, 3 mm over the vault).
  const double gap[4] = {gaps.alveolar_ridge, gaps.upper_teeth, gaps.velum, gaps.pharyngeal_wall};
  for (int refinement : {1, 2}) {
    const TongueModel tongue = make_default_tongue(refinement);
    for (std::size_t o = 0; o < tract.size(); ++o) {
      double nearest = std::numeric_limits<double>::infinity();
      for (const fem::Vec3& x : tongue.mesh.nodes) {
        const fem::SurfacePoint s = tract[o]->closest(x);
        if (s.valid) nearest = std::min(nearest, s.distance);
      }
      SCOPED_TRACE(tract[o]->name() + " at refinement " + std::to_string(refinement));
      // In front of every node. The sheets are the refinement-4 surface moved out along its
      // normals: a coarser tongue's faces cut a little inside that surface, so its nodes sit on
      // it and the distance is the gap, less what the offset loses on the surface's curvature
      // and where the lateral margins' normals tilt (measured: 78-92 % of the gap).
      EXPECT_GT(nearest, 0.7 * gap[o]);
      EXPECT_LT(nearest, 1.05 * gap[o] + 1e-4);
    }
  }
}

}  // namespace
}  // namespace tongue::model
