#include "server/server_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <utility>

#include "bus/activation_validation.hpp"
#include "fem/integrator/static_solver.hpp"
#include "fem/mesh/boundary_faces.hpp"
#include "model/default_tongue.hpp"
#include "scene_run/scene_run_file.hpp"

namespace tongue::server {
namespace {

// Longest single wait for messages [ms]: the stop predicate is looked at least this often.
constexpr int kPollSliceMs = 100;
// Rejections of one kind are reported on stderr at most once per this many seconds.
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

}  // namespace

ServerLoop::ServerLoop(const scene::Scene& scene, scene::BuiltScene built, ServerBus& bus,
                       ServerOptions options, std::function<bool()> stop_requested)
    : scene_(scene),
      built_(std::move(built)),
      bus_(bus),
      options_(std::move(options)),
      stop_requested_(std::move(stop_requested)),
      round_(options_.controllers) {
  if (scene_.analysis.type != scene::AnalysisType::dynamic)
    throw std::invalid_argument(scene_.source +
                                ": the server needs a dynamic analysis (analysis.type: dynamic)");
  if (!built_.muscles || built_.muscles->num_muscles() == 0)
    throw std::invalid_argument(scene_.source +
                                ": the server needs muscles (muscles: builtin or a list)");
  if (options_.timeout_ms <= 0) throw std::invalid_argument("the timeout must be > 0 ms");
  if (!(options_.silence_s > 0.0)) throw std::invalid_argument("the silence must be > 0 s");
  if (options_.publish_every < 1)
    throw std::invalid_argument("states must be published every 1 or more steps");
  if (options_.on_silence == OnSilence::decay && options_.mode != Mode::realtime)
    throw std::invalid_argument("decay on silence needs the real-time mode");
  if (options_.controllers != 1 && options_.mode != Mode::lockstep)
    throw std::invalid_argument("several controllers per step need the lock-step mode");
  for (const auto& m : built_.muscles->muscles()) muscle_names_.push_back(m.name);
  const fem::Mesh& mesh = built_.solid->mesh();
  switch (options_.nodes) {
    case Nodes::all:
      node_indices_.resize(static_cast<std::size_t>(mesh.num_nodes()));
      std::iota(node_indices_.begin(), node_indices_.end(), 0);
      break;
    case Nodes::surface:
      node_indices_ = fem::boundary_nodes(mesh);
      break;
    case Nodes::midsagittal: {
      const auto it = mesh.node_sets.find("midsagittal");
      if (it == mesh.node_sets.end() || it->second.empty())
        throw std::invalid_argument(scene_.source +
                                    ": the mesh has no \"midsagittal\" node set (the node subset "
                                    "midsagittal needs one; the built-in tongue has it)");
      node_indices_ = it->second;
      break;
    }
    case Nodes::landmarks:
      for (const std::string& name : model::landmark_names()) {
        const auto it = mesh.node_sets.find(name);
        if (it != mesh.node_sets.end() && !it->second.empty())
          node_indices_.push_back(it->second.front());
      }
      if (node_indices_.empty())
        throw std::invalid_argument(scene_.source +
                                    ": the mesh has none of the landmark node sets (tip, blade, "
                                    "palatal_dorsum, velar_dorsum, root, gg_insertion) the node "
                                    "subset landmarks needs; the built-in tongue has them");
      break;
  }
  if (!options_.output.empty())
    log_ = scene_run::open_scene_run_file(options_.output, scene_, built_);
}

ServerLoop::~ServerLoop() = default;

ExitStatus ServerLoop::run() {
  ExitStatus status = ExitStatus::error;
  try {
    status = loop();
  } catch (const std::exception& e) {
    failure_ = e.what();
    std::fprintf(stderr, "sim_server: error: %s\n", e.what());
  }
  if (log_) {
    try {
      std::string text;
      switch (status) {
        case ExitStatus::ok:
          text = "completed";
          break;
        case ExitStatus::interrupted:
          text = "interrupted";
          break;
        case ExitStatus::silence:
          text = "stopped: " + silence_text();
          break;
        default:
          text = "failed: " + failure_;
          break;
      }
      log_->set_attribute("status", text);
      log_->set_attribute("resets", std::to_string(resets_));
      log_->flush();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "sim_server: error: %s\n", e.what());
      status = ExitStatus::error;
    }
  }
  return status;
}

ExitStatus ServerLoop::loop() {
  if (!initialize()) return ExitStatus::not_converged;
  publish_model();
  log_frame();
  publish_state("ok");
  double deadline = steady_seconds() + options_.timeout_ms * 1e-3;
  anchor_clock();
  const bool realtime = options_.mode == Mode::realtime;
  while (true) {
    if (stop_requested_ && stop_requested_()) {
      std::fprintf(stderr, "sim_server: interrupted at step %lld\n", static_cast<long long>(step_));
      return ExitStatus::interrupted;
    }
    if (!failure_.empty()) return ExitStatus::not_converged;
    if (shutdown_) return ExitStatus::ok;
    if (options_.max_steps && step_ >= *options_.max_steps) return ExitStatus::ok;

    int wait_ms = kPollSliceMs;
    if (!paused_) {
      if (options_.mode == Mode::fast) {
        wait_ms = 0;
      } else if (realtime) {
        const double left = step_start_time() - steady_seconds();
        wait_ms = left > kSleepBelow ? std::min(static_cast<int>(left * 1e3), kPollSliceMs) : 0;
      } else {
        const double left_ms = (deadline - steady_seconds()) * 1e3;
        wait_ms = std::clamp(static_cast<int>(left_ms) + 1, 0, kPollSliceMs);
      }
    }
    const std::int64_t step_before = step_;
    const std::vector<IncomingMessage> messages = bus_.receive(wait_ms);
    for (const IncomingMessage& message : messages) {
      handle(message);
      if (shutdown_ || !failure_.empty()) break;
    }
    if (shutdown_ || !failure_.empty() || paused_) {
      if (options_.mode == Mode::lockstep) deadline = steady_seconds() + options_.timeout_ms * 1e-3;
      continue;
    }

    if (options_.mode == Mode::fast) {
      advance(levels_);
    } else if (realtime) {
      const double now = steady_seconds();
      if (!silent_ && now - last_activation_ > options_.silence_s) {
        silent_ = true;
        const char* what = options_.on_silence == OnSilence::stop    ? "stopping"
                           : options_.on_silence == OnSilence::decay ? "activations set to 0"
                                                                     : "holding the activation";
        std::fprintf(stderr, "sim_server: %s at step %lld, %s\n", silence_text().c_str(),
                     static_cast<long long>(step_), what);
        if (options_.on_silence == OnSilence::stop) return ExitStatus::silence;
        if (options_.on_silence == OnSilence::decay) levels_.setZero();
      }
      const double left = step_start_time() - now;
      if (left > kSleepBelow) continue;
      if (left > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(left));
      advance(levels_);
    } else {
      const double now = steady_seconds();
      if (step_ != step_before) {
        deadline = now + options_.timeout_ms * 1e-3;
      } else if (now >= deadline) {
        std::fprintf(stderr, "sim_server: %s%s\n", lockstep_wait_text().c_str(),
                     options_.on_silence == OnSilence::stop ? ": stopping" : ", holding");
        if (options_.on_silence == OnSilence::stop) return ExitStatus::silence;
        deadline = now + options_.timeout_ms * 1e-3;
      }
    }
  }
}

void ServerLoop::anchor_clock() {
  anchor_time_ = steady_seconds();
  anchor_step_ = step_;
  last_activation_ = anchor_time_;
  silent_ = false;
}

double ServerLoop::step_start_time() const {
  return anchor_time_ + static_cast<double>(step_ - anchor_step_) * scene_.analysis.dt;
}

bool ServerLoop::should_publish() const {
  if (options_.mode == Mode::lockstep || step_ % options_.publish_every == 0) return true;
  return options_.max_steps && step_ >= *options_.max_steps;
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
  const std::string rest = "for step " + std::to_string(step_ + 1) + " within " +
                           std::to_string(options_.timeout_ms) + " ms";
  if (options_.controllers == 1) return "no activation " + rest;
  return std::to_string(round_.received()) + " of " + std::to_string(round_.expected()) +
         " activations " + rest;
}

bool ServerLoop::initialize() {
  const int n = built_.solid->num_dofs();
  fem::Vector u = fem::Vector::Zero(n);
  built_.muscles->set_activations(fem::Vector::Zero(built_.muscles->num_muscles()));
  if (scene_.analysis.settle) {
    // Rest under gravity and loads with every muscle off, as sim_batch starts.
    const fem::StaticReport report = fem::solve_static(*built_.system, u, built_.static_settings);
    if (!report.converged) {
      failure_ = "settling: " + report.message;
      std::fprintf(stderr, "sim_server: settling failed: %s\n", report.message.c_str());
      return false;
    }
  }
  initial_u_ = u;
  restart();
  return true;
}

void ServerLoop::restart() {
  const int m = built_.muscles->num_muscles();
  levels_ = fem::Vector::Zero(m);
  built_.muscles->set_activations(levels_);
  round_.start(levels_);
  // A fresh integrator: nothing (factorizations, previous dt) carries over from before a reset,
  // so a run after a reset repeats the first one exactly.
  integrator_ = std::make_unique<fem::NewmarkIntegrator>(*built_.system, built_.dynamic_settings);
  integrator_->initialize(initial_u_, fem::Vector::Zero(initial_u_.size()), 0.0);
  accepted_u_ = integrator_->displacement();
  accepted_v_ = integrator_->velocity();
  step_ = 0;
  time_ = 0.0;
  last_report_ = fem::StepReport{};
  last_report_.converged = true;
}

bool ServerLoop::advance(const fem::Vector& levels) {
  levels_ = levels;
  built_.muscles->set_activations(levels_);
  const fem::StepReport r = integrator_->step(scene_.analysis.dt);
  last_report_ = r;
  if (!r.converged) {
    failure_ = "step " + std::to_string(step_ + 1) + " failed to converge: " + r.message;
    std::fprintf(stderr, "sim_server: %s; stopping at the last accepted state\n", failure_.c_str());
    publish_state(
        failure_ + "; stopped at the last accepted state (step " + std::to_string(step_) + ")",
        false);
    return false;
  }
  if (options_.mode == Mode::realtime) {
    const double late = steady_seconds() - (step_start_time() + scene_.analysis.dt);
    if (late > 0.0) {
      ++overruns_;
      const double now = steady_seconds();
      if (now - last_overrun_report_ >= kReportInterval) {
        std::fprintf(stderr, "sim_server: overrun: step %lld finished %.3g ms late",
                     static_cast<long long>(step_ + 1), late * 1e3);
        if (unreported_overruns_ > 0)
          std::fprintf(stderr, " (and %lld more not shown)",
                       static_cast<long long>(unreported_overruns_));
        std::fprintf(stderr, "; %lld overruns in all\n", static_cast<long long>(overruns_));
        last_overrun_report_ = now;
        unreported_overruns_ = 0;
      } else {
        ++unreported_overruns_;
      }
    }
  }
  accepted_u_ = integrator_->displacement();
  accepted_v_ = integrator_->velocity();
  ++step_;
  time_ = integrator_->time();
  if (const auto loss = ellipticity_.first_loss(accepted_u_)) {
    const std::string text = fem::describe(*loss, built_.solid->material());
    std::fprintf(stderr, "sim_server: warning: at step %lld %s\n", static_cast<long long>(step_),
                 text.c_str());
    if (log_) {
      log_->set_attribute("material_warning", "step " + std::to_string(step_) + ": " + text);
    }
  }
  if (options_.mode == Mode::lockstep) round_.start(levels_);
  log_frame();
  if (should_publish()) publish_state("ok");
  return true;
}

void ServerLoop::handle(const IncomingMessage& message) {
  if (message.channel == IncomingMessage::Channel::activation) {
    handle_activation(message);
  } else {
    handle_command(message);
  }
}

void ServerLoop::handle_activation(const IncomingMessage& message) {
  tongue_lcm::lcmt_tongue_activation msg;
  std::string reason;
  if (!bus::decode_activation(message.bytes.data(), static_cast<int>(message.bytes.size()), msg,
                              reason)) {
    reject("undecodable activation", reason);
    return;
  }
  const bus::ActivationCheck check = bus::check_activation(
      msg, muscle_names_, std::vector<double>(levels_.data(), levels_.data() + levels_.size()));
  if (!check.accepted) {
    reject("invalid activation", check.reason);
    return;
  }
  if (options_.mode != Mode::lockstep) {
    // Held from the next step on.
    levels_ = Eigen::Map<const fem::Vector>(check.levels.data(),
                                            static_cast<Eigen::Index>(check.levels.size()));
    last_activation_ = steady_seconds();
    if (silent_) {
      silent_ = false;
      std::fprintf(stderr, "sim_server: activations again at step %lld\n",
                   static_cast<long long>(step_));
    }
    return;
  }
  if (msg.step <= step_) {
    reject("stale activation",
           "step " + std::to_string(msg.step) + " <= current step " + std::to_string(step_));
    return;
  }
  if (msg.step > step_ + 1) {
    reject("future activation",
           "step " + std::to_string(msg.step) + " > next step " + std::to_string(step_ + 1));
    return;
  }
  // While paused a round can be complete; a further message then starts the next one (with one
  // controller: the latest activation for k + 1 is the one applied on resume).
  if (round_.complete()) round_.start(levels_);
  if (const auto muscle = round_.already_set(check.named)) {
    reject("overlapping activation",
           "\"" + muscle_names_[*muscle] + "\" is already set for step " +
               std::to_string(step_ + 1) + " by an earlier message (each of the " +
               std::to_string(options_.controllers) + " controllers names its own muscles)");
    return;
  }
  round_.add(check.named, check.levels);
  if (!round_.complete() || paused_) return;  // a complete round waits for resume
  const fem::Vector merged = round_.levels();
  advance(merged);
}

void ServerLoop::handle_command(const IncomingMessage& message) {
  tongue_lcm::lcmt_tongue_command msg;
  const int size = static_cast<int>(message.bytes.size());
  if (msg.decode(message.bytes.data(), 0, size) != size) {
    reject("undecodable command",
           "not a whole lcmt_tongue_command (" + std::to_string(size) + " bytes)");
    return;
  }
  const std::string& c = msg.command;
  if (c == "shutdown") {
    std::fprintf(stderr, "sim_server: shutdown at step %lld\n", static_cast<long long>(step_));
    shutdown_ = true;
  } else if (c == "describe") {
    // The current state follows the model, so that a controller started after the server
    // (which missed state 0) learns the step to answer, in lock-step as in the other modes.
    publish_model();
    publish_state(paused_ ? "paused" : "ok");
  } else if (c == "pause") {
    paused_ = true;
    publish_state("paused");
  } else if (c == "resume") {
    if (paused_ && options_.mode == Mode::realtime) anchor_clock();
    paused_ = false;
    if (options_.mode == Mode::lockstep && round_.complete()) {
      const fem::Vector merged = round_.levels();
      advance(merged);
    }
  } else if (c == "reset") {
    restart();
    rejected_ = 0;
    overruns_ = 0;
    anchor_clock();
    ++resets_;
    std::fprintf(stderr, "sim_server: reset to step 0\n");
    log_frame();
    publish_state(paused_ ? "paused" : "ok");
  } else {
    reject("unknown command", "'" + c + "'");
  }
}

void ServerLoop::reject(const std::string& kind, const std::string& reason) {
  ++rejected_;
  const double now = steady_seconds();
  const auto it = last_reported_.find(kind);
  if (it != last_reported_.end() && now - it->second < kReportInterval) {
    ++unreported_[kind];
    return;
  }
  const int more = unreported_[kind];
  std::fprintf(stderr, "sim_server: rejected %s at step %lld: %s", kind.c_str(),
               static_cast<long long>(step_), reason.c_str());
  if (more > 0) std::fprintf(stderr, " (and %d more of this kind not shown)", more);
  std::fprintf(stderr, "\n");
  last_reported_[kind] = now;
  unreported_[kind] = 0;
}

void ServerLoop::publish_model() {
  const fem::Mesh& mesh = built_.solid->mesh();
  tongue_lcm::lcmt_tongue_model msg;
  msg.utime = wall_utime();
  msg.num_nodes = mesh.num_nodes();
  const fem::Vector& rest = built_.solid->rest_positions();
  msg.rest_positions.assign(rest.data(), rest.data() + rest.size());
  msg.num_rest_positions = static_cast<std::int32_t>(msg.rest_positions.size());
  msg.num_elements = mesh.num_elements();
  for (const fem::Hex8& e : mesh.elements)
    msg.elements.insert(msg.elements.end(), e.begin(), e.end());
  msg.num_element_nodes = static_cast<std::int32_t>(msg.elements.size());
  msg.muscle_names = muscle_names_;
  for (const auto& m : built_.muscles->muscles()) msg.muscle_max_forces.push_back(m.max_force);
  msg.num_muscles = static_cast<std::int32_t>(msg.muscle_names.size());
  for (const std::string& name : model::landmark_names()) {
    const auto it = mesh.node_sets.find(name);
    if (it == mesh.node_sets.end() || it->second.empty()) continue;
    msg.landmark_names.push_back(name);
    msg.landmark_nodes.push_back(it->second.front());
  }
  msg.num_landmarks = static_cast<std::int32_t>(msg.landmark_names.size());
  msg.dt = scene_.analysis.dt;
  msg.scene = scene_.text;
  bus_.publish_model(msg);
}

void ServerLoop::publish_state(const std::string& status, bool converged) {
  const model::MuscleForces& muscles = *built_.muscles;
  tongue_lcm::lcmt_tongue_state msg;
  msg.utime = wall_utime();
  msg.step = step_;
  msg.time = time_;
  msg.num_nodes = static_cast<std::int32_t>(node_indices_.size());
  msg.node_indices = node_indices_;
  const fem::Vector& rest = built_.solid->rest_positions();
  msg.positions.reserve(3 * node_indices_.size());
  for (const int i : node_indices_)
    for (int c = 0; c < 3; ++c) msg.positions.push_back(rest[3 * i + c] + accepted_u_[3 * i + c]);
  msg.num_positions = static_cast<std::int32_t>(msg.positions.size());
  msg.num_muscles = muscles.num_muscles();
  const fem::Vector lengths = muscles.muscle_lengths(accepted_u_);
  const fem::Vector velocities = muscles.muscle_velocities(accepted_u_, accepted_v_);
  msg.muscle_lengths.assign(lengths.data(), lengths.data() + lengths.size());
  msg.muscle_velocities.assign(velocities.data(), velocities.data() + velocities.size());
  msg.activations.assign(levels_.data(), levels_.data() + levels_.size());
  msg.newton_iterations = last_report_.iterations;
  msg.residual_norm = last_report_.final_residual;
  msg.step_wall_time = last_report_.wall_seconds;
  msg.step_cuts = last_report_.cuts;
  msg.converged = converged;
  msg.status = status;
  msg.rejected_messages = rejected_;
  msg.overruns = overruns_;
  bus_.publish_state(msg);
}

void ServerLoop::log_frame() {
  if (!log_) return;
  log_->append(time_, built_.solid->rest_positions() + accepted_u_,
               {last_report_.iterations, last_report_.final_residual, last_report_.wall_seconds,
                last_report_.cuts},
               scene_run::scene_muscle_frame(built_, accepted_u_, &accepted_v_));
}

}  // namespace tongue::server
