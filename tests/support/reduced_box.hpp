#pragma once
// A reduced basis of a small dynamic scene with one muscle (e.g. box_scenes.hpp's box, settled),
// trained on its full model with the muscle stepped to full activation for `steps` / 2 steps
// and released for as many; its elements sampled within 1 %. For the tests that run a scene's
// reduced model.
#include <string>

#include "reduced/element_reduced_forces.hpp"
#include "reduced/element_sampling.hpp"
#include "reduced/pod_basis.hpp"
#include "reduced/reduced_basis_file.hpp"
#include "scene/scene_builder.hpp"
#include "scene_run/scene_run.hpp"

namespace tongue::testing {

inline void write_reduced_basis_of(const scene::Scene& scene, int steps, const std::string& path) {
  scene_run::SceneRun full(scene, scene::build_scene(scene));
  if (!full.start().converged) throw std::runtime_error("the training scene does not settle");
  const fem::Vector origin = full.displacement();
  Eigen::MatrixXd snapshots(origin.size(), steps);
  for (int k = 0; k < steps; ++k) {
    const fem::Vector level = fem::Vector::Constant(full.num_muscles(), k < steps / 2 ? 1.0 : 0.0);
    if (!full.step(scene.analysis.dt, level).report.converged)
      throw std::runtime_error("a training step failed");
    snapshots.col(k) = full.displacement() - origin;
  }
  const reduced::PodBasis pod = reduced::pod_basis(snapshots, 0.9999999);
  const reduced::ElementSample sample = reduced::sample_elements(
      reduced::element_reduced_forces(*full.built().solid, origin, pod.modes, snapshots),
      static_cast<int>(pod.modes.cols()), 0.01);
  reduced::ReducedBasis basis;
  basis.origin = origin;
  basis.modes = pod.modes;
  basis.singular_values = pod.singular_values;
  basis.sample_elements = sample.elements;
  basis.sample_weights = sample.weights;
  basis.mesh_signature = reduced::mesh_signature(full.built().solid->mesh());
  basis.material = scene::material_text(scene.material);
  reduced::write_reduced_basis(path, basis);
}

}  // namespace tongue::testing
