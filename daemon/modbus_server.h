#pragma once
// A Modbus TCP server over one register table and a few coils, for the simulated
// controller (`mdhd modbus-sim`) and tests: a thread answers any number of clients
// (poll loop; frames cut from the MBAP header without blocking, each answered by
// libmodbus's modbus_reply). A client that disconnects, stalls mid-frame or sends
// garbage (a protocol id other than 0, a length out of 2..254) loses its own
// connection only and never delays the others. (modbus_receive is not used: it
// blocks on a client that stalls mid-frame, holding up every other client.)
//
// The owner publishes register values with setRegisters() and reads coils with
// coil(); both are thread-safe (a mutex guards the shared copy; the server thread
// copies it into libmodbus's mapping before each reply, so no lock is held while
// a reply is sent).
#include <atomic>
#include <cstdint>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "protocol/modbus_map.h"

struct _modbus;
struct _modbus_mapping_t;

namespace mdhd::daemon {

class ModbusServerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ModbusServerOptions {
  std::string host = "127.0.0.1";  // an IPv4 address, "localhost" or "0.0.0.0"
  int port = 0;                    // 0: an ephemeral port (see port())
  protocol::RegisterTable table = protocol::RegisterTable::kHolding;
  int registers = 0;  // registers 0..registers-1 exist; others answer illegal address
  int coils = 1;
  int max_clients = 64;  // more are accepted and closed at once
  // Register values from the first reply on (the rest zero): a controller never
  // shows a pose it is not in, not even before its owner's first setRegisters.
  std::vector<std::uint16_t> initial;
};

class ModbusServer {
 public:
  // Binds and listens (throws ModbusServerError saying why); the thread starts
  // answering at once.
  explicit ModbusServer(ModbusServerOptions options);
  ~ModbusServer();  // stop()
  ModbusServer(const ModbusServer&) = delete;
  ModbusServer& operator=(const ModbusServer&) = delete;

  int port() const { return port_; }  // the bound port
  const std::string& host() const { return options_.host; }

  // Registers from address 0 (at most options.registers of them).
  void setRegisters(std::span<const std::uint16_t> values);
  bool coil(int address) const;
  std::uint64_t requests() const { return requests_.load(); }
  int clients() const { return clients_.load(); }

  // Stops answering, closes every connection and joins the thread. Idempotent.
  void stop();

 private:
  struct Client {
    int fd = -1;
    std::vector<std::uint8_t> buffer;  // bytes of a frame not yet complete
  };
  void run();
  // Reads what the client sent and answers each whole frame; false: drop it.
  bool serveClient(Client& client);
  bool reply(int fd, const std::uint8_t* query, int length);

  ModbusServerOptions options_;
  int listen_fd_ = -1;
  int port_ = 0;
  _modbus* ctx_ = nullptr;
  _modbus_mapping_t* mapping_ = nullptr;  // the server thread's only
  mutable std::mutex mutex_;
  std::vector<std::uint16_t> shared_registers_;  // guarded by mutex_
  std::vector<std::uint8_t> shared_coils_;       // guarded by mutex_
  bool registers_changed_ = true;                // guarded by mutex_
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> requests_{0};
  std::atomic<int> clients_{0};
  std::thread thread_;
};

}  // namespace mdhd::daemon
