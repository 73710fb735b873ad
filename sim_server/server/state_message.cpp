#include "server/state_message.hpp"

#include "fem/contact/obstacle.hpp"
#include "model/default_tongue.hpp"
#include "model/muscle.hpp"

namespace tongue::server {
namespace {

std::vector<double> values(const fem::Vector& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

// v into out, in out's storage once it has grown to v's size.
void assign(std::vector<double>& out, const fem::Vector& v) {
  out.assign(v.data(), v.data() + v.size());
}

// Fibre f of a muscle into the model's fibre columns (the first one opens the offsets).
void add_fibre(tongue_lcm::lcmt_tongue_model& msg, std::int32_t muscle, const model::Fibre& f) {
  if (msg.fibre_offsets.empty()) msg.fibre_offsets.push_back(0);
  msg.fibre_muscles.push_back(muscle);
  msg.fibre_nodes.insert(msg.fibre_nodes.end(), f.nodes.begin(), f.nodes.end());
  msg.fibre_offsets.push_back(static_cast<std::int32_t>(msg.fibre_nodes.size()));
  msg.fibre_has_origin.push_back(f.origin.has_value());
  const fem::Vec3 origin = f.origin.value_or(fem::Vec3::Zero());
  msg.fibre_origins.insert(msg.fibre_origins.end(), {origin.x(), origin.y(), origin.z()});
}

void add_obstacle(tongue_lcm::lcmt_tongue_model& msg, const fem::Obstacle& obstacle) {
  const fem::TriangleSurface& surface = obstacle.surface();
  msg.obstacle_names.push_back(obstacle.name());
  msg.obstacle_vertex_counts.push_back(static_cast<std::int32_t>(surface.vertices.size()));
  msg.obstacle_triangle_counts.push_back(static_cast<std::int32_t>(surface.triangles.size()));
  for (const fem::Vec3& v : surface.vertices)
    msg.obstacle_vertices.insert(msg.obstacle_vertices.end(), {v.x(), v.y(), v.z()});
  for (const auto& t : surface.triangles)
    msg.obstacle_triangles.insert(msg.obstacle_triangles.end(), t.begin(), t.end());
}

}  // namespace

tongue_lcm::lcmt_tongue_model model_message(const scene_run::SceneRun& run, std::int64_t utime) {
  const scene::BuiltScene& built = run.built();
  const fem::Mesh& mesh = built.solid->mesh();
  tongue_lcm::lcmt_tongue_model msg{};
  msg.utime = utime;
  msg.num_nodes = mesh.num_nodes();
  msg.rest_positions = values(built.solid->rest_positions());
  msg.num_rest_positions = static_cast<std::int32_t>(msg.rest_positions.size());
  msg.num_elements = mesh.num_elements();
  for (const fem::Hex8& e : mesh.elements)
    msg.elements.insert(msg.elements.end(), e.begin(), e.end());
  msg.num_element_nodes = static_cast<std::int32_t>(msg.elements.size());
  if (built.muscles) {
    for (const auto& m : built.muscles->muscles()) {
      const auto muscle = static_cast<std::int32_t>(msg.muscle_names.size());
      msg.muscle_names.push_back(m.name);
      msg.muscle_max_forces.push_back(m.max_force);
      for (const auto& f : m.fibres) add_fibre(msg, muscle, f);
    }
  }
  msg.num_muscles = static_cast<std::int32_t>(msg.muscle_names.size());
  msg.num_fibres = static_cast<std::int32_t>(msg.fibre_muscles.size());
  msg.num_fibre_offsets = static_cast<std::int32_t>(msg.fibre_offsets.size());
  msg.num_fibre_nodes = static_cast<std::int32_t>(msg.fibre_nodes.size());
  msg.num_fibre_origins = static_cast<std::int32_t>(msg.fibre_origins.size());
  for (const std::string& name : model::landmark_names()) {
    const auto it = mesh.node_sets.find(name);
    if (it == mesh.node_sets.end() || it->second.empty()) continue;
    msg.landmark_names.push_back(name);
    msg.landmark_nodes.push_back(it->second.front());
  }
  msg.num_landmarks = static_cast<std::int32_t>(msg.landmark_names.size());
  msg.dt = run.scene().analysis.dt;
  msg.scene = run.scene().text;
  if (built.contact)
    for (const auto& obstacle : built.contact->obstacles()) add_obstacle(msg, *obstacle);
  msg.num_obstacles = static_cast<std::int32_t>(msg.obstacle_names.size());
  msg.num_obstacle_vertex_values = static_cast<std::int32_t>(msg.obstacle_vertices.size());
  msg.num_obstacle_triangle_values = static_cast<std::int32_t>(msg.obstacle_triangles.size());
  return msg;
}

void fill_state_message(tongue_lcm::lcmt_tongue_state& msg, const scene_run::SceneRun& run,
                        const std::vector<int>& nodes, const scene_run::StepResult& last,
                        const fem::ContactReport& contact, const StateNotes& notes) {
  msg.utime = notes.utime;
  msg.step = run.step_count();
  msg.time = run.time();
  msg.num_nodes = static_cast<std::int32_t>(nodes.size());
  msg.node_indices.assign(nodes.begin(), nodes.end());
  const fem::Vector& rest = run.built().solid->rest_positions();
  const fem::Vector& u = run.displacement();
  msg.positions.resize(3 * nodes.size());
  double* p = msg.positions.data();
  for (const int i : nodes)
    for (int c = 0; c < 3; ++c) *p++ = rest[3 * i + c] + u[3 * i + c];
  msg.num_positions = static_cast<std::int32_t>(msg.positions.size());
  msg.num_muscles = static_cast<std::int32_t>(last.muscles.lengths.size());
  assign(msg.muscle_lengths, last.muscles.lengths);
  assign(msg.muscle_velocities, last.muscles.velocities);
  assign(msg.activations, last.muscles.activations);
  msg.newton_iterations = last.report.iterations;
  msg.residual_norm = last.report.final_residual;
  msg.step_wall_time = last.report.wall_seconds;
  msg.step_cuts = last.report.cuts;
  msg.converged = notes.converged;
  msg.status = notes.status;
  msg.rejected_messages = notes.rejected_messages;
  msg.overruns = notes.overruns;
  msg.num_contacts = static_cast<std::int32_t>(contact.contacts.size());
  msg.contact_nodes.resize(contact.contacts.size());
  msg.contact_obstacles.resize(contact.contacts.size());
  msg.contact_forces.resize(3 * contact.contacts.size());
  for (std::size_t k = 0; k < contact.contacts.size(); ++k) {
    const fem::NodeContact& c = contact.contacts[k];
    msg.contact_nodes[k] = c.node;
    msg.contact_obstacles[k] = c.obstacle;
    for (int i = 0; i < 3; ++i) msg.contact_forces[3 * k + i] = c.force[i];
  }
  msg.num_contact_forces = static_cast<std::int32_t>(msg.contact_forces.size());
  msg.obstacle_forces.resize(3 * contact.obstacle_force.size());
  for (std::size_t o = 0; o < contact.obstacle_force.size(); ++o)
    for (int i = 0; i < 3; ++i) msg.obstacle_forces[3 * o + i] = contact.obstacle_force[o][i];
  msg.num_obstacle_forces = static_cast<std::int32_t>(msg.obstacle_forces.size());
  msg.max_penetration = contact.max_penetration;
  msg.reduced_model_correction = run.reduced_correction();
}

}  // namespace tongue::server
