#pragma once
// The service's Prometheus metrics (text exposition format 0.0.4): requests by
// route and status with a latency histogram, jobs by outcome with a duration
// histogram, simulated moves and simulation seconds (their ratio is the
// simulation rate), and gauges read at scrape time (queue depth, ...).
// Thread-safe.
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mdhd::service {

// Cumulative histogram over fixed upper bounds (seconds).
class Histogram {
 public:
  explicit Histogram(std::vector<double> bounds)
      : bounds_(std::move(bounds)), counts_(bounds_.size() + 1) {}
  void observe(double v);
  // Appends the _bucket/_sum/_count lines; `labels` is "" or `a="b",` ready to prefix.
  void render(std::string& out, const std::string& name, const std::string& labels) const;

 private:
  std::vector<double> bounds_;
  std::vector<std::uint64_t> counts_;
  double sum_ = 0.0;
  std::uint64_t count_ = 0;
};

class Metrics {
 public:
  Metrics();

  void countRequest(std::string_view route, std::string_view method, int status, double seconds);
  // A job left a worker: outcome is its final status (done, failed, cancelled,
  // requeued); `moves` the motions it simulated in `seconds`.
  void jobFinished(std::string_view outcome, double seconds, std::int64_t moves);
  // A value read at scrape time. `name` must be a Prometheus metric name.
  void addGauge(std::string name, std::string help, std::function<double()> read);
  // A counter of events others define (e.g. shadow alarms); creates it on first use.
  void addToCounter(const std::string& name, const std::string& help, double amount);

  std::string render() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::pair<std::string, std::string>, std::map<int, std::uint64_t>> requests_;
  Histogram requestSeconds_;
  std::map<std::string, std::uint64_t> jobs_;
  Histogram jobSeconds_;
  double simulatedMoves_ = 0.0;
  double simulationSeconds_ = 0.0;
  double lastMovesPerSecond_ = 0.0;
  struct Gauge {
    std::string name;
    std::string help;
    std::function<double()> read;
  };
  std::vector<Gauge> gauges_;
  std::map<std::string, std::pair<std::string, double>> counters_;
};

// `value` with \, " and newlines escaped for a label.
std::string escapeLabel(std::string_view value);

}  // namespace mdhd::service
