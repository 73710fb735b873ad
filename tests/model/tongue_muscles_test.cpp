// The muscles of the built-in tongue against their anatomy (Gerard et al. 2003, sec. II.2):
// each group's fibre direction and place, the left/right halves mirror images, the published
// maximum forces (Buchaillard et al. 2009).
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "fem/mesh/boundary_faces.hpp"
#include "model/default_tongue.hpp"
#include "model/tongue_geometry.hpp"

namespace tongue::model {
namespace {

class TongueMuscles : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { tongue_ = new TongueModel(make_default_tongue()); }
  static void TearDownTestSuite() { delete tongue_; }

  static const Muscle& muscle(const std::string& name) {
    for (const Muscle& m : tongue_->muscles)
      if (m.name == name) return m;
    throw std::invalid_argument("no muscle " + name);
  }
  static fem::Vec3 x(int node) { return tongue_->mesh.nodes[node]; }
  static fem::Vec3 start(const Fibre& f) { return f.origin ? *f.origin : x(f.nodes.front()); }
  // Unit vector from a fibre's start (its bony origin if any) to its end.
  static fem::Vec3 direction(const Fibre& f) { return (x(f.nodes.back()) - start(f)).normalized(); }
  // Smallest |component c| of the fibres' unit end-to-end directions.
  static double least_alignment(const Muscle& m, int c) {
    double least = 1.0;
    for (const Fibre& f : m.fibres) least = std::min(least, std::abs(direction(f)[c]));
    return least;
  }

  static TongueModel* tongue_;
};
TongueModel* TongueMuscles::tongue_ = nullptr;

TEST_F(TongueMuscles, TenGroupsInNineteenIndependentlyDrivenMuscles) {
  EXPECT_EQ(muscle_groups().size(), 10u);
  EXPECT_EQ(tongue_->muscles.size(), 19u);  // 9 paired groups x 2 + SL
  for (const MuscleGroup& g : muscle_groups()) {
    double total = 0.0;
    for (const Muscle& m : tongue_->muscles) {
      if (m.name == g.name || m.name.rfind(g.name + "_", 0) == 0) total += m.max_force;
    }
    EXPECT_DOUBLE_EQ(total, g.max_force) << g.name;  // both halves together
    EXPECT_FALSE(tongue_->mesh.element_set(g.paired ? g.name + "_left" : g.name).empty());
  }
}

TEST_F(TongueMuscles, HalvesAreMirrorImages) {
  for (const MuscleGroup& g : muscle_groups()) {
    if (!g.paired) continue;
    const Muscle& l = muscle(g.name + "_left");
    const Muscle& r = muscle(g.name + "_right");
    ASSERT_EQ(l.fibres.size(), r.fibres.size()) << g.name;
    EXPECT_EQ(l.elements.size(), r.elements.size()) << g.name;
    for (std::size_t f = 0; f < l.fibres.size(); ++f) {
      ASSERT_EQ(l.fibres[f].nodes.size(), r.fibres[f].nodes.size());
      for (std::size_t q = 0; q < l.fibres[f].nodes.size(); ++q) {
        const fem::Vec3 a = x(l.fibres[f].nodes[q]), b = x(r.fibres[f].nodes[q]);
        EXPECT_LT((a - fem::Vec3(b.x(), b.y(), -b.z())).norm(), 1e-15) << g.name;
        EXPECT_GE(a.z(), 0.0) << g.name;  // the left half is on the left (z >= 0)
      }
    }
  }
}

TEST_F(TongueMuscles, TransversalisRunsLaterally) {
  // End-to-end directions within 25 degrees of the z axis (cos 25 = 0.91): the fibres follow the
  // lateral grid lines from the septum out, which bend only with the rounded margins.
  EXPECT_GT(least_alignment(muscle("T_left"), 2), 0.9);
  for (const Fibre& f : muscle("T_left").fibres) EXPECT_EQ(x(f.nodes.front()).z(), 0.0);
}

TEST_F(TongueMuscles, VerticalisRunsVerticallyAwayFromTheMidline) {
  // The fan's radial lines over V lie 50 to 123 degrees from the anterior axis, within 40 degrees
  // of vertical at the midline; the domed margins tilt them a little more: 0.7 = 45 degrees.
  EXPECT_GT(least_alignment(muscle("V_left"), 1), 0.7);
  for (const Fibre& f : muscle("V_left").fibres)
    for (int n : f.nodes) EXPECT_GT(x(n).z(), 0.003);  // no V near the midline
}

TEST_F(TongueMuscles, SuperiorLongitudinalRunsAlongTheDorsumToTheTip) {
  const std::vector<int> surface = fem::boundary_nodes(tongue_->mesh);
  const Muscle& sl = muscle("SL");
  const int tip = tongue_->mesh.node_set("tip").front();
  bool reaches_tip = false;
  for (const Fibre& f : sl.fibres) {
    for (int n : f.nodes) EXPECT_TRUE(std::binary_search(surface.begin(), surface.end(), n));
    EXPECT_LT(x(f.nodes.front()).x(), -0.05);  // starts low in the pharynx, behind
    EXPECT_GT(x(f.nodes.back()).x(), 0.0);     // ends at the front
    reaches_tip |= f.nodes.back() == tip;
  }
  EXPECT_TRUE(reaches_tip);
}

TEST_F(TongueMuscles, GenioglossusRadiatesFromItsInsertion) {
  const fem::Vec3 insertion = BonyAttachments{}.mandible_insertion;
  for (const std::string name : {"GGa_left", "GGm_left", "GGp_left"}) {
    for (const Fibre& f : muscle(name).fibres) {
      ASSERT_TRUE(f.origin.has_value());
      EXPECT_LT((*f.origin - insertion).norm(), 1e-12);
      // Every segment points away from the insertion within 30 degrees.
      fem::Vec3 previous = *f.origin;
      for (int n : f.nodes) {
        const fem::Vec3 seg = x(n) - previous, radial = x(n) - insertion;
        EXPECT_GT(seg.normalized().dot(radial.normalized()), std::cos(M_PI / 6)) << name;
        previous = x(n);
      }
    }
  }
  // Anterior, medium and posterior parts in that order around the fan.
  auto mean_x = [&](const std::string& name) {
    double s = 0.0;
    for (const Fibre& f : muscle(name).fibres)
      s += x(f.nodes.back()).x() / muscle(name).fibres.size();
    return s;
  };
  EXPECT_GT(mean_x("GGa_left"), mean_x("GGm_left"));
  EXPECT_GT(mean_x("GGm_left"), mean_x("GGp_left"));
}

TEST_F(TongueMuscles, MylohyoidRunsSideToSideInTheFloor) {
  EXPECT_GT(least_alignment(muscle("MH_left"), 2), 0.8);  // within 37 degrees of lateral
  for (const Fibre& f : muscle("MH_left").fibres) {
    for (int n : f.nodes) EXPECT_LT(x(n).y(), 0.0);  // the floor lies below the insertion
    EXPECT_EQ(x(f.nodes.back()).z(), 0.0);           // to the midline
  }
}

TEST_F(TongueMuscles, StyloglossusComesFromTheStyloidForwardAlongTheSides) {
  const fem::Vec3 styloid = BonyAttachments{}.styloid_process;
  const TongueGrid& g = tongue_->grid;
  const int layer_size = (g.size.angular + 1) * (g.size.radial + 1);
  int forward = 0;
  for (const Fibre& f : muscle("SG_left").fibres) {
    ASSERT_TRUE(f.origin.has_value());
    EXPECT_LT((*f.origin - styloid).norm(), 1e-12);
    const fem::Vec3 first = x(f.nodes.front()), last = x(f.nodes.back());
    if (last.x() > first.x() + 0.03) {  // the forward group: more than 30 mm toward the tip
      ++forward;
      // Along the side: in the three outermost lateral node layers (lateral fraction >= 0.75).
      for (int n : f.nodes) EXPECT_GE(n / layer_size, g.midline() + 3 * g.refinement);
    }
  }
  EXPECT_GT(forward, 0);
  EXPECT_LT(styloid.x(), -0.05);  // behind and above the tongue body
  EXPECT_GT(styloid.y(), 0.05);
}

TEST_F(TongueMuscles, HyoglossusRisesFromTheHyoidAlongTheBackSides) {
  for (const Fibre& f : muscle("HG_left").fibres) {
    ASSERT_TRUE(f.origin.has_value());
    EXPECT_LT(f.origin->y(), x(f.nodes.front()).y());  // the hyoid is below
    // Rises over 15 mm (the paper's HG is 34 mm tall; three angular elements of the back here).
    EXPECT_GT(x(f.nodes.back()).y(), x(f.nodes.front()).y() + 0.015);
    EXPECT_LT(x(f.nodes.back()).x(), -0.02);  // behind the insertion
    EXPECT_GT(x(f.nodes.back()).z(), 0.01);   // on the side
  }
}

TEST_F(TongueMuscles, InferiorLongitudinalRunsLowFromTipToRoot) {
  double il_y = 0.0, sl_y = 0.0;
  int il_n = 0, sl_n = 0;
  for (const Fibre& f : muscle("IL_left").fibres) {
    double length = 0.0;  // along the fibre, from the root to the underside of the tip
    for (std::size_t q = 0; q + 1 < f.nodes.size(); ++q)
      length += (x(f.nodes[q + 1]) - x(f.nodes[q])).norm();
    EXPECT_GT(length, 0.05);
    EXPECT_GT(x(f.nodes.back()).x(), 0.0);  // ends in front of the insertion, under the tip
    for (int n : f.nodes) il_y += x(n).y(), ++il_n;
  }
  for (const Fibre& f : muscle("SL").fibres)
    for (int n : f.nodes) sl_y += x(n).y(), ++sl_n;
  EXPECT_LT(il_y / il_n, sl_y / sl_n - 0.015);  // well below the superior longitudinal
  for (const Fibre& f : muscle("IL_left").fibres)
    for (int n : f.nodes) EXPECT_GT(x(n).z(), 0.0);  // beside the genioglossus, not in it
}

}  // namespace
}  // namespace tongue::model
