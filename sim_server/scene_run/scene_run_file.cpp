#include "scene_run/scene_run_file.hpp"

#include <ctime>
#include <string>
#include <vector>

namespace tongue::scene_run {

namespace {

// The wall-clock time as ISO 8601 UTC, e.g. 2026-11-22T17:40:00Z.
std::string utc_now_iso8601() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace

run_file::MeshDescription mesh_description(const fem::Mesh& mesh) {
  run_file::MeshDescription d;
  d.nodes.reserve(mesh.nodes.size());
  for (const fem::Vec3& x : mesh.nodes) d.nodes.push_back({x.x(), x.y(), x.z()});
  d.elements.assign(mesh.elements.begin(), mesh.elements.end());
  d.node_sets = mesh.node_sets;
  d.element_sets = mesh.element_sets;
  return d;
}

std::unique_ptr<run_file::RunFileWriter> open_scene_run_file(const std::string& path,
                                                             const scene::Scene& scene,
                                                             const scene::BuiltScene& built) {
  const bool dynamic = scene.analysis.type == scene::AnalysisType::dynamic;
  run_file::RunFileOptions options;
  // A static run's frames are load factors, not times. (assign, not = "1": GCC 12 warns
  // falsely about overlapping memcpy for a one-character literal.)
  if (!dynamic) options.time_unit.assign(1, '1');
  options.deflate_level = scene.output.deflate_level(scene.model.is_reduced());
  std::vector<run_file::MuscleDescription> muscles;
  if (built.muscles) {
    for (const auto& m : built.muscles->muscles()) {
      run_file::MuscleDescription d{m.name, m.max_force, {}};
      for (const auto& f : m.fibres) {
        // The origin stays NaN (the file's "none") unless the fibre has one.
        run_file::FibreDescription fd;
        fd.nodes = f.nodes;
        fd.weight = f.weight;
        if (f.origin) fd.origin = {f.origin->x(), f.origin->y(), f.origin->z()};
        d.fibres.push_back(std::move(fd));
      }
      muscles.push_back(std::move(d));
    }
  }
  std::vector<run_file::ObstacleDescription> obstacles;
  if (built.contact) {
    for (const auto& o : built.contact->obstacles()) {
      run_file::ObstacleDescription d{o->name(), {}, o->surface().triangles};
      for (const fem::Vec3& v : o->surface().vertices) d.vertices.push_back({v.x(), v.y(), v.z()});
      obstacles.push_back(std::move(d));
    }
  }
  run_file::MeshDescription mesh = mesh_description(built.solid->mesh());
  mesh.node_ids = built.numbering.node_ids;
  mesh.element_ids = built.numbering.element_ids;
  auto log = std::make_unique<run_file::RunFileWriter>(path, mesh, scene.text, options, muscles,
                                                       obstacles);
  log->set_attribute("analysis", dynamic ? "dynamic" : "static");
  // What frame 0 shows, so that pictures can compare the end with rest under gravity.
  log->set_attribute("initial_state",
                     dynamic && scene.analysis.settle
                         ? "settled: static equilibrium under the loads, muscles off"
                         : "reference: the rest positions");
  log->set_attribute("status", "running");
  log->set_attribute("project_version", TONGUE_SIM_VERSION);
  log->set_attribute("start_time", utc_now_iso8601());
  return log;
}

run_file::MuscleFrame scene_muscle_frame(const scene::BuiltScene& built, const fem::Vector& u,
                                         const fem::Vector* v) {
  run_file::MuscleFrame frame;
  if (!built.muscles) return frame;
  const model::MuscleForces& m = *built.muscles;
  frame.activations = m.activations();
  if (v) {
    m.muscle_kinematics(u, *v, frame.lengths, frame.velocities);
  } else {
    frame.lengths = m.muscle_lengths(u);
    frame.velocities = fem::Vector::Zero(m.num_muscles());
  }
  return frame;
}

run_file::ContactFrame scene_contact_frame(const scene::BuiltScene& built, const fem::Vector& u) {
  if (!built.contact) return {};
  return scene_contact_frame(built, built.contact->report(u));
}

run_file::ContactFrame scene_contact_frame(const scene::BuiltScene& built,
                                           const fem::ContactReport& report) {
  run_file::ContactFrame frame;
  if (!built.contact) return frame;
  frame.node_forces = fem::Vector::Zero(built.solid->num_dofs());
  frame.obstacle_forces = fem::Vector::Zero(3 * built.contact->obstacles().size());
  for (const fem::NodeContact& c : report.contacts)
    frame.node_forces.segment<3>(3 * c.node) += c.force;
  for (std::size_t o = 0; o < report.obstacle_force.size(); ++o)
    frame.obstacle_forces.segment<3>(3 * o) = report.obstacle_force[o];
  frame.max_penetration = report.max_penetration;
  return frame;
}

}  // namespace tongue::scene_run
