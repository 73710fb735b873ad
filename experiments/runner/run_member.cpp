#include "run_member.hpp"

#include <signal.h>

namespace tongue::runner {

void start(Member& m, const std::filesystem::path& workdir, const std::filesystem::path& folder) {
  m.process = std::make_unique<ChildProcess>(m.argv, workdir, folder / (m.name + ".out"),
                                             folder / (m.name + ".err"));
}

void stop(Member& m, double grace_s, int sig, const char* sig_name) {
  if (!m.process) return;
  if (!m.status) m.status = m.process->wait(grace_s);
  if (!m.status) {
    m.stopped_by = sig_name;
    m.process->signal(sig);
    m.status = m.process->wait(10.0);
  }
  if (!m.status) {
    m.stopped_by = "SIGKILL";
    m.process->signal(SIGKILL);
    m.status = m.process->wait(5.0);
  }
}

std::string quote(const std::vector<std::string>& argv) {
  std::string s;
  for (const std::string& a : argv) {
    if (!s.empty()) s += ' ';
    const bool plain = a.find_first_of(" '\"&?;*") == std::string::npos && !a.empty();
    s += plain ? a : "'" + a + "'";
  }
  return s;
}

}  // namespace tongue::runner
