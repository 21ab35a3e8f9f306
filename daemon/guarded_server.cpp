#include "daemon/guarded_server.h"

#include <httplib.h>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace mdhd::service {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

thread_local Connection* tlsConnection = nullptr;

// Waits for `events` on `sock` up to `timeout`; false on timeout or error.
bool waitSocket(int sock, short events, milliseconds timeout) {
  const Clock::time_point until = Clock::now() + timeout;
  for (;;) {
    const auto left = std::chrono::duration_cast<milliseconds>(until - Clock::now()).count();
    pollfd p{sock, events, 0};
    const int r = poll(&p, 1, static_cast<int>(std::max<long long>(0, left)));
    if (r > 0) return true;
    if (r == 0 || errno != EINTR) return false;
  }
}

void socketAddress(int sock, bool peer, std::string& ip, int& port) {
  sockaddr_storage addr{};
  socklen_t len = sizeof addr;
  const int r = peer ? getpeername(sock, reinterpret_cast<sockaddr*>(&addr), &len)
                     : getsockname(sock, reinterpret_cast<sockaddr*>(&addr), &len);
  if (r != 0) return;
  char host[NI_MAXHOST];
  char serv[NI_MAXSERV];
  if (getnameinfo(reinterpret_cast<sockaddr*>(&addr), len, host, sizeof host, serv, sizeof serv,
                  NI_NUMERICHOST | NI_NUMERICSERV) == 0) {
    ip = host;
    port = std::atoi(serv);
  }
}

// The connection's byte stream for cpp-httplib, in place of its SocketStream: the
// head of a request must arrive by a deadline and within a size (the library
// resets its read timeout per read and buffers a line of any length), and a
// chunked body within a budget.
class GuardedStream final : public httplib::Stream {
 public:
  GuardedStream(int sock, Connection& conn, milliseconds readTimeout, milliseconds writeTimeout,
                std::size_t maxHeadBytes)
      : sock_(sock),
        conn_(conn),
        readTimeout_(readTimeout),
        writeTimeout_(writeTimeout),
        maxHeadBytes_(maxHeadBytes) {}

  bool buffered() const { return used_ < filled_; }

  bool is_readable() const override {
    return buffered() || waitSocket(sock_, POLLIN, readTimeoutNow());
  }
  bool is_writable() const override { return waitSocket(sock_, POLLOUT, writeTimeout_); }

  ssize_t read(char* ptr, std::size_t size) override {
    if (size == 0) return 0;
    if (conn_.inHead) {
      if (conn_.headBytes >= maxHeadBytes_) return -1;
      size = std::min(size, maxHeadBytes_ - conn_.headBytes);
    } else if (conn_.bodyBudget != std::numeric_limits<std::size_t>::max()) {
      if (conn_.bodyBudget == 0) {
        conn_.bodyOverflow = true;
        conn_.close = true;
        return -1;
      }
      size = std::min(size, conn_.bodyBudget);
    }
    if (!buffered()) {
      if (!waitSocket(sock_, POLLIN, readTimeoutNow())) return -1;
      ssize_t n;
      do {
        n = recv(sock_, buf_, sizeof buf_, 0);
      } while (n < 0 && errno == EINTR);
      if (n <= 0) return n;
      used_ = 0;
      filled_ = static_cast<std::size_t>(n);
    }
    const std::size_t n = std::min(size, filled_ - used_);
    std::memcpy(ptr, buf_ + used_, n);
    used_ += n;
    if (conn_.inHead) {
      conn_.headBytes += n;
    } else if (conn_.bodyBudget != std::numeric_limits<std::size_t>::max()) {
      conn_.bodyBudget -= n;
    }
    return static_cast<ssize_t>(n);
  }

  ssize_t write(const char* ptr, std::size_t size) override {
    if (!waitSocket(sock_, POLLOUT, writeTimeout_)) return -1;
    ssize_t n;
    do {
      n = send(sock_, ptr, size, MSG_NOSIGNAL);
    } while (n < 0 && errno == EINTR);
    return n;
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    socketAddress(sock_, true, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    socketAddress(sock_, false, ip, port);
  }
  socket_t socket() const override { return sock_; }

 private:
  milliseconds readTimeoutNow() const {
    if (!conn_.inHead) return readTimeout_;
    const auto left = std::chrono::duration_cast<milliseconds>(conn_.headDeadline - Clock::now());
    return std::max(milliseconds(0), std::min(readTimeout_, left));
  }

  int sock_;
  Connection& conn_;
  milliseconds readTimeout_;
  milliseconds writeTimeout_;
  std::size_t maxHeadBytes_;
  char buf_[16384];
  std::size_t used_ = 0;
  std::size_t filled_ = 0;
};

// cpp-httplib's server with its per-connection loop replaced (the loop is a
// virtual member; request parsing, routing and replies stay the library's): the
// stream above, and a connection whose request was refused before its body was
// read is closed after the reply instead of parsing the body as the next request.
class GuardedServer final : public httplib::Server {
 public:
  GuardedServer(milliseconds headTimeout, std::size_t maxHeadBytes, std::size_t drainBytes)
      : headTimeout_(headTimeout), maxHeadBytes_(maxHeadBytes), drainBytes_(drainBytes) {}

 private:
  bool process_and_close_socket(socket_t sock) override {
    Connection conn;
    tlsConnection = &conn;
    GuardedStream strm(
        sock, conn, milliseconds(read_timeout_sec_ * 1000 + read_timeout_usec_ / 1000),
        milliseconds(write_timeout_sec_ * 1000 + write_timeout_usec_ / 1000), maxHeadBytes_);
    bool ret = false;
    for (std::size_t left = keep_alive_max_count_; left > 0; --left) {
      if (!waitForRequest(sock, strm)) break;
      conn.begin(Clock::now() + headTimeout_);
      bool closed = false;
      ret = process_request(strm, left == 1, closed, nullptr);
      // A request that never reached the screen failed in its head (malformed, too
      // long, too slow): what follows on the connection cannot be trusted.
      if (!ret || closed || conn.close || conn.inHead) break;
    }
    tlsConnection = nullptr;
    if (conn.close) drain(sock);
    shutdown(sock, SHUT_RDWR);
    ::close(sock);
    return ret;
  }

  // Idle keep-alive: a request's first byte, the keep-alive timeout, or stop().
  bool waitForRequest(int sock, const GuardedStream& strm) const {
    if (strm.buffered()) return true;
    const Clock::time_point until = Clock::now() + std::chrono::seconds(keep_alive_timeout_sec_);
    while (svr_sock_ != INVALID_SOCKET) {
      pollfd p{sock, POLLIN, 0};
      const int r = poll(&p, 1, 50);
      if (r > 0) return true;
      if (r < 0 && errno != EINTR) return false;
      if (Clock::now() > until) return false;
    }
    return false;
  }

  // The reply is out; what the client still sends of the refused body is read and
  // dropped for a moment (closing with unread data would reset the connection, and
  // the client could lose the reply), then the connection is closed.
  void drain(int sock) const {
    shutdown(sock, SHUT_WR);
    const Clock::time_point until = Clock::now() + std::chrono::seconds(2);
    std::size_t total = 0;
    char buf[16384];
    while (total < drainBytes_) {
      const auto left = std::chrono::duration_cast<milliseconds>(until - Clock::now());
      if (left.count() <= 0 || !waitSocket(sock, POLLIN, left)) return;
      const ssize_t n = recv(sock, buf, sizeof buf, 0);
      if (n <= 0) return;
      total += static_cast<std::size_t>(n);
    }
  }

  milliseconds headTimeout_;
  std::size_t maxHeadBytes_;
  std::size_t drainBytes_;
};

}  // namespace

Connection* currentConnection() {
  return tlsConnection;
}

std::unique_ptr<httplib::Server> makeGuardedServer(milliseconds headTimeout,
                                                   std::size_t maxHeadBytes,
                                                   std::size_t drainBytes) {
  return std::make_unique<GuardedServer>(headTimeout, maxHeadBytes, drainBytes);
}

}  // namespace mdhd::service
