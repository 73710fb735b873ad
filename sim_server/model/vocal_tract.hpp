#pragma once
// The built-in vocal tract: rigid surfaces around the built-in tongue that it meets when it
// moves, each a sheet at a chosen gap from the tongue's rest surface (the fan grid of
// tongue_geometry.hpp at refinement 4, whatever the tongue's own refinement), so that it fits
// the built-in tongue by construction:
//   "hard_palate": over the dorsum from the tip back to about a third of the dorsum, continued
//       down in front of the tip as the alveolar ridge behind the upper incisors;
//   "upper_teeth": the lingual faces of the upper dental arch, beside the tongue's front two
//       fifths, from its lateral margins down to half its height;
//   "velum": the soft palate (rigid here), over the middle third of the dorsum, 30 mm wide;
//   "pharyngeal_wall": behind the root, the dorsum's back third.
// The palate and the teeth meet along the tongue's lateral margins; each goes on 3 mm past that
// edge, so that the two cross and no node slips out between them.
// Its coordinates are the tongue's (origin at the genioglossus insertion, x anterior, y up, z to
// the left) [m]. The gaps (vocal_tract_gaps) leave the tongue free at rest under gravity and put
// each surface within reach of the paper's muscles: docs/contact.md.
#include <memory>
#include <string>
#include <vector>

#include "fem/contact/obstacle.hpp"

namespace tongue::model {

struct VocalTractGaps {
  double alveolar_ridge = 0.002;   // m, along the tongue's outward normal at rest
  double hard_palate = 0.003;      // m
  double upper_teeth = 0.003;      // m
  double velum = 0.002;            // m
  double pharyngeal_wall = 0.007;  // m
};

// The four surfaces, in the order above, their normals toward the tongue.
std::vector<std::shared_ptr<const fem::Obstacle>> make_vocal_tract(const VocalTractGaps& gaps = {});

}  // namespace tongue::model
