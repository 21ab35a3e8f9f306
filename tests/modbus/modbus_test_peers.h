#pragma once
// Peers for the Modbus client tests: a raw TCP server that answers each request
// the way a test tells it to (garbage, short frames, closing mid-frame, ...), and
// a free loopback port.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <thread>
#include <vector>

namespace mdhd::modbus_test {

using Bytes = std::vector<std::uint8_t>;

// A port nothing listens on (bound once, then released).
inline int freePort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
  socklen_t len = sizeof addr;
  getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  close(fd);
  return ntohs(addr.sin_port);
}

// The well-formed answer to a read-registers request with these register values.
inline Bytes readReply(const Bytes& request, const std::vector<std::uint16_t>& values) {
  const auto n = static_cast<std::uint8_t>(2 * values.size());
  Bytes r = {request[0], request[1], 0, 0, 0, static_cast<std::uint8_t>(3 + n),
             request[6], request[7], n};
  for (std::uint16_t v : values) {
    r.push_back(static_cast<std::uint8_t>(v >> 8));
    r.push_back(static_cast<std::uint8_t>(v & 0xFF));
  }
  return r;
}

// Answers requests on loopback. `behave(connection, request, fd)` is called for
// every request received (connection counts from 0); it writes what it likes to
// fd and returns false to close the connection.
class RawPeer {
 public:
  using Behaviour = std::function<bool(int connection, const Bytes& request, int fd)>;

  explicit RawPeer(Behaviour behave) : behave_(std::move(behave)) {
    listen_ = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (bind(listen_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
        listen(listen_, 4) != 0) {
      throw std::runtime_error("RawPeer: cannot listen");
    }
    socklen_t len = sizeof addr;
    getsockname(listen_, reinterpret_cast<sockaddr*>(&addr), &len);
    port_ = ntohs(addr.sin_port);
    thread_ = std::thread([this] { run(); });
  }
  ~RawPeer() {
    stop_ = true;
    thread_.join();
    close(listen_);
  }
  int port() const { return port_; }
  int connections() const { return connections_.load(); }

 private:
  void run() {
    int fd = -1;
    int connection = -1;
    while (!stop_) {
      pollfd p{fd >= 0 ? fd : listen_, POLLIN, 0};
      if (poll(&p, 1, 20) <= 0) continue;
      if (fd < 0) {
        fd = accept(listen_, nullptr, nullptr);
        connection = connections_++;
        continue;
      }
      std::uint8_t buf[300];
      const ssize_t n = recv(fd, buf, sizeof buf, 0);
      if (n <= 0 || !behave_(connection, Bytes(buf, buf + n), fd)) {
        close(fd);
        fd = -1;
      }
    }
    if (fd >= 0) close(fd);
  }

  Behaviour behave_;
  int listen_ = -1;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  std::atomic<int> connections_{0};
  std::thread thread_;
};

inline void sendAll(int fd, const Bytes& bytes) {
  (void)!send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
}

}  // namespace mdhd::modbus_test
