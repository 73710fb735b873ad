#include "scene_run/reduced_check_watch.hpp"

#include <utility>

namespace tongue::scene_run {

ReducedCheckWatch::ReducedCheckWatch(const scene::Scene& scene, const fem::Vector& origin)
    : built_(scene::build_scene(scene)), full_(*built_.system, origin, built_.dynamic_settings) {
  // The check's factor for the scene's dt, made while the run is being set up (settling the
  // full model) rather than by the first check, which a step would then wait for (about 30 ms
  // on the tongue). A failure here is the first check's to report.
  const double dt = scene.analysis.dt;
  if (dt > 0.0) task_.start([this, dt] { full_.prepare(dt); });
}

std::optional<ReducedCheck> ReducedCheckWatch::check(const fem::Vector& u, const fem::Vector& v,
                                                     const fem::Vector& a,
                                                     const fem::Vector& levels, double dt,
                                                     std::int64_t step, double time) {
  std::optional<ReducedCheck> done = collect();
  u_ = u;  // the same sizes every time: no reallocation
  v_ = v;
  a_ = a;
  levels_ = levels;
  dt_ = dt;
  checked_ = ReducedCheck{step, time, 0.0};
  task_.start([this] { check_state(); });
  return done;
}

std::optional<ReducedCheck> ReducedCheckWatch::collect() {
  task_.wait();
  return std::exchange(result_, std::nullopt);
}

void ReducedCheckWatch::check_state() {
  if (built_.muscles) built_.muscles->set_activations(levels_);
  checked_.correction = full_.correction(u_, v_, a_, dt_);
  result_ = checked_;
}

}  // namespace tongue::scene_run
