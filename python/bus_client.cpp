#include "python/bus_client.hpp"

#include <stdexcept>
#include <utility>

namespace tongue::python {

BusClient::BusClient(const std::string& program, const controller::CommonOptions& options)
    : program_(program), session_(program, options, [this]() -> std::optional<std::string> {
        if (stop_ == nullptr || !*stop_) return std::nullopt;
        return (*stop_)();
      }) {}

const controller::Model* BusClient::connect(const controller::ControlSession::StopCheck& stop) {
  stop_ = &stop;
  model_ = session_.wait_for_model();
  stop_ = nullptr;
  return model_;
}

std::optional<controller::State> BusClient::next(
    const controller::ControlSession::StopCheck& stop) {
  if (model_ == nullptr && !session_.ended() && connect(stop) == nullptr) return std::nullopt;
  if (queued_.empty()) {
    stop_ = &stop;
    std::optional<controller::NewStates> fresh;
    try {
      fresh = session_.next_states();
    } catch (...) {
      stop_ = nullptr;
      throw;
    }
    stop_ = nullptr;
    if (!fresh) return std::nullopt;
    awaiting_ = fresh->answer_step.has_value();
    // A batch without new states: the session ended after the last one, or (repeats alone) it
    // asks again for the answer to the state handed out last.
    if (fresh->states.empty()) return awaiting_ ? last_ : next(stop);
    queued_.assign(std::make_move_iterator(fresh->states.begin()),
                   std::make_move_iterator(fresh->states.end()));
  }
  last_ = std::move(queued_.front());
  queued_.pop_front();
  return last_;
}

void BusClient::send(const controller::MuscleLevels& levels) {
  // A later state follows (the server only takes its answer), or the session ended with this
  // one (nothing is sent for later steps).
  if (!queued_.empty() || (!awaiting_ && session_.ended())) return;
  if (!awaiting_)
    throw std::logic_error(last_ ? "the state of step " + std::to_string(last_->step) +
                                       " is answered already"
                                 : std::string("no state received yet"));
  session_.answer(levels);
  awaiting_ = false;
}

std::string BusClient::summary(const std::string& controller_summary) const {
  return controller::summary_line(program_, session_.outcome(), session_.options(),
                                  controller_summary);
}

controller::CommandLine parse_controller_command_line(const std::vector<std::string>& args,
                                                      const std::vector<std::string>& options) {
  std::vector<const char*> argv{"python"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  return controller::parse_command_line(static_cast<int>(argv.size()), argv.data(), options);
}

}  // namespace tongue::python
