#include "scene_run/ellipticity_watch.hpp"

#include <utility>

namespace tongue::scene_run {

EllipticityWatch::EllipticityWatch(const fem::SolidModel& solid, fem::MeshNumbering numbering)
    : monitor_(solid), material_(solid.material()), numbering_(std::move(numbering)) {}

std::optional<EllipticityFinding> EllipticityWatch::check(const fem::Vector& u, std::int64_t step,
                                                          double time) {
  std::optional<EllipticityFinding> found = collect();
  // After the run's one finding there is nothing left to look for: the task is not woken
  // (each wake-up is a system call and a second core's time, which a closed loop's controller
  // can use).
  if (found_loss_) return found;
  u_ = u;  // the same size every step: no reallocation
  step_ = step;
  time_ = time;
  task_.start([this] { check_state(); });
  return found;
}

std::optional<EllipticityFinding> EllipticityWatch::collect() {
  task_.wait();
  return std::exchange(found_, std::nullopt);
}

void EllipticityWatch::rearm() {
  task_.wait();
  monitor_.reset();
  found_loss_ = false;
}

void EllipticityWatch::check_state() {
  if (const auto loss = monitor_.first_loss(u_)) {
    found_ = EllipticityFinding{step_, time_, *loss, fem::describe(*loss, material_, numbering_)};
    found_loss_ = true;
  }
}

}  // namespace tongue::scene_run
