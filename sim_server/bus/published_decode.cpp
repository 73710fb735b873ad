#include "bus/published_decode.hpp"

#include <cstdint>

#include "bus/wire_format.hpp"

namespace tongue::bus {
namespace {

constexpr int kInt32 = 4;
constexpr int kInt64 = 8;
constexpr int kDouble = 8;
constexpr int kBoolean = 1;
constexpr int kMinString = 4 + 1;  // length prefix and the NUL

bool relation(const std::string& what, const std::string& name, std::int32_t value,
              const std::string& of, std::int32_t base, std::int64_t factor, std::string& reason) {
  if (static_cast<std::int64_t>(value) == factor * base) return true;
  reason = what + name + " = " + std::to_string(value) + " is not " + std::to_string(factor) +
           " * " + of + " (" + std::to_string(base) + ")";
  return false;
}

// The layout of lcmt_tongue_state after the fingerprint (lcmtypes/lcmt_tongue_state.lcm).
struct StateCounts {
  std::int32_t nodes = 0, positions = 0, contacts = 0, contact_forces = 0, obstacle_forces = 0;
};
bool state_layout(WireReader& in, StateCounts& c, std::string& reason) {
  std::int32_t muscles = 0;
  return in.fixed("utime, step, time", kInt64 + kInt64 + kDouble, reason) &&
         in.count("num_nodes", kInt32, c.nodes, reason) &&
         in.fixed("node_indices", std::int64_t{kInt32} * c.nodes, reason) &&
         in.count("num_positions", kDouble, c.positions, reason) &&
         in.fixed("positions", std::int64_t{kDouble} * c.positions, reason) &&
         in.count("num_muscles", 3 * kDouble, muscles, reason) &&
         in.fixed("muscle_lengths, muscle_velocities, activations",
                  std::int64_t{3 * kDouble} * muscles, reason) &&
         in.fixed("newton_iterations, residual_norm, step_wall_time, step_cuts, converged",
                  kInt32 + kDouble + kDouble + kInt32 + kBoolean, reason) &&
         in.string("status", reason) &&
         in.fixed("rejected_messages, overruns", kInt64 + kInt64, reason) &&
         in.count("num_contacts", 2 * kInt32, c.contacts, reason) &&
         in.fixed("contact_nodes, contact_obstacles", std::int64_t{2 * kInt32} * c.contacts,
                  reason) &&
         in.count("num_contact_forces", kDouble, c.contact_forces, reason) &&
         in.fixed("contact_forces", std::int64_t{kDouble} * c.contact_forces, reason) &&
         in.count("num_obstacle_forces", kDouble, c.obstacle_forces, reason) &&
         in.fixed("obstacle_forces", std::int64_t{kDouble} * c.obstacle_forces, reason) &&
         in.fixed("max_penetration, reduced_model_correction", 2 * kDouble, reason) &&
         in.at_end(reason);
}

// The layout of lcmt_tongue_model after the fingerprint (lcmtypes/lcmt_tongue_model.lcm).
struct ModelCounts {
  std::int32_t nodes = 0, rest = 0, elements = 0, element_nodes = 0, fibres = 0, fibre_offsets = 0,
               fibre_origins = 0, obstacles = 0, vertex_values = 0, triangle_values = 0;
};
bool model_layout(WireReader& in, ModelCounts& c, std::string& reason) {
  std::int32_t muscles = 0, landmarks = 0, fibre_nodes = 0;
  return in.fixed("utime", kInt64, reason) && in.count("num_nodes", 0, c.nodes, reason) &&
         in.count("num_rest_positions", kDouble, c.rest, reason) &&
         in.fixed("rest_positions", std::int64_t{kDouble} * c.rest, reason) &&
         in.count("num_elements", 0, c.elements, reason) &&
         in.count("num_element_nodes", kInt32, c.element_nodes, reason) &&
         in.fixed("elements", std::int64_t{kInt32} * c.element_nodes, reason) &&
         in.count("num_muscles", kMinString + kDouble, muscles, reason) &&
         in.strings("muscle_names", muscles, reason) &&
         in.fixed("muscle_max_forces", std::int64_t{kDouble} * muscles, reason) &&
         in.count("num_landmarks", kMinString + kInt32, landmarks, reason) &&
         in.strings("landmark_names", landmarks, reason) &&
         in.fixed("landmark_nodes", std::int64_t{kInt32} * landmarks, reason) &&
         in.fixed("dt", kDouble, reason) && in.string("scene", reason) &&
         in.count("num_obstacles", kMinString + 2 * kInt32, c.obstacles, reason) &&
         in.strings("obstacle_names", c.obstacles, reason) &&
         in.count("num_fibres", kInt32 + kBoolean, c.fibres, reason) &&
         in.fixed("fibre_muscles", std::int64_t{kInt32} * c.fibres, reason) &&
         in.count("num_fibre_offsets", kInt32, c.fibre_offsets, reason) &&
         in.fixed("fibre_offsets", std::int64_t{kInt32} * c.fibre_offsets, reason) &&
         in.count("num_fibre_nodes", kInt32, fibre_nodes, reason) &&
         in.fixed("fibre_nodes", std::int64_t{kInt32} * fibre_nodes, reason) &&
         in.fixed("fibre_has_origin", std::int64_t{kBoolean} * c.fibres, reason) &&
         in.count("num_fibre_origins", kDouble, c.fibre_origins, reason) &&
         in.fixed("fibre_origins", std::int64_t{kDouble} * c.fibre_origins, reason) &&
         in.fixed("obstacle_vertex_counts, obstacle_triangle_counts",
                  std::int64_t{2 * kInt32} * c.obstacles, reason) &&
         in.count("num_obstacle_vertex_values", kDouble, c.vertex_values, reason) &&
         in.fixed("obstacle_vertices", std::int64_t{kDouble} * c.vertex_values, reason) &&
         in.count("num_obstacle_triangle_values", kInt32, c.triangle_values, reason) &&
         in.fixed("obstacle_triangles", std::int64_t{kInt32} * c.triangle_values, reason) &&
         in.at_end(reason);
}

}  // namespace

bool decode_state(const void* data, int size, tongue_lcm::lcmt_tongue_state& out,
                  std::string& reason) {
  const std::string what = "lcmt_tongue_state: ";
  // The shortest state: no nodes, no muscles, an empty status, no contact.
  constexpr int kShortest = kInt64 * 4 + kInt32 * 3 + kInt32 + kDouble * 2 + kInt32 + kBoolean +
                            kMinString + kInt64 * 2 + kInt32 * 3 + kDouble;
  WireReader in(data, size);
  if (!start_message(in, tongue_lcm::lcmt_tongue_state::getHash(), kShortest, what, reason))
    return false;
  StateCounts c;
  if (!state_layout(in, c, reason)) {
    reason = what + reason;
    return false;
  }
  if (!relation(what, "num_positions", c.positions, "num_nodes", c.nodes, 3, reason) ||
      !relation(what, "num_contact_forces", c.contact_forces, "num_contacts", c.contacts, 3,
                reason))
    return false;
  if (c.obstacle_forces % 3 != 0) {
    reason = what + "num_obstacle_forces = " + std::to_string(c.obstacle_forces) +
             " is not a multiple of 3";
    return false;
  }
  return checked_decode(data, size, out, what, reason);
}

bool decode_model(const void* data, int size, tongue_lcm::lcmt_tongue_model& out,
                  std::string& reason) {
  const std::string what = "lcmt_tongue_model: ";
  // The shortest model: nothing in it, an empty scene.
  constexpr int kShortest = kInt64 * 2 + kInt32 * 13 + kDouble + kMinString;
  WireReader in(data, size);
  if (!start_message(in, tongue_lcm::lcmt_tongue_model::getHash(), kShortest, what, reason))
    return false;
  ModelCounts c;
  if (!model_layout(in, c, reason)) {
    reason = what + reason;
    return false;
  }
  if (!relation(what, "num_rest_positions", c.rest, "num_nodes", c.nodes, 3, reason) ||
      !relation(what, "num_element_nodes", c.element_nodes, "num_elements", c.elements, 8,
                reason) ||
      !relation(what, "num_fibre_origins", c.fibre_origins, "num_fibres", c.fibres, 3, reason))
    return false;
  if (c.fibre_offsets != (c.fibres > 0 ? c.fibres + 1 : 0)) {
    reason = what + "num_fibre_offsets = " + std::to_string(c.fibre_offsets) +
             " is not num_fibres + 1 (" + std::to_string(c.fibres + 1) + ")";
    return false;
  }
  if (c.vertex_values % 3 != 0 || c.triangle_values % 3 != 0) {
    reason = what + "num_obstacle_vertex_values (" + std::to_string(c.vertex_values) +
             ") and num_obstacle_triangle_values (" + std::to_string(c.triangle_values) +
             ") must be multiples of 3";
    return false;
  }
  return checked_decode(data, size, out, what, reason);
}

}  // namespace tongue::bus
