#include "daemon/modbus_server.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <modbus/modbus.h>

namespace mdhd::daemon {
namespace {

constexpr int kPollMs = 50;  // how often the loop looks at the stop flag

std::string systemError(const std::string& what) {
  return what + ": " + std::strerror(errno);
}

int listenOn(const std::string& host, int port, int& bound_port) {
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  const std::string ip = host == "localhost" ? "127.0.0.1" : host;
  if (inet_pton(AF_INET, ip.c_str(), &addr.sin_addr) != 1) {
    throw ModbusServerError("'" + host + "' is not an IPv4 address to listen on");
  }
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw ModbusServerError(systemError("socket"));
  const int one = 1;
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || listen(fd, 16) != 0) {
    const std::string message =
        systemError("cannot listen on " + host + ":" + std::to_string(port));
    close(fd);
    throw ModbusServerError(message);
  }
  socklen_t len = sizeof addr;
  getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  bound_port = ntohs(addr.sin_port);
  return fd;
}

}  // namespace

ModbusServer::ModbusServer(ModbusServerOptions options) : options_(std::move(options)) {
  if (options_.registers < 0 || options_.registers > 65536 || options_.coils < 0 ||
      options_.coils > 65536) {
    throw ModbusServerError("register or coil count out of 0..65536");
  }
  listen_fd_ = listenOn(options_.host, options_.port, port_);
  // The context only frames and answers requests on the sockets handed to it.
  ctx_ = modbus_new_tcp("127.0.0.1", port_);
  const bool holding = options_.table == protocol::RegisterTable::kHolding;
  mapping_ = modbus_mapping_new(options_.coils, 0, holding ? options_.registers : 0,
                                holding ? 0 : options_.registers);
  if (ctx_ == nullptr || mapping_ == nullptr) {
    stop();
    throw ModbusServerError("cannot allocate the Modbus context or register mapping");
  }
  shared_registers_.assign(static_cast<std::size_t>(options_.registers), 0);
  std::copy_n(options_.initial.begin(), std::min(options_.initial.size(), shared_registers_.size()),
              shared_registers_.begin());
  shared_coils_.assign(static_cast<std::size_t>(options_.coils), 0);
  thread_ = std::thread([this] { run(); });
}

ModbusServer::~ModbusServer() {
  stop();
}

void ModbusServer::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (listen_fd_ >= 0) close(listen_fd_);
  listen_fd_ = -1;
  if (mapping_ != nullptr) modbus_mapping_free(mapping_);
  mapping_ = nullptr;
  if (ctx_ != nullptr) modbus_free(ctx_);
  ctx_ = nullptr;
}

void ModbusServer::setRegisters(std::span<const std::uint16_t> values) {
  std::lock_guard lock(mutex_);
  const std::size_t n = std::min(values.size(), shared_registers_.size());
  std::copy_n(values.begin(), n, shared_registers_.begin());
  registers_changed_ = true;
}

bool ModbusServer::coil(int address) const {
  std::lock_guard lock(mutex_);
  return address >= 0 && static_cast<std::size_t>(address) < shared_coils_.size() &&
         shared_coils_[static_cast<std::size_t>(address)] != 0;
}

bool ModbusServer::serveClient(Client& client) {
  std::uint8_t chunk[512];
  const ssize_t n = recv(client.fd, chunk, sizeof chunk, MSG_DONTWAIT);
  if (n == 0) return false;  // closed
  if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
  client.buffer.insert(client.buffer.end(), chunk, chunk + n);
  // Frames are cut here from the MBAP header, so a client that stalls mid-frame
  // only waits for itself; libmodbus checks and answers each whole frame.
  while (client.buffer.size() >= 7) {
    const std::vector<std::uint8_t>& b = client.buffer;
    const int protocol_id = (b[2] << 8) | b[3];
    const int length = (b[4] << 8) | b[5];  // unit id + PDU
    if (protocol_id != 0 || length < 2 || length > MODBUS_TCP_MAX_ADU_LENGTH - 6) return false;
    const auto frame = static_cast<std::size_t>(6 + length);
    if (b.size() < frame) break;
    if (!reply(client.fd, b.data(), static_cast<int>(frame))) return false;
    client.buffer.erase(client.buffer.begin(), client.buffer.begin() + static_cast<long>(frame));
  }
  return true;
}

bool ModbusServer::reply(int fd, const std::uint8_t* query, int length) {
  {
    std::lock_guard lock(mutex_);
    if (registers_changed_) {
      std::uint16_t* table = options_.table == protocol::RegisterTable::kHolding
                                 ? mapping_->tab_registers
                                 : mapping_->tab_input_registers;
      std::copy(shared_registers_.begin(), shared_registers_.end(), table);
      registers_changed_ = false;
    }
  }
  const std::uint8_t function = query[7];
  const bool writes_coils =
      function == MODBUS_FC_WRITE_SINGLE_COIL || function == MODBUS_FC_WRITE_MULTIPLE_COILS;
  int sent = 0;
  ++requests_;  // before the reply, so a client that has its answer sees it counted
  modbus_set_socket(ctx_, fd);
  if (writes_coils) {
    // Rare (a feed hold): the owner must see the coil once the client has its reply,
    // so the write, the reply and the copy happen under the lock.
    std::lock_guard lock(mutex_);
    sent = modbus_reply(ctx_, query, length, mapping_);
    std::copy_n(mapping_->tab_bits, shared_coils_.size(), shared_coils_.begin());
  } else {
    // Sent without the lock: a slow reader cannot stall the controller's publisher.
    sent = modbus_reply(ctx_, query, length, mapping_);
  }
  if (sent < 0) return false;
  if (function == MODBUS_FC_WRITE_SINGLE_REGISTER ||
      function == MODBUS_FC_WRITE_MULTIPLE_REGISTERS ||
      function == MODBUS_FC_WRITE_AND_READ_REGISTERS || function == MODBUS_FC_MASK_WRITE_REGISTER) {
    std::lock_guard lock(mutex_);
    registers_changed_ = true;  // the controller's values win over a client's writes
  }
  return true;
}

void ModbusServer::run() {
  std::vector<pollfd> fds;
  std::vector<Client> clients;
  while (!stop_) {
    fds.clear();
    fds.push_back({listen_fd_, POLLIN, 0});
    for (const Client& c : clients) fds.push_back({c.fd, POLLIN, 0});
    const int ready = poll(fds.data(), fds.size(), kPollMs);
    if (ready <= 0) continue;  // timeout, or EINTR from a signal
    std::vector<Client> kept;
    for (std::size_t i = 0; i < clients.size(); ++i) {
      const bool alive =
          (fds[i + 1].revents & (POLLIN | POLLHUP | POLLERR)) == 0 || serveClient(clients[i]);
      if (alive) {
        kept.push_back(std::move(clients[i]));
      } else {
        close(clients[i].fd);
      }
    }
    clients = std::move(kept);
    if (fds[0].revents & POLLIN) {
      const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
      if (fd >= 0 && static_cast<int>(clients.size()) >= options_.max_clients) {
        close(fd);
      } else if (fd >= 0) {
        const int one = 1;
        setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
        const timeval send_limit{1, 0};  // a client that never reads is dropped, not waited for
        setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &send_limit, sizeof send_limit);
        clients.push_back({fd, {}});
      }
    }
    clients_ = static_cast<int>(clients.size());
  }
  for (const Client& c : clients) close(c.fd);
  clients_ = 0;
}

}  // namespace mdhd::daemon
