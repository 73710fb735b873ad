#include "common/rate_limited_reporter.hpp"

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <utility>

namespace tongue::common {
namespace {

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void write_to_stderr(const std::string& line) {
  std::fprintf(stderr, "%s\n", line.c_str());
}

}  // namespace

RateLimitedReporter::RateLimitedReporter(double interval_s, Sink sink, Clock clock)
    : interval_s_(interval_s),
      sink_(sink ? std::move(sink) : Sink(write_to_stderr)),
      clock_(clock ? std::move(clock) : Clock(steady_seconds)) {
  if (!(interval_s >= 0.0))
    throw std::invalid_argument("a report interval must be >= 0 s, not " +
                                std::to_string(interval_s));
}

bool RateLimitedReporter::report(const std::string& kind, const std::string& line) {
  const double now = clock_();
  const auto [it, first] = kinds_.try_emplace(kind);
  Kind& k = it->second;
  if (!first && now - k.last_shown < interval_s_) {
    ++k.not_shown;
    return false;
  }
  if (k.not_shown > 0) {
    sink_(line + " (and " + std::to_string(k.not_shown) + " more of this kind not shown)");
  } else {
    sink_(line);
  }
  k.last_shown = now;
  k.not_shown = 0;
  return true;
}

std::int64_t RateLimitedReporter::not_shown(const std::string& kind) const {
  const auto it = kinds_.find(kind);
  return it == kinds_.end() ? 0 : it->second.not_shown;
}

}  // namespace tongue::common
