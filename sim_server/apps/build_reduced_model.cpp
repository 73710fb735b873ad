// build_reduced_model SCENE.yaml --output BASIS.h5 [--snapshots FILE.h5] [--energy F]
//                     [--duration S] [--pairs N] [--mixes N] [--seed N] [--sampling F]
//
// The first half of a reduced-order model of a scene: its training data and its reduced basis.
// The scene's full model is settled under gravity (the origin of the reduced coordinates) and
// run from there under the training sequences of reduced/training_sequences.hpp (each muscle
// group stepped and ramped, pairs of groups, random mixes), every step's displacement from the
// origin kept as a snapshot; the proper orthogonal decomposition of the snapshots
// (reduced/pod_basis.hpp) gives the basis, the fewest modes that hold the given fraction of the
// snapshots' energy; energy-conserving sampling (reduced/element_sampling.hpp) picks the
// elements and weights that reproduce the mesh's reduced internal forces over the snapshots
// within the fraction --sampling. Writes the basis (reduced/reduced_basis_file.hpp) and, when
// asked, the snapshots (reduced/snapshot_file.hpp); prints the runs, their time, and the modes that
// each energy fraction needs.
//
// A training step that fails to converge ends its sequence there (its snapshots so far are
// kept) and is reported; the basis is still made from the rest. Exit status: 0 done; 1 bad
// command line, scene or file error, or no snapshot at all.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "common/exit_code.hpp"
#include "reduced/element_reduced_forces.hpp"
#include "reduced/element_sampling.hpp"
#include "reduced/pod_basis.hpp"
#include "reduced/reduced_basis_file.hpp"
#include "reduced/snapshot_file.hpp"
#include "reduced/training_sequences.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "scene_run/scene_run.hpp"

namespace tongue::apps {
namespace {

using Clock = std::chrono::steady_clock;

// At most this many snapshots, evenly strided, make the sampling's system.
constexpr Eigen::Index kSamplingSnapshots = 200;

struct Options {
  std::string scene_path, output, snapshots;
  // With 60 random mixes in the training, 0.9997 of the energy (63 modes on the tongue) and a
  // sample within 0.1 step as fast as 0.9999 and 0.01 did with 6 mixes (49 modes, 478 elements)
  // at half the error on held-out runs (docs/reduced.md, "The defaults").
  double energy = 0.9997;
  double sampling = 0.1;
  reduced::TrainingOptions training;
};

void print_usage(std::FILE* to) {
  std::fprintf(to,
               "usage: build_reduced_model SCENE.yaml --output BASIS.h5 [--snapshots FILE.h5]\n"
               "                           [--energy F] [--duration S] [--pairs N] [--mixes N]\n"
               "                           [--seed N] [--sampling F]\n"
               "  --output FILE     the reduced basis to write\n"
               "  --snapshots FILE  also write the training snapshots\n"
               "  --energy F        fraction of the snapshots' energy the modes hold (default "
               "0.9997)\n"
               "  --duration S      each training sequence [s] (default 0.3)\n"
               "  --pairs N         sequences with two muscle groups together (default 12)\n"
               "  --mixes N         sequences with every group on at random (default 60)\n"
               "  --seed N          the training levels' random seed (default 1)\n"
               "  --sampling F      relative misfit of the sampled elements' reduced forces\n"
               "                    (default 0.1)\n");
}

std::optional<Options> parse_arguments(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::optional<std::string> {
      if (i + 1 < argc) return std::string(argv[++i]);
      std::fprintf(stderr, "build_reduced_model: %s needs a value\n", a.c_str());
      return std::nullopt;
    };
    const auto number = [&](double& out) {
      const auto v = value();
      if (!v) return false;
      char* end = nullptr;
      out = std::strtod(v->c_str(), &end);
      if (end == v->c_str() || *end != '\0' || !std::isfinite(out)) {
        std::fprintf(stderr, "build_reduced_model: %s: not a number: %s\n", a.c_str(), v->c_str());
        return false;
      }
      return true;
    };
    double x = 0.0;
    if (a == "--help" || a == "-h") {
      print_usage(stdout);
      std::exit(common::kExitOk);
    } else if (a == "--output" || a == "-o" || a == "--snapshots") {
      const auto v = value();
      if (!v) return std::nullopt;
      (a == "--snapshots" ? o.snapshots : o.output) = *v;
    } else if (a == "--energy") {
      if (!number(o.energy)) return std::nullopt;
    } else if (a == "--sampling") {
      if (!number(o.sampling)) return std::nullopt;
    } else if (a == "--duration") {
      if (!number(o.training.duration)) return std::nullopt;
    } else if (a == "--pairs" || a == "--mixes" || a == "--seed") {
      if (!number(x)) return std::nullopt;
      if (x < 0.0 || x != std::floor(x) || x > 1e9) {
        std::fprintf(stderr, "build_reduced_model: %s must be a whole number >= 0\n", a.c_str());
        return std::nullopt;
      }
      if (a == "--pairs") o.training.pairs = static_cast<int>(x);
      if (a == "--mixes") o.training.mixes = static_cast<int>(x);
      if (a == "--seed") o.training.seed = static_cast<std::uint32_t>(x);
    } else if (!a.empty() && a[0] != '-' && o.scene_path.empty()) {
      o.scene_path = a;
    } else {
      std::fprintf(stderr, "build_reduced_model: unknown argument %s\n", a.c_str());
      return std::nullopt;
    }
  }
  if (o.scene_path.empty() || o.output.empty()) {
    print_usage(stderr);
    return std::nullopt;
  }
  if (!(o.energy > 0.0 && o.energy <= 1.0)) {
    std::fprintf(stderr, "build_reduced_model: --energy must lie in (0, 1]\n");
    return std::nullopt;
  }
  if (!(o.sampling > 0.0 && o.sampling < 1.0)) {
    std::fprintf(stderr, "build_reduced_model: --sampling must lie in (0, 1)\n");
    return std::nullopt;
  }
  return o;
}

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

int run(const Options& o) {
  const scene::Scene s = scene::read_scene(o.scene_path);
  if (s.analysis.type != scene::AnalysisType::dynamic)
    throw std::invalid_argument(s.source + ": training needs a dynamic analysis");
  scene::BuiltScene built = scene::build_scene(s);
  if (!built.muscles || built.muscles->num_muscles() == 0)
    throw std::invalid_argument(s.source + ": training needs muscles");
  std::vector<std::string> names;
  for (const auto& m : built.muscles->muscles()) names.push_back(m.name);
  scene_run::SceneRun runner(s, std::move(built));
  const fem::StaticReport settled = runner.start();
  if (!settled.converged) throw std::runtime_error("settling failed: " + settled.message);
  const fem::Vector origin = runner.displacement();

  const std::vector<reduced::TrainingSequence> sequences =
      reduced::training_sequences(names, o.training);
  const double dt = s.analysis.dt;
  const int steps = static_cast<int>(std::ceil(o.training.duration / dt - 1e-9));
  std::printf("%s: %d training runs of %d steps (dt %g ms, %g s each), %d muscles\n",
              s.source.c_str(), static_cast<int>(sequences.size()), steps, dt * 1e3,
              o.training.duration, static_cast<int>(names.size()));
  reduced::SnapshotSet set;
  // Room for every step of every run; cut to the steps taken at the end.
  set.snapshots.resize(origin.size(), static_cast<Eigen::Index>(sequences.size()) * steps);
  Eigen::Index taken = 0;
  int failed = 0;
  const auto started = Clock::now();
  for (const reduced::TrainingSequence& seq : sequences) {
    runner.restart();
    int kept = 0;
    for (int k = 0; k < steps; ++k) {
      const fem::Vector levels = seq.at((k + 1) * dt).cwiseMax(0.0).cwiseMin(1.0);
      const scene_run::StepResult r = runner.step(dt, levels);
      if (!r.report.converged) {
        std::fprintf(stderr, "build_reduced_model: %s: step %d failed (%s); %d snapshots kept\n",
                     seq.name.c_str(), k + 1, r.report.message.c_str(), kept);
        ++failed;
        break;
      }
      set.snapshots.col(taken++) = runner.displacement() - origin;
      ++kept;
    }
    set.run_names.push_back(seq.name);
    set.run_snapshots.push_back(kept);
  }
  const double training_s = seconds_since(started);
  if (taken == 0) throw std::runtime_error("no training step converged: no snapshot");
  set.snapshots.conservativeResize(Eigen::NoChange, taken);

  const auto pod_started = Clock::now();
  const reduced::PodBasis pod = reduced::pod_basis(set.snapshots, o.energy);
  const double pod_s = seconds_since(pod_started);
  std::printf("training: %d runs (%d ended early), %d snapshots, %.1f s; POD of %d x %d: %.1f s\n",
              static_cast<int>(sequences.size()), failed, static_cast<int>(set.snapshots.cols()),
              training_s, static_cast<int>(set.snapshots.rows()),
              static_cast<int>(set.snapshots.cols()), pod_s);
  std::printf("modes for a fraction of the snapshots' energy:");
  for (const double f : {0.99, 0.999, 0.9999, 0.99999, 0.999999})
    std::printf(" %g: %d;", f, reduced::modes_for(pod.singular_values, f));
  std::printf("\n");

  // The sampling's system has k rows per snapshot and a column per element; every few snapshots
  // are enough to pin the weights (the paper trains on tens to hundreds) and keep it small.
  const auto sampling_started = Clock::now();
  const Eigen::Index stride = (set.snapshots.cols() + kSamplingSnapshots - 1) / kSamplingSnapshots;
  Eigen::MatrixXd sampled(set.snapshots.rows(), (set.snapshots.cols() + stride - 1) / stride);
  for (Eigen::Index j = 0; j < sampled.cols(); ++j) sampled.col(j) = set.snapshots.col(j * stride);
  const fem::SolidModel& solid = *runner.built().solid;
  const reduced::ElementSample sample =
      reduced::sample_elements(reduced::element_reduced_forces(solid, origin, pod.modes, sampled),
                               static_cast<int>(pod.modes.cols()), o.sampling);
  std::printf(
      "sampling: %d of %d elements reproduce the reduced forces of %d snapshots within "
      "%.4f (asked: %g), %.1f s\n",
      static_cast<int>(sample.elements.size()), solid.mesh().num_elements(),
      static_cast<int>(sampled.cols()), sample.relative_error, o.sampling,
      seconds_since(sampling_started));
  if (!sample.within_tolerance)
    std::fprintf(stderr,
                 "build_reduced_model: warning: no sample reached the misfit %g; the best, "
                 "%.4f, is kept\n",
                 o.sampling, sample.relative_error);

  reduced::ReducedBasis basis;
  basis.origin = origin;
  basis.modes = pod.modes;
  basis.singular_values = pod.singular_values;
  basis.energy_fraction = o.energy;
  basis.captured = pod.captured;
  basis.snapshots = static_cast<int>(set.snapshots.cols());
  basis.runs = static_cast<int>(sequences.size());
  basis.mesh_signature = reduced::mesh_signature(runner.built().solid->mesh());
  basis.material = scene::material_text(s.material);
  basis.scene = s.text;
  basis.sample_elements = sample.elements;
  basis.sample_weights = sample.weights;
  basis.sample_tolerance = o.sampling;
  basis.sample_error = sample.relative_error;
  reduced::write_reduced_basis(o.output, basis);
  std::printf("basis: %d modes holding %.8f of the energy -> %s\n",
              static_cast<int>(pod.modes.cols()), pod.captured, o.output.c_str());
  if (!o.snapshots.empty()) {
    reduced::write_snapshots(o.snapshots, set);
    std::printf("snapshots -> %s\n", o.snapshots.c_str());
  }
  return common::kExitOk;
}

}  // namespace
}  // namespace tongue::apps

int main(int argc, char** argv) {
  const auto options = tongue::apps::parse_arguments(argc, argv);
  if (!options) return tongue::common::kExitError;
  try {
    return tongue::apps::run(*options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "build_reduced_model: error: %s\n", e.what());
    return tongue::common::kExitError;
  }
}
