#pragma once
// Writer for muscle definitions as ANSYS macros, in the syntax model/ansys_muscle_macros.hpp
// reads: the muscles' elements as named element components (CreateMuscles.mac), their fibres as
// fibre arrays (Fibers.mac) and their maximum forces (MuscleMaxForce.txt).
//
// The two macros end their lines with CRLF, as the Grenoble files do. The elements file selects
// each bundle with one "ESEL,S,ELEM,,a,b" for its first run of consecutive ids and "ESEL,A,..."
// for the others, names it with "CM,NAME,ELEM", and closes with an empty selection
// ("ESEL,NONE" and a CM the reader skips). The max-force file holds "NAME force" lines, forces
// in N with 17 significant digits so that they read back as the same doubles.
#include <string>
#include <vector>

namespace tongue::model {

struct MacroMuscle {
  std::string name;               // a letter, then letters, digits or '_' (at most 32)
  std::vector<long> element_ids;  // any order; repeats are written once
  // Each fibre's point ids in order: mesh node ids, or an external point's id at either end.
  std::vector<std::vector<long>> fibres;
  double max_force = 0.0;  // N
};

// Writes the three files. Throws std::invalid_argument for an invalid or repeated name, a muscle
// without elements or fibres, a fibre of fewer than 2 points, a non-positive id or a max force
// that is not finite and positive; std::runtime_error naming a file that cannot be written.
void write_ansys_muscle_macros(const std::vector<MacroMuscle>& muscles,
                               const std::string& elements_path, const std::string& fibres_path,
                               const std::string& max_force_path);

}  // namespace tongue::model
