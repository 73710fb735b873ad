#pragma once
// The replay of one or two run files: read whole at start (a bad file is refused before anything
// is served), then their model and any frame on the page's request.
#include <string>
#include <vector>

#include "viewer/drawing_model.hpp"
#include "viewer/frame.hpp"

namespace tongue::viewer {

class RunReplay {
 public:
  // Throws run_file::RunFileError or std::invalid_argument naming the file and what is wrong.
  explicit RunReplay(const std::vector<std::string>& paths);

  int num_runs() const { return static_cast<int>(runs_.size()); }
  // JSON of /api/session.
  std::string session_json() const;
  const std::string& model_json(int run) const { return runs_.at(run).model_json; }
  std::int64_t num_frames(int run) const {
    return static_cast<std::int64_t>(runs_.at(run).time.size());
  }
  Frame frame(int run, std::int64_t index) const;

 private:
  struct Run {
    std::string path, status, analysis;
    std::string model_json;
    std::size_t nodes = 0, muscles = 0, obstacles = 0;
    std::vector<double> time, positions, activations, lengths, residual, wall_time, correction;
    std::vector<int> iterations, cuts;
    std::vector<double> node_forces, obstacle_forces, penetration;  // empty without obstacles
    // activations and lengths are empty without muscles, residual, wall_time and correction
    // when the file lacks them (older files); the others are required.
  };
  static Run load(const std::string& path);
  std::vector<Run> runs_;
};

}  // namespace tongue::viewer
