#pragma once
// The 8 muscles of Gerard et al. 2003 (sec. II.2) in 10 groups, placed on the fan grid as ranges
// of grid indices: GGp, GGm, GGa (genioglossus posterior, medium, anterior), HG (hyoglossus),
// SG (styloglossus), SL (superior longitudinal), IL (inferior longitudinal), T (transversalis),
// V (verticalis), MH (mylohyoid). Paired muscles come as two independently driven halves,
// "<group>_left" (z > 0) and "<group>_right"; SL is unpaired.
#include <string>
#include <vector>

#include "model/muscle.hpp"
#include "model/tongue_geometry.hpp"

namespace tongue::model {

struct MuscleGroup {
  std::string name;
  double max_force;  // both sides together [N] (Buchaillard et al. 2009)
  bool paired;
};

// The 10 groups with their published maximum forces.
const std::vector<MuscleGroup>& muscle_groups();

// External bony attachments [m], in the tongue's coordinates (left side; mirror z for the right).
struct BonyAttachments {
  fem::Vec3 mandible_insertion{0.0, 0.0, 0.0};          // superior mental spine (origin)
  fem::Vec3 styloid_process{-0.070, 0.075, 0.040};      // behind, well above, lateral
  fem::Vec3 hyoid_greater_horn{-0.060, -0.030, 0.016};  // below and behind the root
  fem::Vec3 hyoid_body{-0.050, -0.028, 0.006};          // below the root, near the midline
  // The mylohyoid line on the mandible's inner side, relative to the floor's lateral edge.
  double mylohyoid_line_offset = 0.008;  // farther out laterally [m]
  double mylohyoid_line_rise = 0.006;    // higher [m]
};

// All muscles of the grid, halves with F_max / 2 each; fibre weights equal within a muscle.
std::vector<Muscle> place_muscles(const TongueGrid& grid, const BonyAttachments& bones = {});

}  // namespace tongue::model
