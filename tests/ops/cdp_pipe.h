#pragma once
// Headless Chromium driven over the DevTools protocol on a pipe (--remote-debugging-pipe: the
// browser reads NUL-terminated JSON commands on fd 3 and writes replies and events on fd 4). A
// page that never finishes loading (the dashboard holds an event stream open) cannot be checked
// with --dump-dom or --screenshot, which wait for the load to end; this waits for what the page
// itself reports instead. Every wait is bounded; the browser is killed when the object goes.
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace strata::test {

class Chromium {
 public:
  // Starts `chromium` headless with a fresh profile in `dir`; its log goes to dir/chromium.log.
  // `extra_args` go on its command line (e.g. --ignore-certificate-errors for a test's own certificate).
  Chromium(const std::string& chromium, const std::filesystem::path& dir, int width, int height,
           const std::vector<std::string>& extra_args = {});
  ~Chromium();
  Chromium(const Chromium&) = delete;
  Chromium& operator=(const Chromium&) = delete;

  // A new page on `url`, with console messages, exceptions and log entries recorded.
  void open(const std::string& url);
  // The value of a JavaScript expression in the page (returnByValue).
  nlohmann::json evaluate(const std::string& expression);
  // A PNG of the viewport.
  std::string screenshot_png();
  // Any DevTools method on the page (Input.dispatchKeyEvent, Input.dispatchMouseEvent, ...).
  nlohmann::json page_call(const std::string& method, const nlohmann::json& params) { return call(method, params, true); }
  // Closes the page's tab, as a user closing it does (its sockets close).
  void close_page();
  // Console messages, uncaught exceptions and error log entries of the page, as text.
  const std::vector<std::string>& page_messages() const { return messages_; }
  std::string log() const;

 private:
  nlohmann::json call(const std::string& method, const nlohmann::json& params, bool in_page,
                      std::chrono::milliseconds timeout = std::chrono::seconds(30));
  void note_event(const nlohmann::json& message);

  std::filesystem::path dir_;
  pid_t pid_ = -1;
  int to_browser_ = -1, from_browser_ = -1;
  std::string buffer_;
  std::string session_;
  std::string target_;
  int next_id_ = 1;
  std::vector<std::string> messages_;
};

std::string base64_decode(const std::string& text);

}  // namespace strata::test
