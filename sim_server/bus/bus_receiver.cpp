#include "bus/bus_receiver.hpp"

#include <cerrno>
#include <stdexcept>

namespace tongue::bus {

BusReceiver::BusReceiver(lcm::LCM& lcm, const LcmUrl& url,
                         const std::map<std::string, std::size_t>& limits,
                         const std::string& program)
    : lcm_(lcm), program_(program), reports_(1.0) {
  if (!lcm_.good()) throw std::runtime_error("cannot open the LCM bus at '" + url.text + "'");
  if (url.provider == LcmUrl::Provider::udpm) {
    udpm_ = std::make_unique<UdpmReceiver>(
        url, limits,
        [this](const std::string& kind, const std::string& detail) { report(kind, detail); });
    return;
  }
  for (const auto& [channel, limit] : limits) {
    auto s = std::make_unique<Subscription>(Subscription{this, limit});
    s->lcm = lcm_.subscribeFunction(channel, &BusReceiver::on_message, s.get());
    // liblcm's default queue of 30 drops the rest of a burst; receive() bounds what is taken.
    if (s->lcm == nullptr || s->lcm->setQueueCapacity(100000) != 0)
      throw std::runtime_error("cannot subscribe to " + channel + " on '" + url.text + "'");
    subscriptions_[channel] = std::move(s);
  }
}

BusReceiver::~BusReceiver() {
  for (auto& [channel, s] : subscriptions_) lcm_.unsubscribe(s->lcm);
}

void BusReceiver::set_limit(const std::string& channel, std::size_t max_bytes) {
  if (udpm_) {
    udpm_->set_limit(channel, max_bytes);
  } else if (const auto it = subscriptions_.find(channel); it != subscriptions_.end()) {
    it->second->limit = max_bytes;
  }
}

void BusReceiver::on_message(const lcm::ReceiveBuffer* rbuf, const std::string& channel,
                             Subscription* s) {
  const auto size = static_cast<std::size_t>(rbuf->data_size);
  if (size > s->limit) {
    ++s->receiver->memq_drops_.oversize;
    s->receiver->report("oversize message", std::to_string(size) + " bytes on " + channel +
                                                ", limit " + std::to_string(s->limit));
    return;
  }
  const auto* data = static_cast<const std::uint8_t*>(rbuf->data);
  s->receiver->pending_.push_back({channel, std::vector<std::uint8_t>(data, data + size)});
}

bool BusReceiver::receive(int timeout_ms, std::vector<ReceivedMessage>& out) {
  if (udpm_) return udpm_->receive(timeout_ms, kBatch, out);
  if (pending_.empty()) {
    int handled = lcm_.handleTimeout(timeout_ms < 0 ? 0 : timeout_ms);
    while (handled > 0 && pending_.size() < kBatch) handled = lcm_.handleTimeout(0);
    if (handled < 0) {
      if (errno == EINTR) return false;
      throw std::runtime_error("LCM failed while receiving messages");
    }
  }
  for (std::size_t i = 0; i < kBatch && !pending_.empty(); ++i) {
    out.push_back(std::move(pending_.front()));
    pending_.pop_front();
  }
  return true;
}

DropCounts BusReceiver::drops() const {
  return udpm_ ? udpm_->drops() : memq_drops_;
}

void BusReceiver::report(const std::string& kind, const std::string& detail) {
  reports_.report(kind, program_ + ": dropped " + kind + ": " + detail);
}

}  // namespace tongue::bus
