// lossy_relay: a bus that loses messages, for testing lock-step's loss recovery (the kernel here
// has no netem qdisc). It joins a controllers' bus and a server's bus (two LCM URLs, e.g. two udpm
// ports) for one channel prefix, forwarding the controllers' channels (ACTIVATION, COMMAND) to the
// server's bus and the server's (STATE, MODEL, REJECTION) to the controllers', and drops each
// message with probability --drop, decided by a seeded generator per direction (so that a seed
// gives one drop pattern over the sequence of messages of each direction).
//
// usage: lossy_relay --controllers URL --server URL [--prefix TONGUE_] [--drop P] [--seed N]
// Runs until SIGINT or SIGTERM, then prints one line per direction on stdout:
//   to server: <forwarded> forwarded, <dropped> dropped
//   to controllers: <forwarded> forwarded, <dropped> dropped
// Exit status 0, or 1 for a bad command line or a bus that cannot be opened.
#include <poll.h>
#include <signal.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/channels.hpp"

namespace {

volatile sig_atomic_t g_stop = 0;

void on_signal(int) {
  g_stop = 1;
}

// One direction: messages heard on from, published on to unless dropped.
class Direction {
 public:
  Direction(lcm::LCM& from, lcm::LCM& to, const std::vector<std::string>& channels, double drop,
            std::uint64_t seed)
      : to_(to), drop_(drop), random_(seed) {
    for (const std::string& channel : channels) {
      lcm::Subscription* s = from.subscribe(channel, &Direction::on_message, this);
      // Everything that arrives is forwarded or dropped here, never by LCM's queue.
      if (s != nullptr) s->setQueueCapacity(1000000);
    }
  }
  std::int64_t forwarded() const { return forwarded_; }
  std::int64_t dropped() const { return dropped_; }

 private:
  void on_message(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    // A uniform number in [0, 1) from the top 53 bits: the same on every platform.
    const double u = static_cast<double>(random_() >> 11) * 0x1.0p-53;
    if (u < drop_) {
      ++dropped_;
      return;
    }
    to_.publish(channel, rbuf->data, rbuf->data_size);
    ++forwarded_;
  }

  lcm::LCM& to_;
  double drop_;
  std::mt19937_64 random_;
  std::int64_t forwarded_ = 0, dropped_ = 0;
};

int usage(const char* why) {
  std::fprintf(stderr,
               "lossy_relay: %s\nusage: lossy_relay --controllers URL --server URL "
               "[--prefix TONGUE_] [--drop P] [--seed N]\n",
               why);
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  std::string controllers_url, server_url, prefix{tongue::bus::kDefaultChannelPrefix};
  double drop = 0.0;
  std::uint64_t seed = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--controllers") {
      controllers_url = value;
    } else if (key == "--server") {
      server_url = value;
    } else if (key == "--prefix") {
      prefix = value;
    } else if (key == "--drop") {
      drop = std::strtod(value.c_str(), nullptr);
    } else if (key == "--seed") {
      seed = std::strtoull(value.c_str(), nullptr, 10);
    } else {
      return usage(("unknown option " + key).c_str());
    }
  }
  if (argc % 2 == 0) return usage("every option takes a value");
  if (controllers_url.empty() || server_url.empty()) return usage("both URLs are needed");
  if (!(drop >= 0.0 && drop < 1.0)) return usage("--drop must be in [0, 1)");

  lcm::LCM controllers(controllers_url), server(server_url);
  if (!controllers.good() || !server.good()) return usage("cannot open the buses");
  const tongue::bus::Channels c(prefix);
  Direction to_server(controllers, server, {c.activation, c.command}, drop, seed);
  Direction to_controllers(server, controllers, {c.state, c.model, c.rejection}, drop, seed + 1);

  struct sigaction action {};
  action.sa_handler = on_signal;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  // Unbuffered, so that a test reads the last line as soon as the relay has ended.
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  std::printf("lossy_relay: relaying %s* with drop %g, seed %llu\n", prefix.c_str(), drop,
              static_cast<unsigned long long>(seed));

  pollfd fds[2] = {{controllers.getFileno(), POLLIN, 0}, {server.getFileno(), POLLIN, 0}};
  while (!g_stop) {
    if (poll(fds, 2, 50) <= 0) continue;  // a timeout, or a signal: look at the flag
    if (fds[0].revents & POLLIN) controllers.handle();
    if (fds[1].revents & POLLIN) server.handle();
  }
  std::printf("to server: %lld forwarded, %lld dropped\n",
              static_cast<long long>(to_server.forwarded()),
              static_cast<long long>(to_server.dropped()));
  std::printf("to controllers: %lld forwarded, %lld dropped\n",
              static_cast<long long>(to_controllers.forwarded()),
              static_cast<long long>(to_controllers.dropped()));
  return 0;
}
