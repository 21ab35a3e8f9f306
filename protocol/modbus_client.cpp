#include "protocol/modbus_client.h"

#include <cerrno>

#include <modbus/modbus.h>

namespace mdhd::protocol {
namespace {

using Kind = ModbusError::Kind;

Kind classify(int code) {
  if (code >= EMBXILFUN && code <= EMBXGTAR) return Kind::kException;
  if (code >= EMBBADCRC && code <= EMBBADSLAVE) return Kind::kMalformed;
  switch (code) {
    case ETIMEDOUT:
    case EAGAIN:
      return Kind::kTimeout;
    case ECONNREFUSED:
    case EHOSTUNREACH:
    case ENETUNREACH:
    case EADDRNOTAVAIL:
    case EINVAL:  // libmodbus: bad address or name not resolved
      return Kind::kConnect;
    default:
      return Kind::kConnectionLost;  // ECONNRESET, EPIPE, EBADF, ...
  }
}

}  // namespace

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
  }
  return "?";
}

ModbusTcpClient::ModbusTcpClient(ModbusMap map, BackoffPolicy backoff, Clock clock)
    : map_(std::move(map)),
      blocks_(planReads(map_)),
      policy_(backoff),
      clock_(clock ? std::move(clock) : Clock([] { return std::chrono::steady_clock::now(); })),
      next_wait_(policy_.initial) {
  for (const ReadBlock& b : blocks_) words_.emplace_back(static_cast<std::size_t>(b.count));
}

ModbusTcpClient::~ModbusTcpClient() {
  disconnect();
  if (ctx_ != nullptr) modbus_free(ctx_);
}

std::string ModbusTcpClient::where() const {
  return "modbus " + map_.host + ":" + std::to_string(map_.port);
}

void ModbusTcpClient::disconnect() {
  if (ctx_ != nullptr && connected_) modbus_close(ctx_);
  connected_ = false;
}

void ModbusTcpClient::fail(int code, const std::string& what) {
  const Kind kind = classify(code);
  std::string message = where() + ": " + what + ": " + modbus_strerror(code);
  // An exception reply is a whole frame: the connection is still in step.
  if (kind != Kind::kException) {
    disconnect();
    last_wait_ = next_wait_;
    next_attempt_ = clock_() + last_wait_;
    next_wait_ = std::min(next_wait_ * 2, policy_.max);
    message += " (next attempt in " + std::to_string(last_wait_.count()) + " ms)";
  }
  throw ModbusError(kind, code, message);
}

void ModbusTcpClient::ensureConnected() {
  if (connected_) return;
  const auto now = clock_();
  if (now < next_attempt_) {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(next_attempt_ - now);
    throw ModbusError(Kind::kBackoff, 0,
                      where() + ": reconnecting in " + std::to_string(left.count()) + " ms");
  }
  if (ctx_ == nullptr) {
    ctx_ = modbus_new_tcp_pi(map_.host.c_str(), std::to_string(map_.port).c_str());
    if (ctx_ == nullptr) fail(errno, "cannot create a context");
    const auto sec = static_cast<std::uint32_t>(map_.timeout_ms / 1000);
    const auto usec = static_cast<std::uint32_t>((map_.timeout_ms % 1000) * 1000);
    modbus_set_response_timeout(ctx_, sec, usec);
    modbus_set_byte_timeout(ctx_, sec, usec);
    modbus_set_slave(ctx_, map_.unit_id);
  }
  if (modbus_connect(ctx_) == -1) fail(errno, "connect");
  connected_ = true;
  ++connects_;
}

void ModbusTcpClient::readInto(const ReadBlock& block, std::uint16_t* out) {
  ensureConnected();
  const int rc = map_.table == RegisterTable::kHolding
                     ? modbus_read_registers(ctx_, block.start, block.count, out)
                     : modbus_read_input_registers(ctx_, block.start, block.count, out);
  if (rc != block.count) {
    fail(rc == -1 ? errno : EMBBADDATA, std::string("read ") + registerTableName(map_.table) +
                                            " registers " + std::to_string(block.start) + ".." +
                                            std::to_string(block.start + block.count - 1));
  }
  next_wait_ = policy_.initial;
  last_wait_ = std::chrono::milliseconds(0);
}

std::vector<std::uint16_t> ModbusTcpClient::readBlock(const ReadBlock& block) {
  std::vector<std::uint16_t> words(static_cast<std::size_t>(block.count));
  readInto(block, words.data());
  return words;
}

ModbusSample ModbusTcpClient::read() {
  for (std::size_t i = 0; i < blocks_.size(); ++i) readInto(blocks_[i], words_[i].data());
  try {
    return decodeSample(map_, blocks_, words_);
  } catch (const RegisterValueError& e) {
    throw ModbusError(Kind::kBadValue, 0, where() + ": " + e.what());
  }
}

void ModbusTcpClient::writeFeedHold(bool hold) {
  ensureConnected();
  if (modbus_write_bit(ctx_, map_.feed_hold.coil, hold ? 1 : 0) != 1) {
    fail(errno, "write coil " + std::to_string(map_.feed_hold.coil));
  }
  next_wait_ = policy_.initial;
  last_wait_ = std::chrono::milliseconds(0);
}

}  // namespace mdhd::protocol
