#pragma once
// An XDMF 2 sidecar for a run file, so that ParaView's "XDMF Reader" (Xdmf2) opens the HDF5 time
// series: a temporal collection with one uniform grid per frame whose topology is /elements
// (hex8: ANSYS SOLID185 order is the VTK and XDMF Hexahedron order, so no reordering) and whose
// geometry is the hyperslab of /positions that selects the frame. The heavy data stay in the
// HDF5 file; the sidecar names it by its file name alone, so the pair can be moved together.
#include <string>
#include <vector>

namespace tongue::run_file {

struct XdmfRun {
  std::string h5_file;         // as written into the sidecar, e.g. "run.h5"
  std::vector<double> times;   // /time, one per frame
  long long num_nodes = 0;     // N of /positions [T x N x 3] and /rest_positions [N x 3]
  long long num_elements = 0;  // E of /elements [E x 8]
};

// The sidecar's path for a run file: the same path with the extension .xmf.
std::string xdmf_sidecar_path(const std::string& h5_path);

// The XDMF text. Without frames it holds one grid of the rest positions (no time).
std::string xdmf_text(const XdmfRun& run);

// Writes the text to xmf_path through a temporary file renamed over it, so that a reader never
// sees half a sidecar. Throws std::runtime_error naming the file when writing fails.
void write_xdmf_sidecar(const std::string& xmf_path, const XdmfRun& run);

}  // namespace tongue::run_file
