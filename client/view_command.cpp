// `strata view --server HOST:PORT`: the URL of a daemon's live viewer (`stratad serve --http
// HOST:PORT`, page /view), printed, and opened in the user's browser with xdg-open when there is
// one and a display to show it on. The address is checked first (a TCP connection), so that a typo
// is reported here rather than as a browser error page.
#include <netdb.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "commands.h"

extern char** environ;

namespace strata::client {
namespace {

struct ViewArgs {
  std::string server = "127.0.0.1:8080";
  bool tls = false;
  std::string scene, method, session;
  uint32_t width = 0, height = 0;
  bool no_browser = false;
};

// Percent-encoding of a query value (RFC 3986 unreserved characters stay).
std::string query_value(const std::string& s) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : s) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || c == '/') out += char(c);
    else out += std::string("%") + hex[c >> 4] + hex[c & 15];
  }
  return out;
}

std::string view_url(const ViewArgs& a) {
  std::string url = (a.tls ? "https://" : "http://") + a.server + "/view";
  std::string q;
  auto add = [&](const char* k, const std::string& value) {
    if (!value.empty()) q += (q.empty() ? "?" : "&") + std::string(k) + "=" + query_value(value);
  };
  add("scene", a.scene);
  add("method", a.method);
  add("session", a.session);
  if (a.width) add("width", std::to_string(a.width));
  if (a.height) add("height", std::to_string(a.height));
  return url + q;
}

// Throws std::runtime_error naming --server when nothing accepts a TCP connection there.
void check_reachable(const std::string& server) {
  const auto colon = server.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == server.size())
    throw std::runtime_error("--server = '" + server + "': expected host:port (the address of stratad serve --http)");
  std::string host = server.substr(0, colon);
  if (host.size() > 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  addrinfo hints{};
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  if (const int rc = getaddrinfo(host.c_str(), server.substr(colon + 1).c_str(), &hints, &found); rc != 0)
    throw std::runtime_error("--server = '" + server + "': " + gai_strerror(rc));
  std::unique_ptr<addrinfo, decltype(&freeaddrinfo)> list(found, freeaddrinfo);
  for (const addrinfo* ai = found; ai; ai = ai->ai_next) {
    const int fd = ::socket(ai->ai_family, ai->ai_socktype, ai->ai_protocol);
    if (fd < 0) continue;
    const bool ok = ::connect(fd, ai->ai_addr, ai->ai_addrlen) == 0;
    ::close(fd);
    if (ok) return;
  }
  throw std::runtime_error("--server = '" + server + "': nothing is listening there (start the daemon with stratad serve --http " +
                           server + ")");
}

// Whether `name` is an executable on $PATH.
bool on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::string dirs = path;
  for (size_t start = 0; start <= dirs.size();) {
    const size_t end = dirs.find(':', start);
    const std::string dir = dirs.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (!dir.empty() && ::access((dir + "/" + name).c_str(), X_OK) == 0) return true;
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return false;
}

int run_view(const ViewArgs& a) {
  check_reachable(a.server);
  const std::string url = view_url(a);
  std::cout << url << std::endl;
  const bool display = std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY");
  if (a.no_browser || !display || !on_path("xdg-open")) return 0;
  std::string program = "xdg-open";
  char* argv[] = {program.data(), const_cast<char*>(url.c_str()), nullptr};
  pid_t pid = 0;
  if (posix_spawnp(&pid, "xdg-open", nullptr, nullptr, argv, environ) != 0) {
    std::cerr << "strata view: could not start xdg-open; open the URL above in a browser\n";
    return 0;
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    std::cerr << "strata view: xdg-open failed; open the URL above in a browser\n";
  return 0;
}

}  // namespace

Runner add_view_command(CLI::App& app) {
  auto a = std::make_shared<ViewArgs>();
  auto* cmd = app.add_subcommand("view", "print the URL of a daemon's live viewer (stratad serve --http) and open it in a browser");
  cmd->add_option("--server", a->server, "host:port of the daemon's --http address")->capture_default_str();
  cmd->add_flag("--tls", a->tls, "the page is reached through a TLS proxy in front of --http: an https:// URL");
  cmd->add_option("--scene", a->scene, "scene the page starts (default: carousel)");
  cmd->add_option("--method", a->method, "method the page starts (default: the daemon's)");
  cmd->add_option("--width", a->width, "width of the session the page starts (default 256)");
  cmd->add_option("--height", a->height, "height of the session the page starts (default 256)");
  cmd->add_option("--session", a->session, "watch an existing session (sessions/{session}) instead of starting one");
  cmd->add_flag("--no-browser", a->no_browser, "only print the URL");
  return [a] { return run_view(*a); };
}

}  // namespace strata::client
