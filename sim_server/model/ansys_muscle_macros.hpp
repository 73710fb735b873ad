#pragma once
// Importer for muscle definitions written as ANSYS macros, as the Grenoble tongue model and its
// ArtiSynth descendants distribute them: a macro that stores the muscles' elements as named
// element components (CreateMuscles.mac), a macro that fills fibre arrays (Fibers.mac) and a
// table of maximum forces (MuscleMaxForce.txt). The result keeps the files' ids; the scene
// builder turns them into indices with the mesh's id tables.
//
// All three files are read line by line; a line may end in CRLF, and bytes outside ASCII
// (Latin-1 accents) are allowed in comments only. Comments: from '!' to the end of the line, and
// lines starting with "/COM" or "C***". Commands are case-insensitive; names keep their case.
//
// Elements file: the commands
//   ESEL,S,ELEM,,a[,b[,inc]]   a new selection: element ids a, a + inc, ... up to b (b defaults
//                              to a, inc to 1)
//   ESEL,A,ELEM,,a[,b[,inc]]   add to the selection;  ESEL,U,...: remove;  ESEL,R,...: keep
//                              only those also in the range
//   ESEL,NONE                  empty the selection
//   CM,NAME,ELEM               the selection becomes the bundle NAME (a letter, then letters,
//                              digits or '_', at most 32 characters)
// A CM of an empty selection (typically the closing "ESEL,NONE" then "CM,...") is not a muscle:
// it is listed in `ignored_components`. The lines "/PREP7", "FINISH", "ALLSEL", "/NOPR", "/GOPR"
// and "*DIM,..." are accepted and have no effect; any other command is an error.
//
// Fibres file: assignments
//   NB_NODES_FIBER(f,m)=n      fibre f of muscle m has n points
//   FIBER(k,f,m)=id            its k-th point (k = 1..n) is node id (or an external point's id)
// with muscle m the m-th bundle of the elements file in file order; every bundle needs at least
// one fibre, fibre numbers f of a muscle run from 1 without gaps, and every point 1..n is given
// exactly once.
//
// Max-force file: one line per bundle, either "NAME value" (any order, every bundle once) or the
// values alone, in the bundles' order; forces in N, finite and positive.
//
// External points (bone attachments such as the styloid process) appear in the fibres file as
// ids that are not mesh nodes. A fibre may start or end at one: it becomes the fibre's origin,
// and a fibre ending at it is reversed so that it runs from the external point into the tongue.
// An external point elsewhere on a fibre, or at both ends, is an error.
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fem/types.hpp"

namespace tongue::model {

// A malformed or unreadable macro file: what() reads "<path>, line <n>: <reason>", or
// "<path>: <reason>" for the whole file.
class MacroReadError : public std::runtime_error {
 public:
  MacroReadError(const std::string& path, int line, const std::string& reason);
  const std::string& path() const { return path_; }
  int line() const { return line_; }  // 1-based; 0 for the whole file

 private:
  std::string path_;
  int line_;
};

struct AnsysMuscleFiles {
  std::string elements;   // CreateMuscles.mac
  std::string fibres;     // Fibers.mac
  std::string max_force;  // MuscleMaxForce.txt
  // Id in the fibres file -> position [m] of a fixed point outside the mesh.
  std::map<long, fem::Vec3> external_points;
};

struct ImportedFibre {
  std::vector<long> node_ids;       // mesh node ids in order, away from the origin
  std::optional<fem::Vec3> origin;  // the external point the fibre starts (or ended) at [m]
  bool reversed = false;            // the fibres file lists it from the mesh to the origin
  std::string source;               // "<fibres file>, line <n>" of its NB_NODES_FIBER
};

struct ImportedMuscle {
  std::string name;
  std::vector<long> element_ids;  // ascending
  std::vector<ImportedFibre> fibres;
  double max_force = 0.0;  // N
  std::string source;      // "<elements file>, line <n>" of its CM
};

struct ImportedMuscles {
  std::vector<ImportedMuscle> muscles;          // in the elements file's order
  std::vector<std::string> ignored_components;  // CMs of an empty selection
};

// Reads the three files. Throws MacroReadError naming the file and line for anything the
// format above does not allow. External points no fibre uses are ignored.
ImportedMuscles import_ansys_muscles(const AnsysMuscleFiles& files);

}  // namespace tongue::model
