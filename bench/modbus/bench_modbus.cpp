// Sustained poll rate of one client reading the default map of a 5-axis machine
// (14 registers: 5 float32 joints, tool, spindle_on, line uint32) on loopback:
//  1. ModbusTcpClient::read() (read + decode) against daemon::ModbusServer while a
//     publisher thread rewrites the registers every 2 ms, as `mdhd modbus-sim` does;
//  2. baseline: raw modbus_read_registers against a bare libmodbus server
//     (modbus_tcp_accept + modbus_receive + modbus_reply) with a static mapping.
// Each poll is timed back to back; prints polls/s, median, p99 and max latency.
//
//   bench_modbus [--seconds S]   (default 2 per case)
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include <modbus/modbus.h>

#include "daemon/modbus_server.h"
#include "protocol/modbus_client.h"
#include "sim/kinematics/presets.h"

namespace {

using Clock = std::chrono::steady_clock;
using namespace mdhd;

struct Figures {
  std::size_t polls = 0;
  double seconds = 0.0;
  double median_us = 0.0;
  double p99_us = 0.0;
  double max_us = 0.0;
};

template <typename Poll>
Figures measure(double seconds, Poll&& poll) {
  std::vector<double> us;
  us.reserve(1 << 20);
  const auto start = Clock::now();
  const auto end = start + std::chrono::duration<double>(seconds);
  auto t = start;
  while (t < end) {
    poll();
    const auto next = Clock::now();
    us.push_back(std::chrono::duration<double, std::micro>(next - t).count());
    t = next;
  }
  Figures f;
  f.polls = us.size();
  f.seconds = std::chrono::duration<double>(t - start).count();
  std::sort(us.begin(), us.end());
  f.median_us = us[us.size() / 2];
  f.p99_us = us[std::min(us.size() - 1, us.size() * 99 / 100)];
  f.max_us = us.back();
  return f;
}

void print(const char* name, const Figures& f) {
  std::printf("%-44s %9.0f polls/s  median %6.1f us  p99 %6.1f us  max %7.1f us  (%zu polls)\n",
              name, static_cast<double>(f.polls) / f.seconds, f.median_us, f.p99_us, f.max_us,
              f.polls);
}

Figures simulatedServer(double seconds) {
  const kin::Machine machine = kin::presets::acTrunnion();
  protocol::ModbusMap map = protocol::defaultModbusMap(machine);
  daemon::ModbusServerOptions options;
  options.registers = protocol::registerSpan(map);
  daemon::ModbusServer server(options);
  map.port = server.port();

  std::atomic<bool> stop{false};
  std::thread publisher([&] {  // the virtual machine's rhythm: a new pose every 2 ms
    std::vector<std::uint16_t> image(static_cast<std::size_t>(options.registers));
    protocol::ModbusSample s;
    s.tool = 1;
    s.spindle_on = true;
    for (std::int64_t i = 0; !stop; ++i) {
      for (int a = 0; a < 6; ++a) s.joints[a] = 0.001 * static_cast<double>(i + a);
      s.line = i;
      protocol::encodeSample(map, s, image);
      server.setRegisters(image);
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  });
  protocol::ModbusTcpClient client(map);
  double sink = 0.0;
  const Figures f = measure(seconds, [&] { sink += client.read().joints[gcode::kX]; });
  stop = true;
  publisher.join();
  if (sink < 0) std::printf("(impossible)\n");
  return f;
}

Figures bareLibmodbus(double seconds, int registers) {
  modbus_t* srv = modbus_new_tcp("127.0.0.1", 0);
  const int listen_fd = modbus_tcp_listen(srv, 1);
  sockaddr_in addr{};
  socklen_t len = sizeof addr;
  getsockname(listen_fd, reinterpret_cast<sockaddr*>(&addr), &len);
  const int port = ntohs(addr.sin_port);
  modbus_mapping_t* mapping = modbus_mapping_new(0, 0, registers, 0);
  for (int i = 0; i < registers; ++i) mapping->tab_registers[i] = static_cast<std::uint16_t>(i);
  std::thread server([&] {
    int fd = listen_fd;
    if (modbus_tcp_accept(srv, &fd) < 0) return;
    std::uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
    for (;;) {
      const int rc = modbus_receive(srv, query);
      if (rc > 0) {
        modbus_reply(srv, query, rc, mapping);
      } else if (rc < 0) {
        break;  // the client closed
      }
    }
  });
  modbus_t* client = modbus_new_tcp("127.0.0.1", port);
  modbus_connect(client);
  std::vector<std::uint16_t> words(static_cast<std::size_t>(registers));
  const Figures f = measure(seconds, [&] {
    if (modbus_read_registers(client, 0, registers, words.data()) != registers) {
      std::fprintf(stderr, "baseline read failed: %s\n", modbus_strerror(errno));
      std::exit(1);
    }
  });
  modbus_close(client);
  modbus_free(client);
  server.join();
  close(listen_fd);
  modbus_close(srv);
  modbus_free(srv);
  modbus_mapping_free(mapping);
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 2.0;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--seconds") == 0 && i + 1 < argc) {
      seconds = std::atof(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: bench_modbus [--seconds S]\n");
      return 2;
    }
  }
  if (!(seconds > 0.0)) seconds = 2.0;
  const int registers =
      protocol::registerSpan(protocol::defaultModbusMap(kin::presets::acTrunnion()));
  std::printf("one client, %d registers (default map, 5 joints), loopback, %.1f s per case\n",
              registers, seconds);
  print("ModbusTcpClient::read, simulated server", simulatedServer(seconds));
  print("modbus_read_registers, bare libmodbus server", bareLibmodbus(seconds, registers));
  return 0;
}
