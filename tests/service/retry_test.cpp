// The client's retry policy for read-only calls (client/connection.cpp, channel_arguments): a
// connection closed under GetServerStatus, as a proxy under load once did in the scale test
// (UNAVAILABLE "Socket closed"), is retried on a new connection and the stream goes on.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <thread>

#include "process.h"

namespace strata::test {
namespace {

int listen_loopback(uint16_t& port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof a;
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&a), len) != 0 || ::listen(fd, 16) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0)
    throw std::runtime_error("relay: cannot listen on 127.0.0.1");
  port = ntohs(a.sin_port);
  return fd;
}

int connect_loopback(uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(port);
  if (fd < 0 || ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) throw std::runtime_error("relay: cannot connect");
  return fd;
}

// A TCP relay on 127.0.0.1 in front of a daemon. Its first connection is relayed until the client
// sends its first request (an HTTP/2 HEADERS frame on a stream), which is dropped, and both sides
// are closed: the request left the client and the socket closed under it. Later connections are
// relayed whole. Bounded: every poll wakes every 100 ms to see whether the relay is stopping.
class DroppingRelay {
 public:
  explicit DroppingRelay(const std::string& target) : target_port_(uint16_t(std::stoi(target.substr(target.rfind(':') + 1)))) {
    listen_fd_ = listen_loopback(port_);
    accept_thread_ = std::thread([this] { accept_loop(); });
  }
  ~DroppingRelay() {
    stop_ = true;
    accept_thread_.join();
    for (auto& t : relays_) t.join();
    ::close(listen_fd_);
  }
  std::string address() const { return "127.0.0.1:" + std::to_string(port_); }
  int dropped_requests() const { return dropped_; }
  int connections() const { return connections_; }

 private:
  void accept_loop() {
    while (!stop_) {
      pollfd p{listen_fd_, POLLIN, 0};
      if (::poll(&p, 1, 100) <= 0) continue;
      const int client = ::accept(listen_fd_, nullptr, nullptr);
      if (client < 0) continue;
      const bool drop = connections_++ == 0;
      relays_.emplace_back([this, client, drop] { relay(client, drop); });
    }
  }

  // True once `bytes` (what the client sent so far) hold a HEADERS frame (type 1) on a stream
  // other than 0, after the 24-byte connection preface (RFC 9113 3.4, 4.1).
  static bool holds_request(const std::string& bytes) {
    for (size_t at = 24; at + 9 <= bytes.size();) {
      const size_t length = (size_t(uint8_t(bytes[at])) << 16) | (size_t(uint8_t(bytes[at + 1])) << 8) | uint8_t(bytes[at + 2]);
      const uint32_t stream = ((uint32_t(uint8_t(bytes[at + 5])) & 0x7f) << 24) | (uint32_t(uint8_t(bytes[at + 6])) << 16) |
                              (uint32_t(uint8_t(bytes[at + 7])) << 8) | uint8_t(bytes[at + 8]);
      if (uint8_t(bytes[at + 3]) == 1 && stream != 0) return true;
      at += 9 + length;
    }
    return false;
  }

  void relay(int client, bool drop) {
    const int server = connect_loopback(target_port_);
    std::string sent;  // what the client sent (only while a request is to be dropped)
    std::array<char, 16384> buffer;
    while (!stop_) {
      std::array<pollfd, 2> p{pollfd{client, POLLIN, 0}, pollfd{server, POLLIN, 0}};
      if (::poll(p.data(), 2, 100) <= 0) continue;
      bool closed = false;
      for (int i = 0; i < 2 && !closed; ++i) {
        if (!(p[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
        const ssize_t n = ::read(p[i].fd, buffer.data(), buffer.size());
        if (n <= 0) { closed = true; break; }
        if (i == 0 && drop) {
          // The frames before the request pass; the read that completes the request closes both.
          sent.append(buffer.data(), size_t(n));
          if (holds_request(sent)) { ++dropped_; closed = true; break; }
        }
        const int to = i == 0 ? server : client;
        for (ssize_t off = 0; off < n;) {
          const ssize_t w = ::write(to, buffer.data() + off, size_t(n - off));
          if (w <= 0) { closed = true; break; }
          off += w;
        }
      }
      if (closed) break;
    }
    ::close(client);
    ::close(server);
  }

  uint16_t target_port_;
  uint16_t port_ = 0;
  int listen_fd_ = -1;
  std::atomic<bool> stop_{false};
  std::atomic<int> dropped_{0};
  std::atomic<int> connections_{0};
  std::thread accept_thread_;
  std::vector<std::thread> relays_;  // only the accept thread adds, and only it runs until stop_
};

TEST(RetryTest, ReadOnlyCallIsRetriedOnANewConnectionWhenItsSocketCloses) {
  TempDir dir;
  Daemon daemon;
  DroppingRelay relay(daemon.address());
  const auto stream = run_process({strata_path(), "stream", "--server", relay.address(), "--scene", "cornell", "--method", "pt",
                                   "--width", "16", "--height", "16", "--frames", "2", "--encodings", "raw", "--out",
                                   (dir.path / "out").string(), "--timeout", "60"},
                                  120s);
  EXPECT_EQ(relay.dropped_requests(), 1) << "the relay did not see the first request";
  EXPECT_GE(relay.connections(), 2) << "the client did not open a second connection";
  ASSERT_EQ(stream.exit_code, 0) << "GetServerStatus was not retried after its socket closed:\n" << stream.output;
  EXPECT_TRUE(std::filesystem::exists(dir.path / "out" / "frame_0001.exr"));
}

}  // namespace
}  // namespace strata::test
