// The live hub's flow control: a page gets a frame only after asking, and then the newest one.
#include "viewer/live_hub.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace tongue::viewer {
namespace {

class RecordingPage : public Page {
 public:
  void send(std::shared_ptr<const std::string> text) override {
    messages.push_back(nlohmann::json::parse(*text));
  }
  std::vector<nlohmann::json> frames() const {
    std::vector<nlohmann::json> out;
    for (const auto& m : messages)
      if (m["type"] == "frame") out.push_back(m);
    return out;
  }
  std::vector<nlohmann::json> messages;
};

LiveUpdate state_update(std::int64_t number, std::int64_t step) {
  auto frame = std::make_shared<Frame>();
  frame->step = step;
  frame->time = 0.004 * static_cast<double>(step);
  LiveUpdate u;
  u.frame = frame;
  u.frame_number = number;
  return u;
}

TEST(LiveHub, GreetsAPageWithTheModelVersionAndStatus) {
  LiveHub hub("udpm://239.255.76.67:7667?ttl=0", "TONGUE_");
  LiveUpdate model;
  model.model_json = std::make_shared<const std::string>("{}");
  model.model_version = 3;
  model.status = "model 3 received";
  hub.update(model);
  auto page = std::make_shared<RecordingPage>();
  hub.join(page);
  ASSERT_EQ(page->messages.size(), 2u);
  EXPECT_EQ(page->messages[0]["type"], "hello");
  EXPECT_EQ(page->messages[0]["model_version"], 3);
  EXPECT_EQ(page->messages[1]["text"], "model 3 received");
}

TEST(LiveHub, SendsOnlyWhenAskedAndThenTheNewestState) {
  LiveHub hub("udpm://239.255.76.67:7667?ttl=0", "TONGUE_");
  auto page = std::make_shared<RecordingPage>();
  hub.join(page);
  hub.update(state_update(1, 1));
  EXPECT_TRUE(page->frames().empty());  // not asked yet
  hub.want_frame(page.get());
  ASSERT_EQ(page->frames().size(), 1u);
  EXPECT_EQ(page->frames()[0]["step"], 1);
  // States keep coming while the page draws: none is sent until it asks again.
  for (int n = 2; n <= 5; ++n) hub.update(state_update(n, n));
  EXPECT_EQ(page->frames().size(), 1u);
  hub.want_frame(page.get());
  ASSERT_EQ(page->frames().size(), 2u);
  EXPECT_EQ(page->frames()[1]["step"], 5);
  EXPECT_EQ(page->frames()[1]["dropped"], 3);  // states 2, 3 and 4 were skipped
  // Asking with nothing new waits for the next state.
  hub.want_frame(page.get());
  EXPECT_EQ(page->frames().size(), 2u);
  hub.update(state_update(6, 6));
  ASSERT_EQ(page->frames().size(), 3u);
  EXPECT_EQ(page->frames()[2]["dropped"], 0);
}

TEST(LiveHub, APageThatLeftGetsNothing) {
  LiveHub hub("udpm://239.255.76.67:7667?ttl=0", "TONGUE_");
  auto page = std::make_shared<RecordingPage>();
  hub.join(page);
  hub.want_frame(page.get());
  hub.leave(page.get());
  hub.update(state_update(1, 1));
  EXPECT_TRUE(page->frames().empty());
  EXPECT_EQ(hub.num_pages(), 0u);
}

TEST(RealTimeFactor, SimulatedOverWallTimeRestartingAfterAReset) {
  // Wall clock readings near 10 s keep about 1e-15 s of their differences: 1e-9 is far above.
  constexpr double kTol = 1e-9;
  RealTimeFactor pace;
  EXPECT_FALSE(pace.add(0.0, 10.0).has_value());  // one state says nothing of pace
  EXPECT_NEAR(*pace.add(0.1, 10.05), 2.0, kTol);
  EXPECT_NEAR(*pace.add(0.2, 10.1), 2.0, kTol);
  // A reset sends the simulated time back: the factor starts over.
  EXPECT_FALSE(pace.add(0.0, 10.2).has_value());
  EXPECT_NEAR(*pace.add(0.05, 10.3), 0.5, kTol);
}

}  // namespace
}  // namespace tongue::viewer
