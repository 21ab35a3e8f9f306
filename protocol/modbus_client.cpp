#include "protocol/modbus_client.h"

#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <mutex>
#include <optional>
#include <system_error>
#include <thread>

#include <modbus/modbus.h>

namespace mdhd::protocol {
namespace {

using Kind = ModbusError::Kind;
using SteadyClock = std::chrono::steady_clock;

constexpr std::uint8_t kWriteSingleCoil = 0x05;
constexpr std::size_t kMbapBytes = 7;  // transaction, protocol, length, unit
constexpr int kMaxMbapLength = 254;    // unit id + a PDU of at most 253 bytes

Kind classifyErrno(int code) {
  switch (code) {
    case ETIMEDOUT:
    case EAGAIN:
      return Kind::kTimeout;
    case ECONNREFUSED:
    case EHOSTUNREACH:
    case ENETUNREACH:
    case EADDRNOTAVAIL:
    case EINVAL:
      return Kind::kConnect;
    default:
      return Kind::kConnectionLost;  // ECONNRESET, EPIPE, EBADF, ...
  }
}

std::string hex(unsigned v, int digits) {
  static const char* kHex = "0123456789abcdef";
  std::string s = "0x";
  for (int i = digits - 1; i >= 0; --i) s += kHex[(v >> (4 * i)) & 0xF];
  return s;
}

std::uint16_t be16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>((p[0] << 8) | p[1]);
}

void putBe16(std::vector<std::uint8_t>& out, unsigned v) {
  out.push_back(static_cast<std::uint8_t>((v >> 8) & 0xFF));
  out.push_back(static_cast<std::uint8_t>(v & 0xFF));
}

std::string millis(int ms) {
  return std::to_string(ms) + " ms";
}

// Copies getaddrinfo's list and frees it.
std::vector<Endpoint> takeEndpoints(addrinfo* found) {
  std::vector<Endpoint> out;
  for (addrinfo* a = found; a != nullptr; a = a->ai_next) {
    if (a->ai_addrlen > sizeof(sockaddr_storage)) continue;
    Endpoint e;
    e.family = a->ai_family;
    e.length = a->ai_addrlen;
    std::memcpy(&e.address, a->ai_addr, a->ai_addrlen);
    out.push_back(e);
  }
  freeaddrinfo(found);
  return out;
}

// The addresses of a numeric host (never asks a resolver); nullopt for a name.
std::optional<std::vector<Endpoint>> numericHost(const std::string& host, int port) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_NUMERICHOST | AI_NUMERICSERV;
  addrinfo* found = nullptr;
  if (getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found) != 0)
    return std::nullopt;
  return takeEndpoints(found);
}

}  // namespace

// A host name being resolved on its own thread. The client and the thread share
// it: a client destroyed meanwhile leaves the thread to finish alone.
struct ModbusTcpClient::Lookup {
  std::mutex mutex;
  bool done = false;
  std::vector<Endpoint> found;
  std::string error;  // the resolver's message, when it failed
  int done_fd = -1;   // eventfd, written when done
  Lookup() : done_fd(eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK)) {}
  ~Lookup() {
    if (done_fd >= 0) close(done_fd);
  }
  Lookup(const Lookup&) = delete;
  Lookup& operator=(const Lookup&) = delete;
};

std::vector<Endpoint> resolveHost(const std::string& host, int port) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_NUMERICSERV;
  addrinfo* found = nullptr;
  if (const int rc = getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found);
      rc != 0) {
    throw std::runtime_error(rc == EAI_SYSTEM ? std::strerror(errno) : gai_strerror(rc));
  }
  std::vector<Endpoint> out = takeEndpoints(found);
  if (out.empty()) throw std::runtime_error("no address");
  return out;
}

const char* modbusErrorKindName(ModbusError::Kind kind) {
  switch (kind) {
    case Kind::kConnect:
      return "connect";
    case Kind::kTimeout:
      return "timeout";
    case Kind::kConnectionLost:
      return "connection_lost";
    case Kind::kException:
      return "exception";
    case Kind::kMalformed:
      return "malformed";
    case Kind::kBadValue:
      return "bad_value";
    case Kind::kBackoff:
      return "backoff";
    case Kind::kInterrupted:
      return "interrupted";
  }
  return "?";
}

ModbusTcpClient::ModbusTcpClient(ModbusMap map, BackoffPolicy backoff, Clock clock,
                                 Resolver resolver)
    : map_(std::move(map)),
      blocks_(planReads(map_)),
      policy_(backoff),
      clock_(clock ? std::move(clock) : Clock([] { return SteadyClock::now(); })),
      resolver_(resolver ? std::move(resolver) : Resolver(resolveHost)),
      next_wait_(policy_.initial) {
  for (const ReadBlock& b : blocks_) words_.emplace_back(static_cast<std::size_t>(b.count));
  wake_fd_ = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
}

ModbusTcpClient::~ModbusTcpClient() {
  disconnect();
  if (wake_fd_ >= 0) close(wake_fd_);
}

void ModbusTcpClient::interrupt() {
  interrupted_ = true;
  if (wake_fd_ >= 0) {
    const std::uint64_t one = 1;
    (void)!write(wake_fd_, &one, sizeof one);
  }
}

std::string ModbusTcpClient::where() const {
  return "modbus " + map_.host + ":" + std::to_string(map_.port);
}

ModbusTcpClient::Deadline ModbusTcpClient::deadline() const {
  return SteadyClock::now() + std::chrono::milliseconds(map_.timeout_ms);
}

void ModbusTcpClient::disconnect() {
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
}

void ModbusTcpClient::succeeded() {
  next_wait_ = policy_.initial;
  last_wait_ = std::chrono::milliseconds(0);
}

void ModbusTcpClient::fail(Kind kind, int code, const std::string& what,
                           const std::string& detail) {
  std::string message = where() + ": " + what + ": " + detail;
  // An exception reply is a whole frame: the connection is still in step. An
  // interrupted client is being stopped: no backoff to plan.
  if (kind == Kind::kInterrupted) {
    disconnect();
  } else if (kind != Kind::kException) {
    disconnect();
    last_wait_ = next_wait_;
    next_attempt_ = clock_() + last_wait_;
    next_wait_ = std::min(next_wait_ * 2, policy_.max);
    message += " (next attempt in " + std::to_string(last_wait_.count()) + " ms)";
  }
  throw ModbusError(kind, code, message);
}

void ModbusTcpClient::waitFor(short events, const std::string& what, Deadline deadline) {
  for (;;) {
    if (interrupted_.load()) fail(Kind::kInterrupted, ECANCELED, what, "interrupted");
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - SteadyClock::now());
    if (left.count() <= 0) {
      const std::string ms = std::to_string(map_.timeout_ms) + " ms";
      fail(Kind::kTimeout, ETIMEDOUT, what,
           what == "connect" ? "not connected within " + ms : "no complete reply within " + ms);
    }
    pollfd p[2] = {{fd_, events, 0}, {wake_fd_, POLLIN, 0}};
    const int n = poll(p, wake_fd_ >= 0 ? 2 : 1, static_cast<int>(left.count()));
    if (n < 0 && errno != EINTR) fail(classifyErrno(errno), errno, what, std::strerror(errno));
    if (n > 0 && p[0].revents != 0) return;  // ready, or an error the next call reports
  }
}

std::vector<Endpoint> ModbusTcpClient::resolve(Deadline deadline) {
  const std::string what = "connect";
  if (auto numeric = numericHost(map_.host, map_.port)) return std::move(*numeric);
  if (!lookup_) {
    // A name: resolved on a thread of its own, which the client never joins (the
    // system's resolver may take as long as it likes; the thread ends with it).
    auto lookup = std::make_shared<Lookup>();
    if (lookup->done_fd < 0)
      fail(Kind::kConnect, errno, what, "eventfd: " + std::string(std::strerror(errno)));
    try {
      std::thread([lookup, resolver = resolver_, host = map_.host, port = map_.port] {
        std::vector<Endpoint> found;
        std::string error;
        try {
          found = resolver(host, port);
          if (found.empty()) error = "no address";
        } catch (const std::exception& e) {
          error = e.what();
        }
        std::lock_guard lock(lookup->mutex);
        lookup->found = std::move(found);
        lookup->error = std::move(error);
        lookup->done = true;
        const std::uint64_t one = 1;
        (void)!write(lookup->done_fd, &one, sizeof one);
      }).detach();
    } catch (const std::system_error& e) {
      fail(Kind::kConnect, e.code().value(), what,
           std::string("cannot start resolving the host name: ") + e.what());
    }
    lookup_ = std::move(lookup);
  }
  for (;;) {
    {
      std::lock_guard lock(lookup_->mutex);
      if (lookup_->done) {
        const std::shared_ptr<Lookup> done = std::move(lookup_);  // the next attempt asks again
        if (!done->error.empty())
          fail(Kind::kConnect, EINVAL, what, "cannot resolve the host: " + done->error);
        return done->found;
      }
    }
    if (interrupted_.load()) fail(Kind::kInterrupted, ECANCELED, what, "interrupted");
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - SteadyClock::now());
    if (left.count() <= 0) {
      fail(Kind::kTimeout, ETIMEDOUT, what,
           "the host name " + map_.host + " did not resolve within " + millis(map_.timeout_ms) +
               " (the lookup goes on; a later attempt takes its answer)");
    }
    pollfd p[2] = {{lookup_->done_fd, POLLIN, 0}, {wake_fd_, POLLIN, 0}};
    const int n = poll(p, wake_fd_ >= 0 ? 2 : 1, static_cast<int>(left.count()));
    if (n < 0 && errno != EINTR) fail(classifyErrno(errno), errno, what, std::strerror(errno));
  }
}

void ModbusTcpClient::connectTo(Deadline deadline) {
  const std::string what = "connect";
  const std::vector<Endpoint> found = resolve(deadline);
  int error = ECONNREFUSED;
  for (const Endpoint& a : found) {
    fd_ = socket(a.family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd_ < 0) {
      error = errno;
      continue;
    }
    if (::connect(fd_, reinterpret_cast<const sockaddr*>(&a.address), a.length) == 0) break;
    if (errno != EINPROGRESS) {
      error = errno;
      disconnect();
      continue;
    }
    waitFor(POLLOUT, what, deadline);
    socklen_t len = sizeof error;
    if (getsockopt(fd_, SOL_SOCKET, SO_ERROR, &error, &len) == 0 && error == 0) break;
    disconnect();
  }
  if (fd_ < 0) fail(classifyErrno(error), error, what, std::strerror(error));
  const int one = 1;
  setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
}

void ModbusTcpClient::ensureConnected(Deadline deadline) {
  if (interrupted_.load()) fail(Kind::kInterrupted, ECANCELED, "connect", "interrupted");
  if (fd_ >= 0) return;
  const auto now = clock_();
  if (now < next_attempt_) {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(next_attempt_ - now);
    throw ModbusError(Kind::kBackoff, 0,
                      where() + ": reconnecting in " + std::to_string(left.count()) + " ms");
  }
  connectTo(deadline);
  ++connects_;
}

void ModbusTcpClient::sendAll(const Bytes& bytes, const std::string& what, Deadline deadline) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n > 0) {
      sent += static_cast<std::size_t>(n);
    } else if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      waitFor(POLLOUT, what, deadline);
    } else if (n < 0 && errno != EINTR) {
      fail(classifyErrno(errno), errno, what, std::strerror(errno));
    }
  }
}

void ModbusTcpClient::receive(std::uint8_t* out, std::size_t n, const std::string& what,
                              Deadline deadline) {
  std::size_t got = 0;
  while (got < n) {
    const ssize_t r = recv(fd_, out + got, n - got, 0);
    if (r > 0) {
      got += static_cast<std::size_t>(r);
    } else if (r == 0) {
      fail(Kind::kConnectionLost, ECONNRESET, what,
           "the peer closed the connection" +
               (got > 0 ? " after " + std::to_string(got) + " bytes of a reply part"
                        : std::string()));
    } else if (errno == EAGAIN || errno == EWOULDBLOCK) {
      waitFor(POLLIN, what, deadline);
    } else if (errno != EINTR) {
      fail(classifyErrno(errno), errno, what, std::strerror(errno));
    }
  }
}

ModbusTcpClient::Bytes ModbusTcpClient::exchange(const Bytes& pdu, const std::string& what,
                                                 Deadline deadline) {
  const std::uint16_t tid = ++transaction_;
  Bytes request;
  request.reserve(kMbapBytes + pdu.size());
  putBe16(request, tid);
  putBe16(request, 0);
  putBe16(request, static_cast<unsigned>(pdu.size() + 1));
  request.push_back(static_cast<std::uint8_t>(map_.unit_id));
  request.insert(request.end(), pdu.begin(), pdu.end());
  // Bytes waiting before the request is sent answer no request of ours: a peer
  // that sends unasked, or more than a reply said. Taken for this reply they
  // would fail it as another request's reply, which misleads.
  std::uint8_t early[8];
  const ssize_t waiting = recv(fd_, early, sizeof early, MSG_PEEK | MSG_DONTWAIT);
  if (waiting > 0) {
    std::string bytes;
    for (ssize_t i = 0; i < waiting; ++i) bytes += (i > 0 ? " " : "") + hex(early[i], 2);
    fail(Kind::kMalformed, EMBBADDATA, what,
         "the peer sent bytes no request asked for (" + bytes +
             (waiting == static_cast<ssize_t>(sizeof early) ? " ..." : "") +
             ") before this request");
  }
  if (waiting == 0) {
    fail(Kind::kConnectionLost, ECONNRESET, what,
         "the peer closed the connection before this request");
  }
  if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
    fail(classifyErrno(errno), errno, what, std::strerror(errno));
  sendAll(request, what, deadline);

  std::uint8_t header[kMbapBytes];
  receive(header, kMbapBytes, what, deadline);
  const std::uint16_t reply_tid = be16(header);
  const std::uint16_t protocol = be16(header + 2);
  const std::uint16_t length = be16(header + 4);
  const std::uint8_t unit = header[6];
  if (protocol != 0) {
    fail(Kind::kMalformed, EMBBADDATA, what,
         "the reply's MBAP protocol id is " + std::to_string(protocol) + ", not 0 (Modbus)");
  }
  if (reply_tid != tid) {
    fail(Kind::kMalformed, EMBBADDATA, what,
         "the reply's transaction id is " + hex(reply_tid, 4) + ", not " + hex(tid, 4) +
             " (another request's reply)");
  }
  if (length < 2 || length > kMaxMbapLength) {
    fail(Kind::kMalformed, EMBBADDATA, what,
         "the reply's MBAP length is " + std::to_string(length) + ", outside 2..254");
  }
  if (unit != map_.unit_id) {
    fail(Kind::kMalformed, EMBBADSLAVE, what,
         "the reply comes from unit id " + std::to_string(unit) + ", not " +
             std::to_string(map_.unit_id));
  }
  Bytes reply(static_cast<std::size_t>(length - 1));
  receive(reply.data(), reply.size(), what, deadline);
  if (reply[0] == (pdu[0] | 0x80)) {
    if (reply.size() != 2) {
      fail(Kind::kMalformed, EMBBADDATA, what,
           "an exception reply of " + std::to_string(reply.size()) + " PDU bytes, not 2");
    }
    const int code = reply[1];
    const bool known =
        code >= MODBUS_EXCEPTION_ILLEGAL_FUNCTION && code <= MODBUS_EXCEPTION_GATEWAY_TARGET;
    fail(Kind::kException, known ? MODBUS_ENOBASE + code : 0, what,
         known ? std::string(modbus_strerror(MODBUS_ENOBASE + code))
               : "exception code " + std::to_string(code));
  }
  if (reply[0] != pdu[0]) {
    fail(Kind::kMalformed, EMBBADDATA, what,
         "the reply is for function " + std::to_string(reply[0]) + ", not " +
             std::to_string(pdu[0]));
  }
  return reply;
}

void ModbusTcpClient::readInto(const ReadBlock& block, std::uint16_t* out, Deadline deadline) {
  ensureConnected(deadline);
  const std::string what = std::string("read ") + registerTableName(map_.table) + " registers " +
                           std::to_string(block.start) + ".." +
                           std::to_string(block.start + block.count - 1);
  Bytes pdu = {static_cast<std::uint8_t>(map_.table == RegisterTable::kHolding ? 0x03 : 0x04)};
  putBe16(pdu, static_cast<unsigned>(block.start));
  putBe16(pdu, static_cast<unsigned>(block.count));
  const Bytes reply = exchange(pdu, what, deadline);
  const std::size_t want = 2 * static_cast<std::size_t>(block.count);
  if (reply.size() < 2 || reply[1] != want || reply.size() != 2 + want) {
    fail(Kind::kMalformed, EMBBADDATA, what,
         "a reply of " + std::to_string(reply.size() < 2 ? 0 : reply[1]) + " data bytes (" +
             std::to_string(reply.size()) + " PDU bytes) where " + std::to_string(want) +
             " were asked");
  }
  for (int i = 0; i < block.count; ++i) out[i] = be16(reply.data() + 2 + 2 * i);
  succeeded();
}

std::vector<std::uint16_t> ModbusTcpClient::readBlock(const ReadBlock& block) {
  std::vector<std::uint16_t> words(static_cast<std::size_t>(block.count));
  readInto(block, words.data(), deadline());
  return words;
}

ModbusSample ModbusTcpClient::read() {
  const Deadline until = deadline();  // one deadline for the whole poll
  for (std::size_t i = 0; i < blocks_.size(); ++i) readInto(blocks_[i], words_[i].data(), until);
  try {
    return decodeSample(map_, blocks_, words_);
  } catch (const RegisterValueError& e) {
    throw ModbusError(Kind::kBadValue, 0, where() + ": " + e.what());
  }
}

void ModbusTcpClient::writeFeedHold(bool hold) {
  const Deadline until = deadline();
  ensureConnected(until);
  const std::string what = "write coil " + std::to_string(map_.feed_hold.coil);
  Bytes pdu = {kWriteSingleCoil};
  putBe16(pdu, static_cast<unsigned>(map_.feed_hold.coil));
  putBe16(pdu, hold ? 0xFF00 : 0x0000);
  const Bytes reply = exchange(pdu, what, until);
  // A write-single-coil reply echoes the request: anything else did not write it.
  if (reply != pdu) {
    std::string echoed = reply.size() == 5 ? "coil " + std::to_string(be16(reply.data() + 1)) +
                                                 " value " + hex(be16(reply.data() + 3), 4)
                                           : std::to_string(reply.size()) + " PDU bytes";
    fail(Kind::kMalformed, EMBBADDATA, what,
         "the reply echoes " + echoed + ", not coil " + std::to_string(map_.feed_hold.coil) +
             " value " + hex(hold ? 0xFF00 : 0, 4));
  }
  succeeded();
}

}  // namespace mdhd::protocol
