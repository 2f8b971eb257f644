#include "process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "grpc/health/v1/health.grpc.pb.h"

extern char** environ;

namespace strata::test {

std::string stratad_path() { return STRATAD_PATH; }
std::string strata_path() { return STRATA_PATH; }

Process::Process(const std::vector<std::string>& argv) {
  const std::string log = (dir_.path / "output.log").string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const int rc = posix_spawn(&pid_, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + argv.at(0) + ": " + std::strerror(rc));
}

Process::~Process() {
  if (pid_ > 0 && !status_) {
    ::kill(pid_, SIGKILL);
    wait_exit(10s);
  }
}

void Process::signal(int sig) const {
  if (pid_ > 0 && !status_) ::kill(pid_, sig);
}

std::optional<int> Process::wait_exit(std::chrono::milliseconds timeout) {
  if (status_) return status_;
  const auto until = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    int status = 0;
    const pid_t r = waitpid(pid_, &status, WNOHANG);
    if (r == pid_) {
      status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      return status_;
    }
    if (std::chrono::steady_clock::now() >= until) return std::nullopt;
    std::this_thread::sleep_for(10ms);
  }
}

std::string Process::output() const {
  std::ifstream in(dir_.path / "output.log");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

uint64_t Process::rss_bytes() const {
  std::ifstream in("/proc/" + std::to_string(pid_) + "/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stoull(line.substr(6)) * 1024;  // "VmRSS:  1234 kB"
  return 0;
}

ProcessResult run_process(const std::vector<std::string>& argv, std::chrono::milliseconds timeout) {
  Process p(argv);
  ProcessResult r;
  if (auto code = p.wait_exit(timeout)) r.exit_code = *code;
  else p.signal(SIGKILL);
  p.wait_exit(10s);
  r.output = p.output();
  return r;
}

Daemon::Daemon(const std::vector<std::string>& args) {
  const std::string port_file = (dir_.path / "port").string();
  std::vector<std::string> argv = {stratad_path(), "serve", "--listen", "127.0.0.1:0", "--port-file", port_file};
  // A test that asks for a method gets that method's frames from the first one on, unless it asks
  // for the progressive start (service/session.h).
  if (std::find(args.begin(), args.end(), "--progressive-start") == args.end()) argv.push_back("--no-progressive-start");
  argv.insert(argv.end(), args.begin(), args.end());
  process_ = std::make_unique<Process>(argv);
  const bool ready = wait_until([&] {
    std::ifstream in(port_file);
    int port = 0;
    if (!(in >> port) || port <= 0) return false;
    address_ = "127.0.0.1:" + std::to_string(port);
    return true;
  }, 60s);
  if (!ready) throw std::runtime_error("stratad serve did not start:\n" + process_->output());
  auto health = grpc::health::v1::Health::NewStub(loopback_channel(address_));
  const bool serving = wait_until([&] {
    grpc::ClientContext ctx;
    ctx.set_deadline(std::chrono::system_clock::now() + 2s);
    grpc::health::v1::HealthCheckResponse resp;
    return health->Check(&ctx, {}, &resp).ok() && resp.status() == grpc::health::v1::HealthCheckResponse::SERVING;
  }, 30s);
  if (!serving) throw std::runtime_error("stratad serve is not SERVING:\n" + process_->output());
}

}  // namespace strata::test
