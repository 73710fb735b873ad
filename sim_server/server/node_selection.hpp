#pragma once
// The nodes whose positions the server's states carry.
#include <string>
#include <vector>

#include "fem/mesh/mesh.hpp"

namespace tongue::server {

// All nodes; the mesh's boundary (fem::boundary_nodes); its "midsagittal" node set; its
// landmarks (the first node of each landmark set present, as listed in the model message).
enum class Nodes { all, surface, midsagittal, landmarks };

// The node indices of nodes in mesh, in the order the states carry them. Throws
// std::invalid_argument naming source (the scene file) when the mesh lacks the node sets that
// nodes asks for.
std::vector<int> select_nodes(const fem::Mesh& mesh, Nodes nodes, const std::string& source);

}  // namespace tongue::server
