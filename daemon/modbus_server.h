#pragma once
// A Modbus TCP server over one register table and a few coils, for the simulated
// controller (`mdhd modbus-sim`) and tests: a thread answers any number of clients
// with libmodbus (poll loop + modbus_receive/modbus_reply). A client that
// disconnects, stalls mid-frame or sends garbage loses its own connection only.
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
  int max_clients = 64;       // more are accepted and closed at once
  int byte_timeout_ms = 100;  // a client stalling mid-frame is dropped after this
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
  void run();
  void serveClient(int fd, std::vector<int>& drop);

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
