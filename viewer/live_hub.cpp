#include "viewer/live_hub.hpp"

#include <nlohmann/json.hpp>

#include "bus/channels.hpp"

namespace tongue::viewer {
namespace {

std::string dumped(const nlohmann::json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace

LiveHub::LiveHub(std::string url, std::string prefix)
    : url_(std::move(url)), prefix_(std::move(prefix)) {}

void LiveHub::update(const LiveUpdate& u) {
  if (u.model_json) {
    model_ = u.model_json;
    model_version_ = u.model_version;
    broadcast(dumped({{"type", "model"}, {"version", model_version_}}));
  }
  if (u.status) {
    status_ = *u.status;
    broadcast(dumped({{"type", "status"}, {"text", status_}}));
  }
  if (u.frame) {
    frame_ = u.frame;
    frame_number_ = u.frame_number;
    for (auto& [key, watcher] : pages_) offer(watcher);
  }
}

void LiveHub::join(const std::shared_ptr<Page>& page) {
  pages_[page.get()] = Watcher{page, false, 0};
  page->send(std::make_shared<const std::string>(dumped(
      {{"type", "hello"},
       {"mode", "live"},
       {"model_version", model_ ? nlohmann::json(model_version_) : nlohmann::json(nullptr)}})));
  if (!status_.empty())
    page->send(
        std::make_shared<const std::string>(dumped({{"type", "status"}, {"text", status_}})));
}

void LiveHub::leave(const Page* page) {
  pages_.erase(page);
}

void LiveHub::want_frame(const Page* page) {
  const auto it = pages_.find(page);
  if (it == pages_.end()) return;
  it->second.wants = true;
  offer(it->second);
}

void LiveHub::offer(Watcher& w) {
  if (!w.wants || !frame_ || frame_number_ <= w.last_sent) return;
  const std::shared_ptr<Page> page = w.page.lock();
  if (!page) return;
  const std::int64_t dropped = w.last_sent == 0 ? 0 : frame_number_ - w.last_sent - 1;
  w.wants = false;
  w.last_sent = frame_number_;
  page->send(std::make_shared<const std::string>(frame_json(*frame_, dropped)));
}

void LiveHub::broadcast(const std::string& text) {
  const auto shared = std::make_shared<const std::string>(text);
  for (auto& [key, watcher] : pages_)
    if (const auto page = watcher.page.lock()) page->send(shared);
}

std::string LiveHub::session_json() const {
  return dumped(
      {{"mode", "live"}, {"runs", nlohmann::json::array()}, {"bus", url_}, {"prefix", prefix_}});
}

std::string LiveHub::waiting_text() const {
  return "no model yet: waiting for " + bus::Channels(prefix_).model + " on " + url_;
}

}  // namespace tongue::viewer
