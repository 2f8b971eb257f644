#include "cdp_pipe.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <stdexcept>

namespace strata::test {

std::string base64_decode(const std::string& text) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::string out;
  uint32_t acc = 0;
  int bits = 0;
  for (char c : text) {
    const int v = value(c);
    if (v < 0) continue;  // padding and line breaks
    acc = (acc << 6) | uint32_t(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += char((acc >> bits) & 0xff);
    }
  }
  return out;
}

Chromium::Chromium(const std::string& chromium, const std::filesystem::path& dir, int width, int height,
                   const std::vector<std::string>& extra_args)
    : dir_(dir) {
  ::signal(SIGPIPE, SIG_IGN);  // a browser that died must fail the test, not kill it
  int in[2], out[2];
  if (::pipe(in) != 0 || ::pipe(out) != 0) throw std::runtime_error("pipe failed");
  const std::string log = (dir / "chromium.log").string();
  std::vector<std::string> args = {chromium, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                                   "--no-default-browser-check", "--disable-extensions", "--disable-background-networking",
                                   "--disable-sync", "--mute-audio", "--disable-dev-shm-usage", "--hide-scrollbars",
                                   "--force-device-scale-factor=1", "--remote-debugging-pipe",
                                   "--user-data-dir=" + (dir / "profile").string(),
                                   "--window-size=" + std::to_string(width) + "," + std::to_string(height),
                                   // Nothing resolves but loopback: a page that needed the network would break.
                                   "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1"};
  args.insert(args.end(), extra_args.begin(), extra_args.end());
  args.push_back("about:blank");
  pid_ = ::fork();
  if (pid_ == 0) {
    // Out of the way of 3 and 4 first, then into place.
    const int r = ::fcntl(in[0], F_DUPFD, 10), w = ::fcntl(out[1], F_DUPFD, 10);
    ::dup2(r, 3);
    ::dup2(w, 4);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    for (int f = 5; f < 1024; ++f) ::close(f);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(in[0]);
  ::close(out[1]);
  to_browser_ = in[1];
  from_browser_ = out[0];
  if (pid_ < 0) throw std::runtime_error("fork failed");
}

Chromium::~Chromium() {
  if (pid_ > 0) {
    try {
      call("Browser.close", nlohmann::json::object(), false, std::chrono::seconds(5));
    } catch (...) {
    }
    for (int i = 0; i < 50; ++i) {
      if (::waitpid(pid_, nullptr, WNOHANG) == pid_) {
        pid_ = -1;
        break;
      }
      ::usleep(100'000);
    }
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  if (to_browser_ >= 0) ::close(to_browser_);
  if (from_browser_ >= 0) ::close(from_browser_);
}

std::string Chromium::log() const {
  std::ifstream in(dir_ / "chromium.log");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void Chromium::note_event(const nlohmann::json& m) {
  const std::string method = m.value("method", "");
  const auto& p = m.contains("params") ? m["params"] : nlohmann::json::object();
  if (method == "Runtime.consoleAPICalled") {
    std::string text = "console." + p.value("type", "") + ":";
    for (const auto& a : p["args"]) text += " " + (a.contains("value") ? a["value"].dump() : a.value("description", ""));
    messages_.push_back(text);
  } else if (method == "Runtime.exceptionThrown") {
    const auto& d = p["exceptionDetails"];
    messages_.push_back("exception: " + d.value("text", "") + " " +
                        (d.contains("exception") ? d["exception"].value("description", "") : ""));
  } else if (method == "Log.entryAdded") {
    const auto& e = p["entry"];
    if (e.value("level", "") == "error" || e.value("level", "") == "warning")
      messages_.push_back("log." + e.value("level", "") + ": " + e.value("text", "") + " " + e.value("url", ""));
  }
}

nlohmann::json Chromium::call(const std::string& method, const nlohmann::json& params, bool in_page, std::chrono::milliseconds timeout) {
  const int id = next_id_++;
  nlohmann::json msg = {{"id", id}, {"method", method}, {"params", params}};
  if (in_page) msg["sessionId"] = session_;
  const std::string text = msg.dump() + std::string(1, '\0');
  for (size_t off = 0; off < text.size();) {
    const ssize_t n = ::write(to_browser_, text.data() + off, text.size() - off);
    if (n <= 0) throw std::runtime_error("chromium closed its pipe (" + method + ")");
    off += size_t(n);
  }
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    for (size_t end; (end = buffer_.find('\0')) != std::string::npos;) {
      const auto reply = nlohmann::json::parse(buffer_.substr(0, end), nullptr, false);
      buffer_.erase(0, end + 1);
      if (reply.is_discarded()) continue;
      if (!reply.contains("id")) {
        note_event(reply);
        continue;
      }
      if (reply["id"] != id) continue;
      if (reply.contains("error")) throw std::runtime_error(method + ": " + reply["error"].dump());
      return reply.value("result", nlohmann::json::object());
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) throw std::runtime_error(method + ": no reply from chromium within the timeout");
    pollfd p{from_browser_, POLLIN, 0};
    if (::poll(&p, 1, int(left)) <= 0) continue;
    char buf[65536];
    const ssize_t n = ::read(from_browser_, buf, sizeof buf);
    if (n <= 0) throw std::runtime_error("chromium closed its pipe (" + method + ")");
    buffer_.append(buf, size_t(n));
  }
}

void Chromium::open(const std::string& url) {
  const auto target = call("Target.createTarget", {{"url", "about:blank"}}, false);
  target_ = target["targetId"].get<std::string>();
  const auto attached = call("Target.attachToTarget", {{"targetId", target_}, {"flatten", true}}, false);
  session_ = attached["sessionId"];
  call("Runtime.enable", nlohmann::json::object(), true);
  call("Log.enable", nlohmann::json::object(), true);
  call("Page.enable", nlohmann::json::object(), true);
  call("Page.navigate", {{"url", url}}, true);
}

nlohmann::json Chromium::evaluate(const std::string& expression) {
  const auto r = call("Runtime.evaluate", {{"expression", expression}, {"returnByValue", true}}, true);
  if (r.contains("exceptionDetails")) throw std::runtime_error("evaluate: " + r["exceptionDetails"].dump());
  return r["result"].value("value", nlohmann::json());
}

void Chromium::close_page() {
  call("Target.closeTarget", {{"targetId", target_}}, false);
  session_.clear();
  target_.clear();
}

std::string Chromium::screenshot_png() {
  const auto r = call("Page.captureScreenshot", {{"format", "png"}}, true);
  return base64_decode(r.value("data", ""));
}

}  // namespace strata::test
