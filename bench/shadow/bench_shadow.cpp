// Live shadowing on loopback, on a 5-joint machine (the AC trunnion preset, the
// default map: 14 registers), against daemon::ModbusServer in this process:
//  1. baseline: back-to-back ModbusTcpClient::read() (read + decode), no carving;
//  2. a ShadowSession polling at poll_hz 1000 while a publisher thread moves the
//     tool through the stock every millisecond (a 15 mm circle 1 mm deep at
//     2,000 mm/min, the C table turning): polls/s achieved, the carve backlog
//     (samples waiting to be cut: the largest seen and at the end), motions cut;
//  3. through `mdhd serve`'s HTTP service: the tool is moved into a fixture by one
//     register change; the time until the alarm event arrives on the SSE stream,
//     over many cycles: median, p99, max.
//
//   bench_shadow [--seconds S] [--baseline-seconds S] [--cycles N] [--engine-only 1]
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "daemon/modbus_server.h"
#include "daemon/service.h"
#include "daemon/shadow_session.h"
#include "protocol/machine_json.h"
#include "protocol/modbus_map_json.h"
#include "sim/kinematics/inverse.h"
#include "sim/kinematics/presets.h"
#include "tests/shadow/sse_reader.h"

namespace {

using namespace mdhd;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

constexpr double kToolLength = 50.0;

struct Args {
  double seconds = 3.0;
  double baseline_seconds = 2.0;
  int cycles = 200;
  bool engine_only = false;  // only the contact motions in the engine (for a profiler)
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    const double v = std::atof(argv[i + 1]);
    if (k == "--seconds") a.seconds = v;
    if (k == "--engine-only") a.engine_only = v != 0.0;
    if (k == "--baseline-seconds") a.baseline_seconds = v;
    if (k == "--cycles") a.cycles = static_cast<int>(v);
  }
  return a;
}

protocol::Job cell() {
  protocol::Job job;
  job.machine = kin::presets::acTrunnion();
  geom::Tool t;
  t.number = 1;
  t.shape = geom::ToolShape::kFlat;
  t.diameter = 6;
  t.shank_diameter = 6;
  t.flute_length = 12;
  t.length = kToolLength;
  t.holder = {{30, 20}};
  job.tools.push_back(t);
  job.stock = {{-30, -30, -20}, {30, 30, 0}};
  protocol::Fixture f;  // a clamp beside the stock
  f.box = {{40, -10, -20}, {60, 10, 10}};
  job.fixtures.push_back(f);
  job.options.density = 10;
  return job;
}

// Joints putting the tool tip at `tip` (W) with the rotaries given.
gcode::AxisValues jointsAt(const kin::Kinematics& kin, glm::dvec3 tip, double a, double c) {
  gcode::AxisValues q = kin.machine().home;
  q[gcode::kA] = a;
  q[gcode::kC] = c;
  return kin::solveTipOrThrow(kin, tip, kToolLength, q);
}

class Controller {
 public:
  explicit Controller(const protocol::ModbusMap& map) : map_(map) {
    daemon::ModbusServerOptions o;
    o.registers = protocol::registerSpan(map);
    o.coils = 1;
    server_ = std::make_unique<daemon::ModbusServer>(o);
    image_.resize(static_cast<std::size_t>(o.registers));
  }
  int port() const { return server_->port(); }
  void show(const gcode::AxisValues& q) {
    protocol::ModbusSample s;
    s.joints = q;
    s.tool = 1;
    s.spindle_on = true;
    s.line = 0;
    protocol::encodeSample(map_, s, image_);
    server_->setRegisters(image_);
  }

 private:
  protocol::ModbusMap map_;
  std::unique_ptr<daemon::ModbusServer> server_;
  std::vector<std::uint16_t> image_;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * (v.size() - 1) + 0.5))];
}

void baseline(const protocol::Job& job, double seconds) {
  protocol::ModbusMap map = protocol::defaultModbusMap(*job.machine);
  Controller controller(map);
  controller.show(job.machine->home);
  map.port = controller.port();
  protocol::ModbusTcpClient client(map);
  std::vector<double> us;
  const auto start = Clock::now();
  auto t = start;
  while (t - start < std::chrono::duration<double>(seconds)) {
    client.read();
    const auto next = Clock::now();
    us.push_back(std::chrono::duration<double, std::micro>(next - t).count());
    t = next;
  }
  const double s = std::chrono::duration<double>(t - start).count();
  std::printf(
      "baseline: bare ModbusTcpClient::read, 5 joints, back to back: %.0f polls/s "
      "(median %.1f us, p99 %.1f us)\n",
      us.size() / s, percentile(us, 0.5), percentile(us, 0.99));
}

void carving(const protocol::Job& job, double seconds) {
  const kin::Kinematics kin(*job.machine);
  shadow::ShadowSpec spec;
  spec.job = job;
  spec.map = protocol::defaultModbusMap(*job.machine);
  spec.map.poll_hz = 1000;
  Controller controller(spec.map);
  spec.map.port = controller.port();
  const glm::dvec3 centre{0, 0, -1};
  constexpr double kRadius = 15.0, kFeed = 2000.0;  // mm, mm/min
  const double omega = kFeed / 60.0 / kRadius;      // rad/s
  controller.show(jointsAt(kin, centre + glm::dvec3(kRadius, 0, 0), 0, 0));
  shadow::ShadowSession session("bench", spec);
  const double full = session.stockVolume();
  session.start();
  std::atomic<bool> stop{false};
  std::thread publisher([&] {
    const auto t0 = Clock::now();
    while (!stop) {
      const double t = std::chrono::duration<double>(Clock::now() - t0).count();
      const glm::dvec3 tip =
          centre + kRadius * glm::dvec3(std::cos(omega * t), std::sin(omega * t), 0);
      controller.show(jointsAt(kin, tip, 0, 10.0 * std::sin(t)));
      std::this_thread::sleep_for(1ms);
    }
  });
  std::this_thread::sleep_for(200ms);  // connected, carving
  const shadow::ShadowCounters before = session.counters();
  const auto t0 = Clock::now();
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  const shadow::ShadowCounters after = session.counters();
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  const nlohmann::json status = session.status();
  stop = true;
  publisher.join();
  const bool idle = session.waitIdle(30s);
  const double removed = full - session.stockVolume();
  session.stop();
  const double rate = (after.polls_ok - before.polls_ok) / s;
  std::printf(
      "shadow: poll_hz 1000, 5 joints, carving a %.0f mm circle 1 mm deep at %.0f mm/min "
      "(density %.0f): %.0f polls/s (%.1f %% of 1000), %.0f motions/s cut, %llu samples merged, "
      "carve backlog max %llu samples, %llu pending at the end, last carve lag %.2f ms, "
      "failed polls %llu, %s; removed %.1f mm3\n",
      2 * kRadius, kFeed, job.options.density, rate, rate / 10.0,
      (after.motions - before.motions) / s,
      static_cast<unsigned long long>(after.merged - before.merged),
      static_cast<unsigned long long>(after.max_backlog),
      static_cast<unsigned long long>(status["carving"]["pending"].get<std::uint64_t>()),
      after.carve_lag_ms, static_cast<unsigned long long>(after.polls_failed - before.polls_failed),
      idle ? "caught up" : "NOT caught up within 30 s", removed);
}

// One kind of contact for the latency loop: the poses shown before the change (a
// few ms each, each a motion that ends any contact), the pose that makes the
// contact, and the poses after it.
struct Cycle {
  const char* name;
  std::vector<gcode::AxisValues> before;
  gcode::AxisValues contact;
  std::vector<gcode::AxisValues> after;
};

void latency(const protocol::Job& job, const std::vector<Cycle>& kinds, int cycles) {
  const kin::Kinematics kin(*job.machine);
  const auto dir =
      std::filesystem::temp_directory_path() / ("mdhd-bench-shadow-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  service::ServiceConfig config;
  config.port = 0;
  config.data_dir = (dir / "data").string();
  config.log_file = (dir / "log.jsonl").string();
  config.workers = 1;
  service::Service service(config);
  service.start();
  httplib::Client http("127.0.0.1", service.port());
  http.set_tcp_nodelay(true);

  for (const Cycle& kind : kinds) {
    protocol::ModbusMap map = protocol::defaultModbusMap(*job.machine);
    map.poll_hz = 1000;
    Controller controller(map);
    map.port = controller.port();
    controller.show(kind.before.front());
    nlohmann::json request = {
        {"machine", protocol::machineToJson(*job.machine)},
        {"tools",
         {{{"number", 1},
           {"shape", "flat"},
           {"diameter", 6},
           {"flute_length", 12},
           {"length", kToolLength},
           {"shank_diameter", 6},
           {"holder", {{{"diameter", 30}, {"length", 20}}}}}}},
        {"stock", {{"box", {{"min", {-30, -30, -20}}, {"max", {30, 30, 0}}}}}},
        {"fixtures", {{{"box", {{"min", {40, -10, -20}}, {"max", {60, 10, 10}}}}}}},
        {"options", {{"density", job.options.density}}},
        {"modbus", protocol::modbusMapToJson(map)}};
    const auto posted = http.Post("/api/v1/shadows", request.dump(), "application/json");
    if (!posted || posted->status != 201) {
      std::printf("latency: POST failed: %s\n", posted ? posted->body.c_str() : "no reply");
      return;
    }
    const std::string id = nlohmann::json::parse(posted->body)["id"];
    shadow::testing::SseReader events(service.port(), "/api/v1/shadows/" + id + "/events");
    // Shows a pose and waits until the shadow has polled and cut it (outside the
    // timed part: a missed pose would leave the last contact open).
    const auto showAndWait = [&](const gcode::AxisValues& q) {
      controller.show(q);
      const auto deadline = Clock::now() + 2s;
      while (Clock::now() < deadline) {
        const auto r = http.Get(("/api/v1/shadows/" + id).c_str());
        if (r && r->status == 200) {
          const nlohmann::json s = nlohmann::json::parse(r->body);
          bool there = s["carving"]["pending"] == 0;
          for (const kin::Joint& j : job.machine->joints)
            there = there && std::abs(s["joints"][j.name].get<double>() -
                                      q[*kin::axisOfName(j.name)]) < 1e-3;
          if (there) return;
        }
        std::this_thread::sleep_for(1ms);
      }
    };
    std::vector<double> ms;
    for (int i = 0; i < cycles; ++i) {
      for (const gcode::AxisValues& q : kind.before) showAndWait(q);
      const auto t0 = Clock::now();
      controller.show(kind.contact);
      const auto alarm = events.waitNth("alarm", ms.size() + 1, 2s);
      if (!alarm) {
        std::printf("latency: no alarm within 2 s in cycle %d\n", i);
        break;
      }
      ms.push_back(std::chrono::duration<double, std::milli>(alarm->at - t0).count());
      for (const gcode::AxisValues& q : kind.after) showAndWait(q);
    }
    http.Delete(("/api/v1/shadows/" + id).c_str());
    std::printf(
        "latency register change -> SSE alarm (%s, poll_hz 1000, density %.0f), %zu cycles: "
        "median %.2f ms, p99 %.2f ms, min %.2f ms, max %.2f ms\n",
        kind.name, job.options.density, ms.size(), percentile(ms, 0.5), percentile(ms, 0.99),
        percentile(ms, 0.0), percentile(ms, 1.0));
  }
  service.stop();
  std::filesystem::remove_all(dir);
}

// The engine's share of the latency: the contact motion alone through
// check::Simulation::machineMotion (same cell, same motions as the cycle), timed.
void engineTime(const protocol::Job& job, const Cycle& kind, int cycles) {
  const kin::Kinematics kin(*job.machine);
  shadow::ShadowCarver carver(job, kin, nullptr);
  std::vector<double> ms;
  int t = 0;
  const auto sample = [&](const gcode::AxisValues& q) {
    shadow::PollSample s;
    s.t = Clock::time_point{} + std::chrono::milliseconds(t += 5);
    s.joints = q;
    s.tool = 1;
    s.spindle_on = true;
    return s;
  };
  // When the carver hears the contact (what the shadow publishes at once).
  std::vector<double> heard_ms;
  Clock::time_point t0;
  carver.setAlarmListener([&](const check::Collision&, std::size_t) {
    heard_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  });
  for (int i = 0; i < cycles; ++i) {
    for (const gcode::AxisValues& q : kind.before) carver.carve(std::vector{sample(q)});
    t0 = Clock::now();
    const shadow::CarveResult r = carver.carve(std::vector{sample(kind.contact)});
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    if (r.alarms.size() != 1)
      std::printf("engine: cycle %d raised %zu alarms\n", i, r.alarms.size());
    for (const gcode::AxisValues& q : kind.after) carver.carve(std::vector{sample(q)});
  }
  std::printf(
      "  the contact motion alone in the engine (%s, ShadowCarver::carve): contact heard after "
      "median %.2f ms (p99 %.2f ms), whole motion median %.2f ms (p99 %.2f ms)\n",
      kind.name, percentile(heard_ms, 0.5), percentile(heard_ms, 0.99), percentile(ms, 0.5),
      percentile(ms, 0.99));
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  const Args args = parse(argc, argv);
  const protocol::Job job = cell();
  if (!args.engine_only) {
    baseline(job, args.baseline_seconds);
    carving(job, args.seconds);
  }
  const kin::Kinematics kin(*job.machine);
  const auto at = [&](double x, double y, double z) { return jointsAt(kin, {x, y, z}, 0, 0); };
  const std::vector<Cycle> kinds = {
      // The shank into the stock: down a hole below the flutes, then sideways.
      {"shank_contact, stock",
       {at(-20, 0, 5), at(-20, 0, -15)},
       at(-15, 0, -15),
       {at(-20, 0, -15), at(-20, 0, 5)}},
      // The cutter into the clamp beside the stock.
      {"fixture_contact", {at(50, -20, 20), at(50, -15, 20)}, at(50, 0, 8), {}}};
  if (!args.engine_only) latency(job, kinds, args.cycles);
  for (const Cycle& kind : kinds) engineTime(job, kind, std::max(3, args.cycles / 4));
  return 0;
}
