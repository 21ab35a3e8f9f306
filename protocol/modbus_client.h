#pragma once
// Reading a controller's registers over Modbus TCP. `RegisterSource` is what a
// shadow polls; `ModbusTcpClient` implements it, framing Modbus TCP itself (libmodbus
// names the errors).
//
// Failures are ModbusError, never a crash, a hang beyond timeout_ms or a SIGPIPE.
// timeout_ms bounds a whole call (read(): resolving the host name and connecting
// when needed, and every read of the poll; writeFeedHold(): the same and the
// write), however the peer and the name resolver pace their answers: a host name
// is resolved on a thread of its own (one at a time per client), so a resolver
// that never answers costs a call timeout_ms and interrupt() nothing; a later call
// waits for the same lookup. Every reply is checked: transaction id, protocol id 0, an MBAP
// length that matches the reply, the unit id, the function, the byte count, and a
// coil write's echo.
// After any failure except a Modbus exception reply or a bad value (the
// connection is still in step) the client drops the connection (a late reply
// would be taken for the next request) and reconnects on a later call once its
// backoff has passed: 50 ms, doubling per failure up to 2 s, back to 50 ms after a
// success. A call inside the backoff fails at once with kind kBackoff: the client
// never sleeps, so a poller keeps its own rhythm.
//
// Thread-safety: one client per polling thread; only interrupt() may be called
// from another thread.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/socket.h>

#include "protocol/modbus_map.h"

namespace mdhd::protocol {

class ModbusError : public std::runtime_error {
 public:
  enum class Kind {
    kConnect,         // cannot connect (refused, unreachable, name not found)
    kTimeout,         // no (complete) reply within timeout_ms
    kConnectionLost,  // the peer closed or reset the connection
    kException,       // the controller answered with a Modbus exception
    kMalformed,       // a reply that is not a valid answer to the request
    kBadValue,        // registers read fine but decode to no value (NaN, inf, ...)
    kBackoff,         // waiting before the next reconnection attempt
    kInterrupted,     // interrupt() was called (the caller is stopping)
  };
  ModbusError(Kind kind, int code, const std::string& message)
      : std::runtime_error(message), kind_(kind), code_(code) {}
  Kind kind() const { return kind_; }
  int code() const { return code_; }  // errno / libmodbus error number, 0 when none

 private:
  Kind kind_;
  int code_;
};

const char* modbusErrorKindName(ModbusError::Kind kind);

class RegisterSource {
 public:
  virtual ~RegisterSource() = default;
  // One poll of every mapped register, decoded. Throws ModbusError.
  virtual ModbusSample read() = 0;
  // Writes the map's feed-hold coil (true: hold). Throws ModbusError.
  virtual void writeFeedHold(bool hold) = 0;
  // From any thread: a call blocked on the network, and every later call, fails
  // at once with kind kInterrupted. For stopping the thread that polls.
  virtual void interrupt() {}
};

struct BackoffPolicy {
  std::chrono::milliseconds initial{50};
  std::chrono::milliseconds max{2000};
};

// One address a host name resolved to.
struct Endpoint {
  int family = 0;
  sockaddr_storage address{};
  socklen_t length = 0;
};

// Resolves host:port to its addresses, or throws std::runtime_error saying why
// not. May block as long as the system's resolver does: the client calls it on a
// thread of its own, never for a numeric address.
using Resolver = std::function<std::vector<Endpoint>(const std::string& host, int port)>;
// The default Resolver: getaddrinfo (TCP, IPv4 or IPv6).
std::vector<Endpoint> resolveHost(const std::string& host, int port);

class ModbusTcpClient : public RegisterSource {
 public:
  using Clock = std::function<std::chrono::steady_clock::time_point()>;

  // The map must be valid (validateModbusMap). Does not connect yet. `clock` is
  // for tests of the backoff; by default the steady clock. `resolver`: for tests
  // of a slow or silent name resolver; by default resolveHost.
  explicit ModbusTcpClient(ModbusMap map, BackoffPolicy backoff = {}, Clock clock = {},
                           Resolver resolver = {});
  ~ModbusTcpClient() override;
  ModbusTcpClient(const ModbusTcpClient&) = delete;
  ModbusTcpClient& operator=(const ModbusTcpClient&) = delete;

  ModbusSample read() override;
  void writeFeedHold(bool hold) override;
  void interrupt() override;

  // The raw registers of one read (as planReads plans them), for tools and benches.
  std::vector<std::uint16_t> readBlock(const ReadBlock& block);

  bool connected() const { return fd_ >= 0; }
  // The wait imposed by the latest failure (0 after a success) and the next one's.
  std::chrono::milliseconds lastWait() const { return last_wait_; }
  std::chrono::milliseconds nextWait() const { return next_wait_; }
  // When the next connection attempt is allowed.
  std::chrono::steady_clock::time_point nextAttempt() const { return next_attempt_; }
  std::uint64_t connects() const { return connects_; }  // successful connections so far
  const ModbusMap& map() const { return map_; }

 private:
  using Deadline = std::chrono::steady_clock::time_point;
  using Bytes = std::vector<std::uint8_t>;
  struct Lookup;  // a host name being resolved, shared with its thread

  Deadline deadline() const;
  void ensureConnected(Deadline deadline);
  // The host's addresses: at once for a numeric address, else from the lookup in
  // flight (started when none is), waited for until the deadline or interrupt().
  std::vector<Endpoint> resolve(Deadline deadline);
  void connectTo(Deadline deadline);
  void readInto(const ReadBlock& block, std::uint16_t* out, Deadline deadline);
  // Sends one request PDU and returns the reply PDU after checking its MBAP
  // header (transaction, protocol, length, unit) and function; an exception
  // reply throws kException.
  Bytes exchange(const Bytes& pdu, const std::string& what, Deadline deadline);
  // Waits until fd_ is ready for `events` or the wake fd fires; throws on the
  // deadline or an interrupt.
  void waitFor(short events, const std::string& what, Deadline deadline);
  void sendAll(const Bytes& bytes, const std::string& what, Deadline deadline);
  void receive(std::uint8_t* out, std::size_t n, const std::string& what, Deadline deadline);
  void succeeded();
  void disconnect();
  [[noreturn]] void fail(ModbusError::Kind kind, int code, const std::string& what,
                         const std::string& detail);
  std::string where() const;

  ModbusMap map_;
  std::vector<ReadBlock> blocks_;
  BackoffPolicy policy_;
  Clock clock_;
  Resolver resolver_;
  std::shared_ptr<Lookup> lookup_;  // in flight, or done and not taken yet
  int fd_ = -1;
  int wake_fd_ = -1;  // eventfd written by interrupt()
  std::atomic<bool> interrupted_{false};
  std::uint16_t transaction_ = 0;
  std::chrono::milliseconds last_wait_{0};
  std::chrono::milliseconds next_wait_;
  std::chrono::steady_clock::time_point next_attempt_{};
  std::uint64_t connects_ = 0;
  std::vector<std::vector<std::uint16_t>> words_;
};

}  // namespace mdhd::protocol
