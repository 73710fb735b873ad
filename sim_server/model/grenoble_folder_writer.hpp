#pragma once
// The built-in tongue (model/default_tongue.hpp) written as a user's folder of Grenoble files,
// the input of docs/your_tongue.md and of the scene templates scenes/templates/grenoble_*.yaml:
//   tongue.node, tongue.elem     the mesh (ANSYS NWRITE/EWRITE, 17 significant digits), node and
//                                element ids = index + 1
//   CreateMuscles.mac, Fibers.mac, MuscleMaxForce.txt
//                                the muscles (model/ansys_muscle_macro_writer.hpp), in the
//                                built-in order, named as Grenoble bundles (grenoble_bundle_name)
//   external_points.txt          the fibres' bony origins: "id x y z" lines in m, ids after the
//                                last node id, one per distinct point
//   jaw_nodes.txt, hyoid_nodes.txt, root_bottom_nodes.txt
//                                the "mandible", "hyoid" and "root_bottom" node sets, one-based
//   landmarks/<name>.txt         tip, blade, palatal_dorsum, velar_dorsum, root: node ids
// Every fibre starts at its origin when it has one, as the built-in fibres do, so that the
// importer gives back the built-in muscles exactly.
#include <map>
#include <string>
#include <vector>

#include "fem/types.hpp"

namespace tongue::model {

struct GrenobleFolder {
  std::map<long, fem::Vec3> external_points;  // id -> position [m], as in external_points.txt
  std::vector<std::string> bundles;           // the muscles' names, in the files' order
};

// The Grenoble name of a built-in muscle: the group's (GGp -> GGP, SG -> STY, T -> TRANS,
// V -> VERT; the others in capitals) with "_left" -> "_L" and "_right" -> "_R"; "SL" stays.
std::string grenoble_bundle_name(const std::string& builtin_name);

// Writes the folder (created if missing; existing files of these names are replaced) for the
// built-in tongue at the given refinement. length_scale is the file unit in m: 1e-3 for mm, as
// the templates read, or 1 for files that read back bit for bit with length_scale: 1. Throws
// std::invalid_argument for a bad refinement or length_scale and std::runtime_error naming a
// file or folder that cannot be written.
GrenobleFolder write_builtin_tongue_folder(const std::string& dir, int refinement,
                                           double length_scale);

}  // namespace tongue::model
