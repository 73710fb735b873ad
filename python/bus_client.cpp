#include "python/bus_client.hpp"

#include <stdexcept>
#include <utility>

namespace tongue::python {
namespace {

// The stop check of one call, for the session to ask while the call lasts (and not after, when
// the check is gone).
class StopScope {
 public:
  StopScope(const controller::ControlSession::StopCheck*& slot,
            const controller::ControlSession::StopCheck& stop)
      : slot_(slot) {
    slot_ = &stop;
  }
  ~StopScope() { slot_ = nullptr; }
  StopScope(const StopScope&) = delete;
  StopScope& operator=(const StopScope&) = delete;

 private:
  const controller::ControlSession::StopCheck*& slot_;
};

}  // namespace

BusClient::BusClient(const std::string& program, const controller::CommonOptions& options)
    : program_(program), session_(program, options, [this]() -> std::optional<std::string> {
        if (stop_ == nullptr || !*stop_) return std::nullopt;
        return (*stop_)();
      }) {}

const controller::Model* BusClient::connect(const controller::ControlSession::StopCheck& stop) {
  const StopScope scope(stop_, stop);
  model_ = session_.wait_for_model();
  return model_;
}

std::optional<controller::State> BusClient::next(
    const controller::ControlSession::StopCheck& stop) {
  if (model_ == nullptr && !session_.ended() && connect(stop) == nullptr) return std::nullopt;
  if (queued_.empty()) {
    std::optional<controller::NewStates> fresh;
    {
      const StopScope scope(stop_, stop);
      fresh = session_.next_states();
    }
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
