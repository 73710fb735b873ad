#pragma once
// What each HTTP address of the viewer answers (docs/viewer.md): the page's files, Debian's
// three.js, and the JSON of the session, the model and, in a replay, any frame.
#include <string>
#include <string_view>

#include "viewer/live_hub.hpp"
#include "viewer/run_replay.hpp"

namespace tongue::viewer {

struct HttpAnswer {
  unsigned status = 200;
  std::string content_type = "application/json";
  std::string body;
};

class Routes {
 public:
  // Exactly one of replay and hub is set; they outlive the routes.
  Routes(std::string web_dir, const RunReplay* replay, const LiveHub* hub);

  // The answer to a GET of target (path and query, as the request line has it).
  HttpAnswer answer(std::string_view target) const;

 private:
  HttpAnswer file(const std::string& path, const std::string& content_type) const;
  HttpAnswer model(std::string_view query) const;
  HttpAnswer frame(std::string_view query) const;

  std::string web_dir_;
  const RunReplay* replay_;
  const LiveHub* hub_;
};

}  // namespace tongue::viewer
