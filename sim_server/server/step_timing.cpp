#include "server/step_timing.hpp"

#include <algorithm>
#include <cstdio>

namespace tongue::server {
namespace {

using Part = StepTiming::Part;
constexpr std::array<Part, StepTiming::kParts> kAll{Part::physics, Part::run_file,
                                                    Part::state_message, Part::loop};

int index(Part part) {
  return static_cast<int>(part);
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

// The parts with their figures in ms, "physics 5.61 ms, run file 0.82 ms, ...".
template <typename Figure>
std::string parts_text(Figure figure) {
  std::string text;
  for (const Part part : kAll) {
    std::string name = part_name(part);
    std::replace(name.begin(), name.end(), '_', ' ');
    char item[64];
    std::snprintf(item, sizeof item, "%s%s %.3f ms", text.empty() ? "" : ", ", name.c_str(),
                  figure(part));
    text += item;
  }
  return text;
}

std::string span_text(double span_s) {
  char text[96];
  std::snprintf(text, sizeof text, "%.3f s from the first step's start to the last one's end",
                span_s);
  return text;
}

}  // namespace

const char* part_name(Part part) {
  switch (part) {
    case Part::physics:
      return "physics";
    case Part::run_file:
      return "run_file";
    case Part::state_message:
      return "state_message";
    case Part::loop:
      return "loop";
  }
  return "?";
}

StepTiming::Clock::time_point StepTiming::add(Part part, Clock::time_point start) {
  const Clock::time_point now = Clock::now();
  current_[index(part)] += std::chrono::duration<double>(now - start).count();
  return now;
}

void StepTiming::start_step(Clock::time_point at) {
  if (count_ == 0) first_start_ = at;
}

void StepTiming::end_step(Clock::time_point at) {
  last_end_ = at;
  for (int i = 0; i < kParts; ++i) {
    total_[i] += current_[i];
    max_[i] = std::max(max_[i], current_[i]);
    current_[i] = 0.0;
  }
  ++count_;
}

double StepTiming::mean_ms(Part part) const {
  return count_ > 0 ? 1e3 * total_[index(part)] / static_cast<double>(count_) : 0.0;
}

double StepTiming::max_ms(Part part) const {
  return 1e3 * max_[index(part)];
}

double StepTiming::span_s() const {
  return count_ > 0 ? std::chrono::duration<double>(last_end_ - first_start_).count() : 0.0;
}

std::string StepTiming::summary() const {
  const SolverMeans m = solver_means();
  char solver[224];
  std::snprintf(solver, sizeof solver,
                "; solver per step: %.3g iterations, %.3g factorizations, assembly %.3f ms, "
                "factorization %.3f ms, solves %.3f ms",
                m.iterations, m.factorizations, m.assembly_ms, m.factorization_ms, m.solve_ms);
  return "per step (" + std::to_string(count_) +
         " steps): " + parts_text([this](Part p) { return mean_ms(p); }) + " (mean; max " +
         parts_text([this](Part p) { return max_ms(p); }) + "); " + span_text(span_s()) + solver;
}

StepTiming::SolverMeans StepTiming::solver_means() const {
  if (solver_.steps == 0) return {};
  const double n = solver_.steps;
  return {solver_.iterations / n, solver_.factorizations / n, 1e3 * solver_.assembly / n,
          1e3 * solver_.factorization / n, 1e3 * solver_.solve / n};
}

std::vector<std::pair<std::string, std::string>> StepTiming::attributes() const {
  std::vector<std::pair<std::string, std::string>> out{{"timing_steps", std::to_string(count_)},
                                                       {"timing_span_s", number(span_s())}};
  for (const Part part : kAll) {
    const std::string name = std::string("timing_") + part_name(part);
    out.emplace_back(name + "_ms", number(mean_ms(part)));
    out.emplace_back(name + "_max_ms", number(max_ms(part)));
  }
  const SolverMeans m = solver_means();
  out.emplace_back("timing_iterations", number(m.iterations));
  out.emplace_back("timing_factorizations", number(m.factorizations));
  out.emplace_back("timing_assembly_ms", number(m.assembly_ms));
  out.emplace_back("timing_factorization_ms", number(m.factorization_ms));
  out.emplace_back("timing_solve_ms", number(m.solve_ms));
  return out;
}

}  // namespace tongue::server
