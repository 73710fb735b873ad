#pragma once
// A node list file, as meshing tools and ArtiSynth write attachment sets (the nodes fixed to the
// jaw or the hyoid): non-negative integers separated by whitespace or commas, any number per
// line. A '#' or '!' starts a comment to the end of the line; lines may end in CRLF, and bytes
// outside ASCII (Latin-1) are allowed in comments only.
#include <stdexcept>
#include <string>
#include <vector>

namespace tongue::scene {

struct NodeListEntry {
  long number = 0;
  int line = 0;  // 1-based
};

// The file's numbers in order. Throws std::runtime_error "<path>, line <n>: <reason>" for a
// token that is not a non-negative integer or a non-ASCII byte outside a comment, and
// "<path>: <reason>" for a missing, unreadable or empty file (no number).
std::vector<NodeListEntry> read_node_list(const std::string& path);

}  // namespace tongue::scene
