#include "scene_run/ellipticity_watch.hpp"

#include <stdexcept>
#include <utility>

namespace tongue::scene_run {

EllipticityWatch::EllipticityWatch(const fem::SolidModel& solid, fem::MeshNumbering numbering)
    : monitor_(solid), material_(solid.material()), numbering_(std::move(numbering)) {}

std::optional<EllipticityFinding> EllipticityWatch::check(const fem::Vector& u, std::int64_t step,
                                                          double time) {
  if (step % every_ != 0) {
    // Kept, to be checked if no other state comes before collect().
    if (!found_loss_) {
      skipped_u_ = u;
      skipped_step_ = step;
      skipped_time_ = time;
      skipped_ = true;
    }
    return std::nullopt;
  }
  skipped_ = false;
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
  check_skipped();
  return std::exchange(found_, std::nullopt);
}

void EllipticityWatch::check_every(int n) {
  if (n < 1) throw std::invalid_argument("EllipticityWatch::check_every: n must be at least 1");
  every_ = n;
}

void EllipticityWatch::check_skipped() {
  if (!skipped_) return;
  skipped_ = false;
  if (found_loss_) return;
  u_.swap(skipped_u_);
  step_ = skipped_step_;
  time_ = skipped_time_;
  check_state();
}

void EllipticityWatch::rearm() {
  task_.wait();
  check_skipped();  // the last run's last state: its finding is delivered by the next call
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
