#pragma once
// A file of external points (bony attachments of fibres, outside the mesh): one point per line,
// "id x y z", the id as in the fibres macro (a positive integer) and the position in m, fields
// separated by whitespace or commas. A '#' or '!' starts a comment to the end of the line; lines
// may end in CRLF; empty lines and a file with no point are allowed (no fibre ends on bone).
#include <map>
#include <string>

#include "fem/types.hpp"

namespace tongue::scene {

// The points by id. Throws std::runtime_error "<path>, line <n>: <reason>" for a line that is
// not an id and three finite numbers or an id given twice, and "<path>: <reason>" for a missing
// or unreadable file.
std::map<long, fem::Vec3> read_external_points(const std::string& path);

}  // namespace tongue::scene
