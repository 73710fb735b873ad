#include "server/server_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <thread>
#include <utility>

#include "scene_run/scene_run_file.hpp"
#include "server/state_message.hpp"

namespace tongue::server {
namespace {

// Longest single wait for messages [ms]: the stop predicate is looked at least this often.
constexpr int kPollSliceMs = 100;
// Overruns and steps accepted beyond the contact's tolerance are reported on stderr at most once
// per kind per this many seconds.
constexpr double kReportInterval = 1.0;
// Real-time: a wait for the next step's start shorter than this [s] is slept, not polled (the
// bus waits in whole milliseconds).
constexpr double kSleepBelow = 1e-3;

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::int64_t wall_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// built, once the scene is known to be one the server can run (checked before SceneRun is made,
// so that the message says what the server needs).
scene::BuiltScene server_scene(const scene::Scene& scene, scene::BuiltScene built) {
  if (scene.analysis.type != scene::AnalysisType::dynamic)
    throw std::invalid_argument(scene.source +
                                ": the server needs a dynamic analysis (analysis.type: dynamic)");
  if (!built.muscles || built.muscles->num_muscles() == 0)
    throw std::invalid_argument(scene.source +
                                ": the server needs muscles (muscles: builtin or a list)");
  return built;
}

std::vector<std::string> muscle_names(const scene_run::SceneRun& run) {
  std::vector<std::string> names;
  for (const auto& m : run.built().muscles->muscles()) names.push_back(m.name);
  return names;
}

void check_options(const ServerOptions& options) {
  if (options.timeout_ms <= 0) throw std::invalid_argument("the timeout must be > 0 ms");
  if (!(options.silence_s > 0.0)) throw std::invalid_argument("the silence must be > 0 s");
  if (options.publish_every < 1)
    throw std::invalid_argument("states must be published every 1 or more steps");
  if (options.on_silence == OnSilence::decay && options.mode != Mode::realtime)
    throw std::invalid_argument("decay on silence needs the real-time mode");
  if (options.controllers != 1 && options.mode != Mode::lockstep)
    throw std::invalid_argument("several controllers per step need the lock-step mode");
}

}  // namespace

ServerLoop::ServerLoop(const scene::Scene& scene, scene::BuiltScene built, bus::ServerBus& bus,
                       ServerOptions options, std::function<bool()> stop_requested)
    : run_(scene, server_scene(scene, std::move(built))),
      bus_(bus),
      options_(std::move(options)),
      stop_requested_(std::move(stop_requested)),
      step_reports_(kReportInterval),
      repeater_(options_.mode == Mode::lockstep ? options_.repeat_ms : 0, options_.repeats,
                std::max(options_.repeat_ms, options_.timeout_ms)),
      input_(options_.mode, options_.controllers, muscle_names(run_)) {
  check_options(options_);
  node_indices_ = select_nodes(run_.built().solid->mesh(), options_.nodes, scene.source);
  if (!options_.output.empty())
    log_ = std::make_unique<run_file::RunFileQueue>(
        scene_run::open_scene_run_file(options_.output, scene, run_.built()));
}

ServerLoop::~ServerLoop() = default;

ExitStatus ServerLoop::run() {
  ExitStatus status = common::kExitError;
  try {
    status = loop();
    // The last states' checks, which no next step reports.
    const scene_run::FinishedChecks last = run_.finish_checks();
    if (last.ellipticity_loss) warn_material(*last.ellipticity_loss);
    if (last.reduced_warning) warn_reduced(*last.reduced_warning);
  } catch (const std::exception& e) {
    status = common::kExitError;
    failure_ = e.what();
    std::fprintf(stderr, "sim_server: error: %s\n", e.what());
  }
  std::fprintf(stderr, "sim_server: %s\n", timing_.summary().c_str());
  const std::int64_t repeated_states = repeater_.total(), repeated_activations = input_.repeats();
  if (repeated_states > 0 || repeated_activations > 0)
    std::fprintf(stderr,
                 "sim_server: %lld states published again while activations were late, %lld "
                 "activations repeated by their senders (taken once)\n",
                 static_cast<long long>(repeated_states),
                 static_cast<long long>(repeated_activations));
  if (log_) {
    try {
      log_->set_attribute("status", status_text(status));
      log_->set_attribute("resets", std::to_string(resets_));
      if (options_.mode == Mode::lockstep) {
        log_->set_attribute("repeated_states", std::to_string(repeated_states));
        log_->set_attribute("repeated_activations", std::to_string(repeated_activations));
      }
      for (const auto& [name, value] : timing_.attributes()) log_->set_attribute(name, value);
      log_->flush();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "sim_server: error: %s\n", e.what());
      status = common::kExitError;
    }
  }
  return status;
}

std::string ServerLoop::status_text(ExitStatus status) const {
  switch (status) {
    case common::kExitOk:
      return "completed";
    case common::kExitInterrupted:
      return "interrupted";
    case common::kExitSilence:
      return "stopped: " + silence_text();
    default:  // kExitError, kExitNotConverged (the server never times out waiting: kExitTimeout)
      return "failed: " + failure_;
  }
}

ExitStatus ServerLoop::loop() {
  if (!start()) return common::kExitNotConverged;
  publish_model();
  log_frame();
  publish_state("ok");
  deadline_ = steady_seconds() + options_.timeout_ms * 1e-3;
  repeater_.restart(steady_seconds());
  anchor_clock();
  // One message per turn, so that a step a message makes due is taken before the next message
  // is judged (the step number it must carry moves on).
  while (true) {
    if (const auto end = ending()) return *end;
    if (inbox_.empty()) {
      for (bus::IncomingMessage& m : bus_.receive(wait_ms())) inbox_.push_back(std::move(m));
    }
    if (!inbox_.empty()) {
      const auto turn = StepTiming::Clock::now();
      input_.record(inbox_.front(), run_.step_count(), steady_seconds());
      inbox_.pop_front();
      timing_.add(StepTiming::Part::loop, turn);
      publish_notices();
      if (const auto command = input_.take_command()) execute(*command);
      if (shutdown_ || !failure_.empty()) continue;
    }
    if (inbox_.empty()) {
      if (const auto end = watch_silence()) return *end;
      repeat_state();
    }
    if (const fem::Vector* levels = due_levels()) {
      if (options_.mode == Mode::realtime) {
        const double left = step_start_time() - steady_seconds();
        if (left > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(left));
      }
      take_step(*levels);
      deadline_ = steady_seconds() + options_.timeout_ms * 1e-3;
      repeater_.restart(steady_seconds());
    }
  }
}

std::optional<ExitStatus> ServerLoop::ending() const {
  if (stop_requested_ && stop_requested_()) {
    std::fprintf(stderr, "sim_server: interrupted at step %lld\n",
                 static_cast<long long>(run_.step_count()));
    return common::kExitInterrupted;
  }
  if (!failure_.empty()) return common::kExitNotConverged;
  if (shutdown_) return common::kExitOk;
  if (options_.max_steps && run_.step_count() >= *options_.max_steps) return common::kExitOk;
  return std::nullopt;
}

int ServerLoop::wait_ms() const {
  if (paused_) return kPollSliceMs;
  switch (options_.mode) {
    case Mode::fast:
      return 0;
    case Mode::realtime: {
      const double left = step_start_time() - steady_seconds();
      return left > kSleepBelow ? std::min(static_cast<int>(left * 1e3), kPollSliceMs) : 0;
    }
    case Mode::lockstep:
      break;
  }
  const double until = std::min(deadline_, repeater_.next().value_or(deadline_));
  const double left_ms = (until - steady_seconds()) * 1e3;
  return std::clamp(static_cast<int>(left_ms) + 1, 0, kPollSliceMs);
}

const fem::Vector* ServerLoop::due_levels() const {
  if (paused_ || shutdown_ || !failure_.empty()) return nullptr;
  switch (options_.mode) {
    case Mode::lockstep:
      return input_.round().complete() ? &input_.round().levels() : nullptr;
    case Mode::fast:
      // Messages first: a step takes every activation that had arrived before it.
      return inbox_.empty() ? &input_.held() : nullptr;
    case Mode::realtime:
      if (!inbox_.empty() || step_start_time() - steady_seconds() > kSleepBelow) return nullptr;
      return &input_.held();
  }
  return nullptr;
}

std::optional<ExitStatus> ServerLoop::watch_silence() {
  const double now = steady_seconds();
  if (paused_) {
    deadline_ = now + options_.timeout_ms * 1e-3;  // a pause is not a silence
    return std::nullopt;
  }
  const std::int64_t step = run_.step_count();
  if (options_.mode == Mode::lockstep) {
    if (now < deadline_) return std::nullopt;
    std::fprintf(stderr, "sim_server: %s%s\n", lockstep_wait_text().c_str(),
                 options_.on_silence == OnSilence::stop ? ": stopping" : ", holding");
    if (options_.on_silence == OnSilence::stop) return common::kExitSilence;
    deadline_ = now + options_.timeout_ms * 1e-3;
    return std::nullopt;
  }
  if (options_.mode != Mode::realtime) return std::nullopt;
  const bool quiet = now - input_.last_heard() > options_.silence_s;
  if (silent_ && !quiet) {
    silent_ = false;
    std::fprintf(stderr, "sim_server: activations again at step %lld\n",
                 static_cast<long long>(step));
  } else if (!silent_ && quiet) {
    silent_ = true;
    const char* what = options_.on_silence == OnSilence::stop    ? "stopping"
                       : options_.on_silence == OnSilence::decay ? "activations set to 0"
                                                                 : "holding the activation";
    std::fprintf(stderr, "sim_server: %s at step %lld, %s\n", silence_text().c_str(),
                 static_cast<long long>(step), what);
    if (options_.on_silence == OnSilence::stop) return common::kExitSilence;
    if (options_.on_silence == OnSilence::decay) input_.zero_held();
  }
  return std::nullopt;
}

void ServerLoop::repeat_state() {
  if (options_.mode != Mode::lockstep || paused_ || input_.round().complete()) return;
  if (repeater_.due(steady_seconds())) publish_state("ok");
}

void ServerLoop::publish_notices() {
  for (tongue_lcm::lcmt_tongue_rejection& notice : input_.take_notices()) {
    notice.utime = wall_utime();
    bus_.publish_rejection(notice);
  }
}

void ServerLoop::anchor_clock() {
  anchor_time_ = steady_seconds();
  anchor_step_ = run_.step_count();
  input_.mark_heard(anchor_time_);
  silent_ = false;
}

double ServerLoop::step_start_time() const {
  return anchor_time_ +
         static_cast<double>(run_.step_count() - anchor_step_) * run_.scene().analysis.dt;
}

bool ServerLoop::should_publish() const {
  const std::int64_t step = run_.step_count();
  if (options_.mode == Mode::lockstep || step % options_.publish_every == 0) return true;
  return options_.max_steps && step >= *options_.max_steps;
}

std::string ServerLoop::silence_text() const {
  if (options_.mode == Mode::lockstep) {
    if (options_.controllers == 1)
      return "no activation for " + std::to_string(options_.timeout_ms) + " ms";
    return lockstep_wait_text();
  }
  char text[64];
  std::snprintf(text, sizeof text, "no activation for %g s", options_.silence_s);
  return text;
}

std::string ServerLoop::lockstep_wait_text() const {
  const std::string rest = "for step " + std::to_string(run_.step_count() + 1) + " within " +
                           std::to_string(options_.timeout_ms) + " ms";
  if (options_.controllers == 1) return "no activation " + rest;
  const ActivationRound& round = input_.round();
  std::string text = std::to_string(round.received()) + " of " + std::to_string(round.expected()) +
                     " activations " + rest;
  if (input_.round_rejections() > 0)
    text += " (" + std::to_string(input_.round_rejections()) +
            " rejected, the last: " + input_.round_rejection() + ")";
  return text;
}

bool ServerLoop::start() {
  const fem::StaticReport settling = run_.start();
  if (!settling.converged) {
    failure_ = "settling: " + settling.message;
    std::fprintf(stderr, "sim_server: settling failed: %s\n", settling.message.c_str());
    return false;
  }
  clear_to_step_zero();
  return true;
}

void ServerLoop::clear_to_step_zero() {
  input_.clear(run_.num_muscles());
  last_ = scene_run::StepResult{};
  last_.report.converged = true;
  last_.muscles = run_.muscle_frame();
  contact_.reset();
}

const fem::ContactReport& ServerLoop::contact() {
  if (!contact_) {
    const auto& obstacles = run_.built().contact;
    contact_ = obstacles ? obstacles->report(run_.displacement()) : fem::ContactReport{};
  }
  return *contact_;
}

void ServerLoop::execute(bus::Command command) {
  const long long step = run_.step_count();
  switch (command) {
    case bus::Command::shutdown:
      std::fprintf(stderr, "sim_server: shutdown at step %lld\n", step);
      shutdown_ = true;
      break;
    case bus::Command::describe:
      // The current state follows the model, so that a controller started after the server
      // (which missed state 0) learns the step to answer, in lock-step as in the other modes.
      publish_model();
      publish_state(paused_ ? "paused" : "ok");
      break;
    case bus::Command::pause:
      paused_ = true;
      publish_state("paused");
      break;
    case bus::Command::resume:
      if (paused_ && options_.mode == Mode::realtime) anchor_clock();
      if (paused_) repeater_.restart(steady_seconds());
      paused_ = false;  // a complete lock-step round is now due
      break;
    case bus::Command::reset:
      run_.restart();
      clear_to_step_zero();
      input_.clear_rejected();
      overruns_ = 0;
      anchor_clock();
      deadline_ = steady_seconds() + options_.timeout_ms * 1e-3;
      ++resets_;
      std::fprintf(stderr, "sim_server: reset to step 0\n");
      log_frame();
      publish_state(paused_ ? "paused" : "ok");
      repeater_.restart(steady_seconds());
      break;
  }
}

void ServerLoop::take_step(const fem::Vector& levels) {
  const double dt = run_.scene().analysis.dt;
  const double finish_by = step_start_time() + dt;  // real-time: later is an overrun
  const std::int64_t from = run_.step_count();
  auto mark = StepTiming::Clock::now();
  timing_.start_step(mark);
  last_ = run_.step(dt, levels);
  mark = timing_.add(StepTiming::Part::physics, mark);
  timing_.add_solver(last_.report);
  if (last_.ellipticity_loss) warn_material(*last_.ellipticity_loss);
  if (last_.reduced_warning) warn_reduced(*last_.reduced_warning);
  if (!last_.report.converged) {
    failure_ = "step " + std::to_string(from + 1) + " failed to converge: " + last_.report.message;
    std::fprintf(stderr, "sim_server: %s; stopping at the last accepted state\n", failure_.c_str());
    publish_state(
        failure_ + "; stopped at the last accepted state (step " + std::to_string(from) + ")",
        false);
    return;
  }
  if (options_.mode == Mode::realtime) count_overrun(steady_seconds() - finish_by);
  if (last_.report.constraint_unmet) {
    step_reports_.report(
        "contact", "sim_server: warning: step " + std::to_string(run_.step_count()) +
                       " accepted with a node deeper than the contact's penetration tolerance "
                       "(max_augmentations spent)");
  }
  contact_.reset();
  // The state first: in lock-step the controller's turn starts with it, and the rest of the
  // step's work (the run file's frame, the bookkeeping) overlaps that turn.
  if (should_publish()) publish_state("ok");
  mark = timing_.add(StepTiming::Part::state_message, mark);
  log_frame();
  mark = timing_.add(StepTiming::Part::run_file, mark);
  if (options_.mode == Mode::lockstep) input_.next_round(run_.levels());
  timing_.end_step(timing_.add(StepTiming::Part::loop, mark));
}

void ServerLoop::count_overrun(double late) {
  if (late <= 0.0) return;
  ++overruns_;
  char text[128];
  std::snprintf(text, sizeof text,
                "sim_server: overrun: step %lld finished %.3g ms late; %lld overruns in all",
                static_cast<long long>(run_.step_count()), late * 1e3,
                static_cast<long long>(overruns_));
  step_reports_.report("overrun", text);
}

void ServerLoop::warn_material(const scene_run::EllipticityFinding& found) {
  const std::string step = std::to_string(found.step);
  std::fprintf(stderr, "sim_server: warning: at step %s %s\n", step.c_str(), found.warning.c_str());
  if (log_) log_->set_attribute("material_warning", "step " + step + ": " + found.warning);
}

void ServerLoop::warn_reduced(const std::string& warning) {
  std::fprintf(stderr, "sim_server: warning: %s\n", warning.c_str());
  if (log_) log_->set_attribute("reduced_model_warning", warning);
}

void ServerLoop::publish_model() {
  bus_.publish_model(model_message(run_, wall_utime()));
}

void ServerLoop::publish_state(const std::string& status, bool converged) {
  StateNotes notes;
  notes.status = status;
  notes.converged = converged;
  notes.rejected_messages = input_.rejected();
  notes.overruns = overruns_;
  notes.utime = wall_utime();
  fill_state_message(state_, run_, node_indices_, last_, contact(), notes);
  bus_.publish_state(state_);
}

void ServerLoop::log_frame() {
  if (!log_) return;
  const fem::StepReport& r = last_.report;
  positions_.noalias() = run_.built().solid->rest_positions() + run_.displacement();
  log_->append(run_.time(), positions_,
               {r.iterations, r.final_residual, r.wall_seconds, r.cuts, run_.reduced_correction()},
               last_.muscles, scene_run::scene_contact_frame(run_.built(), contact()));
}

}  // namespace tongue::server
