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

// The palate's lateral edges are the teeth's upper ones. Beyond the rim of an open sheet a point
// is neither in front of it nor behind it, so two sheets that only met there would leave a line
// that a node could slip through, out of the tongue's corner between them: each goes on past
// the edge, and every point outside the edge is behind one of them. Walked out from the
// tongue's corner through each vertex the two sheets share (a vertex lies at its gap from a
// tongue node along that node's normal), to 0.5, 1 and 2 mm beyond it.
TEST(VocalTract, NoWayOutBetweenThePalateAndTheTeeth) {
  const auto tract = make_vocal_tract();
  const fem::Obstacle &palate = *tract[0], &teeth = *tract[1];
  const TongueModel tongue = make_default_tongue(4);  // the grid the sheets are offset from
  int shared = 0;
  for (const fem::Vec3& v : palate.surface().vertices) {
    bool on_teeth = false;
    for (const fem::Vec3& w : teeth.surface().vertices) on_teeth |= (v - w).norm() < 1e-12;
    if (!on_teeth) continue;
    ++shared;
    fem::Vec3 corner = tongue.mesh.nodes.front();
    for (const fem::Vec3& x : tongue.mesh.nodes)
      if ((x - v).norm() < (corner - v).norm()) corner = x;
    const fem::Vec3 out = (v - corner).normalized();
    for (const double beyond : {0.0005, 0.001, 0.002}) {
      const fem::Vec3 x = v + beyond * out;
      const fem::SurfacePoint p = palate.closest(x), t = teeth.closest(x);
      EXPECT_TRUE((p.valid && p.distance < 0.0) || (t.valid && t.distance < 0.0))
          << "no sheet in the way at (" << x.transpose() << ") m";
    }
  }
  EXPECT_GT(shared, 20);  // both lateral edges over the vault
}

}  // namespace
}  // namespace tongue::model
