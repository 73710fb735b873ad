#include "viewer/routes.hpp"

#include <cctype>
#include <charconv>
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "common/bounded_file.hpp"

namespace tongue::viewer {
namespace {

// Debian's three.js (package libjs-three, r111), served from where the package puts it.
constexpr const char* kThreeDir = "/usr/share/javascript/three/";
constexpr std::size_t kMaxServedFile = 8u << 20;  // bytes; three.min.js is about 600 kB

HttpAnswer error(unsigned status, const std::string& why) {
  return {status, "application/json",
          nlohmann::json{{"error", why}}.dump(-1, ' ', false,
                                              nlohmann::json::error_handler_t::replace)};
}

std::string content_type(const std::string& name) {
  const std::string ext = std::filesystem::path(name).extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".png") return "image/png";
  if (ext == ".svg") return "image/svg+xml";
  return "application/octet-stream";
}

// A file name of the page's flat folder: letters, digits, '_', '-', '.', not starting with '.'
// (so no path, no hidden file).
bool plain_name(std::string_view name) {
  if (name.empty() || name.front() == '.' || name.size() > 100) return false;
  for (char c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.')
      return false;
  return true;
}

// The value of key in a query "a=1&b=2" as a non-negative integer, or nullopt.
std::optional<std::int64_t> query_number(std::string_view query, std::string_view key) {
  while (!query.empty()) {
    const std::size_t amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    const std::size_t eq = pair.find('=');
    if (eq != std::string_view::npos && pair.substr(0, eq) == key) {
      const std::string_view value = pair.substr(eq + 1);
      std::int64_t n = 0;
      const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
      if (ec != std::errc() || end != value.data() + value.size() || n < 0) return std::nullopt;
      return n;
    }
    if (amp == std::string_view::npos) break;
    query.remove_prefix(amp + 1);
  }
  return std::nullopt;
}

}  // namespace

Routes::Routes(std::string web_dir, const RunReplay* replay, const LiveHub* hub)
    : web_dir_(std::move(web_dir)), replay_(replay), hub_(hub) {}

HttpAnswer Routes::answer(std::string_view target) const {
  const std::size_t mark = target.find('?');
  const std::string_view path = target.substr(0, mark);
  const std::string_view query = mark == std::string_view::npos ? "" : target.substr(mark + 1);
  if (path == "/api/session")
    return {200, "application/json", replay_ ? replay_->session_json() : hub_->session_json()};
  if (path == "/api/model") return model(query);
  if (path == "/api/frame") return frame(query);
  if (path == "/three/three.min.js")
    return file(std::string(kThreeDir) + "build/three.min.js", content_type("three.min.js"));
  if (path == "/three/OrbitControls.js")
    return file(std::string(kThreeDir) + "examples/js/controls/OrbitControls.js",
                content_type("OrbitControls.js"));
  const std::string_view name = path == "/" ? "index.html" : path.substr(1);
  if (!plain_name(name)) return error(404, "no such page");
  return file(web_dir_ + "/" + std::string(name), content_type(std::string(name)));
}

HttpAnswer Routes::file(const std::string& path, const std::string& type) const {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return error(404, "no such page");
  try {
    return {200, type, common::read_bounded_file(path, kMaxServedFile)};
  } catch (const std::exception& e) {
    return error(500, e.what());
  }
}

HttpAnswer Routes::model(std::string_view query) const {
  if (!replay_) {
    const auto json = hub_->model_json();
    return json ? HttpAnswer{200, "application/json", *json} : error(404, hub_->waiting_text());
  }
  const std::int64_t run = query_number(query, "run").value_or(0);
  if (run >= replay_->num_runs())
    return error(404, "no run " + std::to_string(run) + ": " + std::to_string(replay_->num_runs()) +
                          " run file(s) open");
  return {200, "application/json", replay_->model_json(static_cast<int>(run))};
}

HttpAnswer Routes::frame(std::string_view query) const {
  if (!replay_) return error(404, "frames are replayed from run files; live frames come on /ws");
  const auto run = query_number(query, "run");
  const auto index = query_number(query, "index");
  if (!run || !index) return error(400, "/api/frame wants run=R&index=I, both numbers");
  if (*run >= replay_->num_runs()) return error(404, "no run " + std::to_string(*run));
  const int r = static_cast<int>(*run);
  if (*index >= replay_->num_frames(r))
    return error(404, "run " + std::to_string(r) + " has " +
                          std::to_string(replay_->num_frames(r)) + " frames, no frame " +
                          std::to_string(*index));
  return {200, "application/json", frame_json(replay_->frame(r, *index))};
}

}  // namespace tongue::viewer
