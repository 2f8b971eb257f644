#pragma once
// A minimal HTTP/1.0 client for loopback tests (no library in the way of what the server sends):
// GET a path, and read a server-sent-events stream for a bounded time.
#include <chrono>
#include <string>

namespace strata::test {

struct HttpResponse {
  int status = 0;        // 0: no connection or no status line
  std::string headers;   // the header block, status line included
  std::string body;
};

// GET http://host:port/path; everything read until the server closes or `timeout` passes.
// `headers`: more request header lines, each ending in \r\n.
HttpResponse http_get(const std::string& host_port, const std::string& path, std::chrono::milliseconds timeout = std::chrono::seconds(10),
                      const std::string& headers = "");

// The "host:port" in the first line of `output` that contains `marker` followed by "http://host:port".
std::string address_after(const std::string& output, const std::string& marker);

}  // namespace strata::test
