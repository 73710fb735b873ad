// stress_random_probe [--material NAME] [--seconds S] [--every K] [--watch STEP]
//                     [--force-length LAMBDA0|constant]
//
// A diagnostic, not a test: replays the random activations of random_activation_test.cpp (same
// seed, same sequence) on the built-in tongue without a bus, with the integrator sim_server
// uses, and says what the fibres do. Every K steps (default 25) and at a failure it prints the
// Newton figures, the shortest fibre segment relative to its rest length and the smallest
// det J / det J0. At the step that fails (or at --watch STEP) it solves that step again with the
// same Newton solver on a copy of the Newmark residual and prints, per iteration, the residual
// norm [N], the nodes that carry most of it and the shortest segments, flagging a segment whose
// direction reversed since the previous iterate. --force-length sets the scene's
// muscle_force_length (default: the scene default); `constant` replays the plain fibre model.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "fem/integrator/newmark_integrator.hpp"
#include "random_activation_sequence.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "scene_run/scene_run.hpp"
#include "stress_support.hpp"

namespace tongue::stress {
namespace {

using fem::Vec3;
using fem::Vector;

constexpr double kDt = 0.004;      // s, as the stress test
constexpr double kMeanHold = 0.1;  // s, as the stress test
constexpr unsigned kSeed = 2026;   // as the stress test

struct Options {
  std::string material = "mooney_rivlin5";
  double seconds = 2.0;
  int every = 25;
  long watch = -1;
  std::string force_length;  // the scene's muscle_force_length; empty: its default
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--material") {
      o.material = value;
    } else if (key == "--seconds") {
      o.seconds = std::stod(value);
    } else if (key == "--every") {
      o.every = std::stoi(value);
    } else if (key == "--watch") {
      o.watch = std::stol(value);
    } else if (key == "--force-length") {
      o.force_length = value;
    } else {
      std::fprintf(stderr, "stress_random_probe: unknown option '%s'\n", key.c_str());
      std::exit(1);
    }
  }
  return o;
}

// One fibre segment: its end points (node -1: the fibre's fixed origin) and where it belongs.
struct Segment {
  int muscle = 0, fibre = 0, index = 0;
  int from = -1, to = -1;
  Vec3 origin = Vec3::Zero();
  double rest_length = 0.0;  // m
};

std::vector<Segment> segments_of(const model::MuscleForces& muscles, const Vector& rest) {
  std::vector<Segment> out;
  for (int m = 0; m < muscles.num_muscles(); ++m) {
    const auto& fibres = muscles.muscles()[m].fibres;
    for (int f = 0; f < static_cast<int>(fibres.size()); ++f) {
      const model::Fibre& fibre = fibres[f];
      int from = -1;
      size_t first = 0;
      if (!fibre.origin) {
        from = fibre.nodes[0];
        first = 1;
      }
      for (size_t i = first; i < fibre.nodes.size(); ++i) {
        Segment s{m, f, static_cast<int>(i), from, fibre.nodes[i], Vec3::Zero(), 0.0};
        if (fibre.origin) s.origin = *fibre.origin;
        out.push_back(s);
        from = fibre.nodes[i];
      }
    }
  }
  for (Segment& s : out) {
    const Vec3 a = s.from >= 0 ? Vec3(rest.segment<3>(3 * s.from)) : s.origin;
    s.rest_length = (Vec3(rest.segment<3>(3 * s.to)) - a).norm();
  }
  return out;
}

Vec3 segment_vector(const Segment& s, const Vector& x) {
  const Vec3 a = s.from >= 0 ? Vec3(x.segment<3>(3 * s.from)) : s.origin;
  return Vec3(x.segment<3>(3 * s.to)) - a;
}

// The probe's view of the model: muscles, segments, elements.
struct Probe {
  const scene::BuiltScene& built;
  std::vector<Segment> segments;
  std::vector<double> rest;
  std::vector<int> elements;

  Vector positions(const Vector& u) const { return built.solid->rest_positions() + u; }

  std::string describe(const Segment& s) const {
    char text[160];
    std::snprintf(text, sizeof text, "%s fibre %d segment %d (nodes %d-%d)",
                  built.muscles->muscles()[s.muscle].name.c_str(), s.fibre, s.index, s.from, s.to);
    return text;
  }
  // Indices of the n shortest segments relative to rest at u.
  std::vector<int> shortest(const Vector& u, int n) const {
    const Vector x = positions(u);
    std::vector<int> order(segments.size());
    std::vector<double> ratio(segments.size());
    for (size_t i = 0; i < segments.size(); ++i) {
      order[i] = static_cast<int>(i);
      ratio[i] = segment_vector(segments[i], x).norm() / segments[i].rest_length;
    }
    std::partial_sort(order.begin(), order.begin() + n, order.end(),
                      [&](int a, int b) { return ratio[a] < ratio[b]; });
    order.resize(n);
    return order;
  }
  double ratio(int i, const Vector& u) const {
    return segment_vector(segments[i], positions(u)).norm() / segments[i].rest_length;
  }
  double min_jacobian(const Vector& u) const {
    const Vector x = positions(u);
    return testing::min_relative_jacobian(rest, std::vector<double>(x.data(), x.data() + x.size()),
                                          elements);
  }
};

// A copy of the Newmark step's residual (newmark_integrator.cpp) that records every iterate.
class RecordingStep : public fem::NonlinearProblem {
 public:
  RecordingStep(const fem::MechanicalSystem& system, const fem::SymmetricMatrix& mass,
                const fem::SymmetricMatrix& damping, const fem::NewmarkParameters& p, double dt,
                const fem::TimeIntegrator& state)
      : system_(system),
        dofs_(system.solid().dofs()),
        mass_(mass),
        damping_(damping),
        p_(p),
        dt_(dt),
        u_n_(dofs_.gather_free(state.displacement())),
        v_n_(dofs_.gather_free(state.velocity())),
        a_n_(dofs_.gather_free(state.acceleration())),
        full_(state.displacement()) {}

  std::shared_ptr<const fem::SparsityPattern> pattern() const override {
    return mass_.shared_pattern();
  }
  bool residual(const Vector& x, Vector& r) override { return evaluate(x, r, nullptr); }
  bool residual_and_tangent(const Vector& x, Vector& r, fem::SymmetricMatrix& K) override {
    if (!evaluate(x, r, &K)) return false;
    K.scale_and_add(1.0, 1.0 / (p_.beta * dt_ * dt_), mass_);
    K.scale_and_add(1.0, p_.gamma / (p_.beta * dt_), damping_);
    return true;
  }
  struct Iterate {
    Vector u;  // full
    Vector r;  // free
    bool with_tangent;
  };
  const std::vector<Iterate>& iterates() const { return iterates_; }

 private:
  bool evaluate(const Vector& x, Vector& r, fem::SymmetricMatrix* K) {
    dofs_.scatter_free(x, full_);
    Vector r_full;
    if (!system_.residual(full_, 1.0, r_full, K).ok) return false;
    const Vector a = (x - u_n_ - dt_ * v_n_) / (p_.beta * dt_ * dt_) - (0.5 / p_.beta - 1.0) * a_n_;
    const Vector v = v_n_ + dt_ * ((1.0 - p_.gamma) * a_n_ + p_.gamma * a);
    r = dofs_.gather_free(r_full) + mass_.multiply(a) + damping_.multiply(v);
    iterates_.push_back({full_, r, K != nullptr});
    return true;
  }

  const fem::MechanicalSystem& system_;
  const fem::DofMap& dofs_;
  const fem::SymmetricMatrix& mass_;
  const fem::SymmetricMatrix& damping_;
  fem::NewmarkParameters p_;
  double dt_;
  Vector u_n_, v_n_, a_n_, full_;
  std::vector<Iterate> iterates_;
};

// Solves one step again on RecordingStep and prints each iterate.
void dissect(const Probe& probe, const fem::TimeIntegrator& integrator,
             const fem::SymmetricMatrix& mass, const fem::SymmetricMatrix& damping, double dt,
             int max_iterations) {
  const auto& settings = probe.built.dynamic_settings;
  RecordingStep step(*probe.built.system, mass, damping, settings.newmark, dt, integrator);
  fem::NewtonSettings newton = settings.newton;
  newton.max_iterations = max_iterations;
  newton.max_tangent_reuse = 0;
  fem::NewtonSolver solver(probe.built.solid->pattern(), newton);
  const fem::DofMap& dofs = probe.built.solid->dofs();
  Vector x = dofs.gather_free(integrator.displacement());
  const fem::NewtonReport report = solver.solve(step, x);
  std::printf("dissect dt %.3g s: %s after %d iterations, residual %.3e -> %.3e N %s\n", dt,
              report.converged ? "converged" : "FAILED", report.iterations, report.initial_residual,
              report.final_residual, report.failure.c_str());
  // The shortest segments at the start, followed through the iterates.
  const std::vector<int> watched = probe.shortest(integrator.displacement(), 4);
  const auto& its = step.iterates();
  const Vector x0 = probe.positions(integrator.displacement());
  std::vector<Vec3> previous;
  for (int s : watched) previous.push_back(segment_vector(probe.segments[s], x0));
  std::printf("  watched segments: ");
  for (int s : watched)
    std::printf("[%s rest %.2f mm] ", probe.describe(probe.segments[s]).c_str(),
                probe.segments[s].rest_length * 1e3);
  std::printf(
      "\n  eval  tangent  |r| [N]     top node (|r_node| [N], share of |r|^2)   "
      "watched segment l/l0 (* = reversed)\n");
  for (size_t k = 0; k < its.size(); ++k) {
    const auto& it = its[k];
    // Residual per node.
    std::vector<double> node_r2(probe.built.solid->mesh().num_nodes(), 0.0);
    for (int i = 0; i < it.r.size(); ++i) node_r2[dofs.free_dofs()[i] / 3] += it.r[i] * it.r[i];
    const int top =
        static_cast<int>(std::max_element(node_r2.begin(), node_r2.end()) - node_r2.begin());
    const double total = it.r.squaredNorm();
    std::printf("  %4zu  %s  %.3e   node %4d (%.3e, %4.0f %%)   ", k,
                it.with_tangent ? "yes" : " no", std::sqrt(total), top, std::sqrt(node_r2[top]),
                100.0 * node_r2[top] / total);
    const Vector x = probe.positions(it.u);
    for (size_t w = 0; w < watched.size(); ++w) {
      const Vec3 d = segment_vector(probe.segments[watched[w]], x);
      const bool reversed = d.dot(previous[w]) < 0.0;
      std::printf("%.3f%s ", d.norm() / probe.segments[watched[w]].rest_length,
                  reversed ? "*" : " ");
      previous[w] = d;
    }
    std::printf("\n");
  }
}

int run(const Options& o) {
  std::string text = testing::tongue_scene_head(0.49, o.material) +
                     "analysis: {type: dynamic, settle: true, duration: 1, dt: 0.004}\n";
  if (!o.force_length.empty()) text += "muscle_force_length: " + o.force_length + "\n";
  const scene::Scene scene = scene::parse_scene(text, ".", "<probe scene>");
  scene_run::SceneRun run(scene, scene::build_scene(scene));
  Probe probe{run.built(), {}, {}, {}};
  const scene::BuiltScene& built = run.built();
  const Vector& rest = built.solid->rest_positions();
  probe.segments = segments_of(*built.muscles, rest);
  probe.rest.assign(rest.data(), rest.data() + rest.size());
  for (const auto& element : built.solid->mesh().elements)
    for (int n : element) probe.elements.push_back(n);

  if (!run.start().converged) {
    std::fprintf(stderr, "settling failed\n");
    return 1;
  }
  const fem::TimeIntegrator& integrator = run.integrator();
  // Replicas of the integrator's mass and damping (newmark_integrator.cpp) for dissect().
  const fem::SymmetricMatrix mass = built.solid->mass_matrix(built.dynamic_settings.lumped_mass);
  fem::SymmetricMatrix damping(built.solid->pattern());
  {
    const auto& d = built.dynamic_settings.damping;
    damping.scale_and_add(0.0, d.mass_coefficient, mass);
    fem::SymmetricMatrix K0(built.solid->pattern());
    Vector f;
    built.solid->assemble(integrator.displacement(), f, &K0);
    damping.scale_and_add(1.0, d.stiffness_coefficient, K0);
  }

  RandomActivationSequence sequence(built.muscles->num_muscles(), kDt, kMeanHold, kSeed);
  const long steps = std::lround(o.seconds / kDt);
  double worst_ratio = 1e300, worst_jacobian = 1e300;
  int total_cuts = 0;
  std::printf(
      "step   t [s]   iters cuts  |r0| [N]   shortest segment l/l0 (which)   "
      "det J/J0 min\n");
  for (long k = 1; k <= steps; ++k) {
    const std::vector<double>& levels = sequence.next();
    if (k == o.watch) dissect(probe, integrator, mass, damping, kDt, 40);
    const fem::StepReport r =
        run.step(kDt, Eigen::Map<const Vector>(levels.data(), levels.size())).report;
    total_cuts += r.cuts;
    if (!r.converged) {
      std::printf("step %ld FAILED: %s\n", k, r.message.c_str());
      const int s = probe.shortest(integrator.displacement(), 1)[0];
      const Segment& worst = probe.segments[s];
      const model::Fibre& fibre = built.muscles->muscles()[worst.muscle].fibres[worst.fibre];
      std::printf(
          "at the last accepted state: shortest %s at %.3f of rest (its fibre at %.3f of rest), "
          "det J/J0 min %.3f\n",
          probe.describe(worst).c_str(), probe.ratio(s, integrator.displacement()),
          model::fibre_length(fibre, probe.positions(integrator.displacement())) /
              model::fibre_length(fibre, rest),
          probe.min_jacobian(integrator.displacement()));
      std::printf("activations:");
      for (int m = 0; m < built.muscles->num_muscles(); ++m)
        std::printf(" %s %.2f", built.muscles->muscles()[m].name.c_str(), levels[m]);
      std::printf("\n");
      dissect(probe, integrator, mass, damping, kDt, 40);
      dissect(probe, integrator, mass, damping, kDt / 16, 40);
      return 2;
    }
    const int s = probe.shortest(integrator.displacement(), 1)[0];
    const double ratio = probe.ratio(s, integrator.displacement());
    worst_ratio = std::min(worst_ratio, ratio);
    if (k % o.every == 0 || k == steps) {
      const double jac = probe.min_jacobian(integrator.displacement());
      worst_jacobian = std::min(worst_jacobian, jac);
      std::printf("%5ld %7.3f  %4d %4d  %.3e   %.3f (%s)   %.3f\n", k, integrator.time(),
                  r.iterations, r.cuts, r.initial_residual, ratio,
                  probe.describe(probe.segments[s]).c_str(), jac);
    }
  }
  std::printf(
      "done: %ld steps (%.1f s simulated), %ld jumps, %d cuts, shortest segment %.3f of "
      "rest, det J/J0 min %.3f (sampled every %d steps)\n",
      steps, o.seconds, sequence.jumps(), total_cuts, worst_ratio, worst_jacobian, o.every);
  return 0;
}

}  // namespace
}  // namespace tongue::stress

int main(int argc, char** argv) {
  try {
    return tongue::stress::run(tongue::stress::parse(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stress_random_probe: %s\n", e.what());
    return 1;
  }
}
