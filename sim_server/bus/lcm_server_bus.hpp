#pragma once
// ServerBus on an lcm::LCM: publications on the state and model channels through liblcm, and
// raw bytes received on the activation and command channels through a BusReceiver (its own
// socket on udpm: liblcm never receives), each message no larger than its channel's limit
// (receive_limits.hpp), at most BusReceiver::kBatch per receive(). The bytes go to
// decode_activation and decode_command, never straight to lcm-gen's decoder. A message is
// encoded into one buffer kept for the bus's life (lcm::LCM::publish of a message would
// allocate one per call) and its bytes published.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/bus_receiver.hpp"
#include "bus/channels.hpp"
#include "bus/lcm_url.hpp"
#include "bus/server_bus.hpp"

namespace tongue::bus {

class LcmServerBus final : public ServerBus {
 public:
  // activation_limit: the largest activation message taken [bytes] (activation_limit() of the
  // model's muscles). Throws std::invalid_argument for a URL parse_lcm_url rejects and
  // std::runtime_error naming the URL when LCM cannot be initialized on it.
  LcmServerBus(const std::string& url, const Channels& channels, std::size_t activation_limit);
  LcmServerBus(const LcmServerBus&) = delete;
  LcmServerBus& operator=(const LcmServerBus&) = delete;

  void publish_model(const tongue_lcm::lcmt_tongue_model& msg) override;
  void publish_state(const tongue_lcm::lcmt_tongue_state& msg) override;
  void publish_rejection(const tongue_lcm::lcmt_tongue_rejection& msg) override;
  std::vector<IncomingMessage> receive(int timeout_ms) override;

  // What the receiver dropped so far (oversize, bad datagrams, bad fragments).
  DropCounts drops() const { return receiver_.drops(); }

 private:
  template <typename Message>
  void publish(const std::string& channel, const Message& msg);

  LcmUrl url_;
  lcm::LCM lcm_;
  Channels channels_;
  BusReceiver receiver_;
  std::vector<std::uint8_t> encoded_;  // the last message published, encoded
};

}  // namespace tongue::bus
