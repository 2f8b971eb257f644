#include "http_get.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <sstream>

namespace strata::test {

HttpResponse http_get(const std::string& host_port, const std::string& path, std::chrono::milliseconds timeout,
                      const std::string& headers) {
  HttpResponse r;
  const auto colon = host_port.rfind(':');
  if (colon == std::string::npos) return r;
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(uint16_t(std::stoi(host_port.substr(colon + 1))));
  if (inet_pton(AF_INET, host_port.substr(0, colon).c_str(), &addr.sin_addr) != 1) return r;
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return r;
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    ::close(fd);
    return r;
  }
  const std::string request = "GET " + path + " HTTP/1.0\r\nHost: " + host_port + "\r\n" + headers + "\r\n";
  if (::send(fd, request.data(), request.size(), MSG_NOSIGNAL) != ssize_t(request.size())) {
    ::close(fd);
    return r;
  }
  std::string all;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  char buf[65536];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) break;
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, int(left)) <= 0) break;
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    all.append(buf, size_t(n));
  }
  ::close(fd);
  const auto end = all.find("\r\n\r\n");
  r.headers = all.substr(0, end);
  r.body = end == std::string::npos ? "" : all.substr(end + 4);
  std::istringstream status(r.headers);
  std::string version;
  status >> version >> r.status;
  return r;
}

std::string address_after(const std::string& output, const std::string& marker) {
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) {
    const auto m = line.find(marker);
    if (m == std::string::npos) continue;
    const auto h = line.find("http://", m);
    if (h == std::string::npos) continue;
    const auto start = h + 7;
    const auto stop = line.find('/', start);
    return line.substr(start, stop == std::string::npos ? std::string::npos : stop - start);
  }
  return "";
}

}  // namespace strata::test
