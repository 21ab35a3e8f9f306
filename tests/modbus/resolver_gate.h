#pragma once
// A name resolver for tests: answers 127.0.0.1 for any name, but only once its
// gate is open (or `give_up` has passed: a test of the old, blocking client then
// ends instead of hanging). Counts its calls. The first `free_calls` calls pass
// at once.
#include <arpa/inet.h>
#include <netinet/in.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <memory>
#include <mutex>

#include "protocol/modbus_client.h"

namespace mdhd::modbus_test {

struct ResolverGate {
  std::mutex mutex;
  std::condition_variable opened;
  bool open = false;
  int free_calls = 0;
  std::atomic<int> calls{0};
  std::chrono::milliseconds give_up{5000};

  void release() {
    std::lock_guard lock(mutex);
    open = true;
    opened.notify_all();
  }
};

inline protocol::Endpoint loopbackEndpoint(int port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  protocol::Endpoint e;
  e.family = AF_INET;
  e.length = sizeof a;
  std::memcpy(&e.address, &a, sizeof a);
  return e;
}

// The resolver; the gate outlives the client (its thread holds it).
inline protocol::Resolver gatedResolver(std::shared_ptr<ResolverGate> gate) {
  return [gate](const std::string&, int port) {
    if (gate->calls++ >= gate->free_calls) {
      std::unique_lock lock(gate->mutex);
      gate->opened.wait_for(lock, gate->give_up, [&] { return gate->open; });
    }
    return std::vector<protocol::Endpoint>{loopbackEndpoint(port)};
  };
}

}  // namespace mdhd::modbus_test
