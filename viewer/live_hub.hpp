#pragma once
// The pages watching a live run, on the web server's thread: the newest state and model from the
// LiveFeed, and for each page whether it asked for a frame and which it saw last. A page gets a
// frame only after asking ("next"), and then the newest one: a slow page skips states, it never
// holds anything up.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "viewer/live_feed.hpp"

namespace tongue::viewer {

// A page's connection, as the hub sees it.
class Page {
 public:
  virtual ~Page() = default;
  virtual void send(std::shared_ptr<const std::string> text) = 0;
};

class LiveHub {
 public:
  LiveHub(std::string url, std::string prefix);

  void update(const LiveUpdate& u);
  void join(const std::shared_ptr<Page>& page);
  void leave(const Page* page);
  // The page drew its last frame: send the newest it has not seen, now or when one comes.
  void want_frame(const Page* page);

  std::string session_json() const;
  // The model's JSON, or nullptr before the first.
  std::shared_ptr<const std::string> model_json() const { return model_; }
  // What the page shows while there is no model.
  std::string waiting_text() const;
  std::size_t num_pages() const { return pages_.size(); }

 private:
  struct Watcher {
    std::weak_ptr<Page> page;
    bool wants = false;
    std::int64_t last_sent = 0;
  };
  void offer(Watcher& w);
  void broadcast(const std::string& text);

  std::string url_, prefix_;
  std::shared_ptr<const std::string> model_;
  int model_version_ = 0;
  std::string status_;
  std::shared_ptr<const Frame> frame_;
  std::int64_t frame_number_ = 0;
  std::map<const Page*, Watcher> pages_;
};

}  // namespace tongue::viewer
