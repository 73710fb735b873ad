#include "controller/controller_bus.hpp"

#include <cerrno>
#include <chrono>
#include <stdexcept>
#include <utility>

#include "bus/rejection_notice.hpp"

namespace tongue::controller {

std::int64_t wall_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

ControllerBus::ControllerBus(const std::string& url, const bus::Channels& channels,
                             std::string sender)
    : url_(url), channels_(channels), sender_(std::move(sender)), lcm_(url) {
  if (!lcm_.good()) throw std::runtime_error("cannot open the LCM bus at '" + url + "'");
  lcm::Subscription* state = lcm_.subscribe(channels_.state, &ControllerBus::on_state, this);
  lcm::Subscription* model = lcm_.subscribe(channels_.model, &ControllerBus::on_model, this);
  // Raw bytes: a notice is decoded by the bounds-checked decode_rejection, any sender can
  // publish on the channel.
  lcm::Subscription* rejection =
      lcm_.subscribe(channels_.rejection, &ControllerBus::on_rejection, this);
  for (lcm::Subscription* s : {state, model, rejection}) {
    if (s == nullptr) throw std::runtime_error("cannot subscribe on '" + url + "'");
    subscriptions_.push_back(s);
  }
  // Real-time servers publish every step; a slow controller must not lose states to LCM's
  // default queue of 30 (it answers the latest one and feeds all to its controller).
  state->setQueueCapacity(10000);
}

ControllerBus::~ControllerBus() {
  for (lcm::Subscription* s : subscriptions_) lcm_.unsubscribe(s);
}

bool ControllerBus::poll(int timeout_ms) {
  int handled = lcm_.handleTimeout(timeout_ms < 0 ? 0 : timeout_ms);
  // Take whatever else is already there without waiting.
  while (handled > 0) handled = lcm_.handleTimeout(0);
  if (handled < 0) {
    if (errno == EINTR) return false;
    throw std::runtime_error("LCM failed while receiving on '" + url_ + "'");
  }
  return true;
}

void ControllerBus::send_activation(std::int64_t step, const MuscleLevels& levels) {
  Activation msg;
  msg.utime = wall_utime();
  msg.step = step;
  msg.num_muscles = static_cast<std::int32_t>(levels.names.size());
  msg.names = levels.names;
  msg.levels = levels.levels;
  msg.sender = sender_;
  publish(msg);
  last_activation_ = std::move(msg);
}

void ControllerBus::resend_activation() {
  if (last_activation_) publish(*last_activation_);
}

void ControllerBus::publish(const Activation& msg) {
  if (lcm_.publish(channels_.activation, &msg) != 0)
    throw std::runtime_error("cannot publish on " + channels_.activation);
}

void ControllerBus::send_command(bus::Command command) {
  const tongue_lcm::lcmt_tongue_command msg = bus::command_message(command, wall_utime());
  if (lcm_.publish(channels_.command, &msg) != 0)
    throw std::runtime_error("cannot publish on " + channels_.command);
}

void ControllerBus::on_state(const lcm::ReceiveBuffer*, const std::string&, const State* msg) {
  states_.push_back(*msg);
}

void ControllerBus::on_model(const lcm::ReceiveBuffer*, const std::string&, const Model* msg) {
  models_.push_back(*msg);
}

void ControllerBus::on_rejection(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  Rejection notice;
  std::string reason;
  if (bus::decode_rejection(rbuf->data, static_cast<int>(rbuf->data_size), notice, reason))
    rejections_.push_back(std::move(notice));
}

}  // namespace tongue::controller
