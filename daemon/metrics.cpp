#include "daemon/metrics.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace mdhd::service {
namespace {

std::string number(double v) {
  if (std::isinf(v)) return v > 0 ? "+Inf" : "-Inf";
  if (std::isnan(v)) return "NaN";
  // The shortest text that reads back as v (0.0005, not 0.00050000000000000001).
  char buf[32];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

void header(std::string& out, const std::string& name, const char* type, const std::string& help) {
  out += "# HELP " + name + " " + help + "\n# TYPE " + name + " " + type + "\n";
}

}  // namespace

std::string escapeLabel(std::string_view value) {
  std::string out;
  for (char c : value) {
    if (c == '\\' || c == '"') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else {
      out += c;
    }
  }
  return out;
}

void Histogram::observe(double v) {
  std::size_t i = 0;
  while (i < bounds_.size() && v > bounds_[i]) ++i;
  ++counts_[i];
  sum_ += v;
  ++count_;
}

void Histogram::render(std::string& out, const std::string& name, const std::string& labels) const {
  std::uint64_t cumulative = 0;
  for (std::size_t i = 0; i <= bounds_.size(); ++i) {
    cumulative += counts_[i];
    const std::string le = i < bounds_.size() ? number(bounds_[i]) : "+Inf";
    out += name + "_bucket{" + labels + "le=\"" + le + "\"} " + std::to_string(cumulative) + "\n";
  }
  const std::string plain = labels.empty() ? "" : "{" + labels.substr(0, labels.size() - 1) + "}";
  out += name + "_sum" + plain + " " + number(sum_) + "\n";
  out += name + "_count" + plain + " " + std::to_string(count_) + "\n";
}

Metrics::Metrics()
    : requestSeconds_({0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.5, 1, 5}),
      jobSeconds_({0.1, 0.25, 0.5, 1, 2.5, 5, 10, 30, 60, 300, 1800}) {}

void Metrics::countRequest(std::string_view route, std::string_view method, int status,
                           double seconds) {
  // The method label is one of a fixed set: the method token is the client's, and
  // a series per token (`M00001XXX...`, up to the 64 KiB head) grew the registry
  // and every scrape without bound, before any token check.
  static constexpr std::string_view kMethods[] = {"GET",   "HEAD",    "POST",  "PUT",    "DELETE",
                                                  "PATCH", "OPTIONS", "TRACE", "CONNECT"};
  std::string_view label = "other";
  for (std::string_view m : kMethods) {
    if (method == m) label = m;
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  ++requests_[{std::string(route), std::string(label)}][status];
  requestSeconds_.observe(seconds);
}

void Metrics::jobFinished(std::string_view outcome, double seconds, std::int64_t moves) {
  const std::lock_guard<std::mutex> lock(mutex_);
  ++jobs_[std::string(outcome)];
  jobSeconds_.observe(seconds);
  simulatedMoves_ += static_cast<double>(moves);
  simulationSeconds_ += seconds;
  if (seconds > 0) lastMovesPerSecond_ = static_cast<double>(moves) / seconds;
}

void Metrics::addGauge(std::string name, std::string help, std::function<double()> read) {
  const std::lock_guard<std::mutex> lock(mutex_);
  gauges_.push_back({std::move(name), std::move(help), std::move(read)});
}

void Metrics::addToCounter(const std::string& name, const std::string& help, double amount) {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto& c = counters_[name];
  c.first = help;
  c.second += amount;
}

std::string Metrics::render() const {
  std::vector<std::pair<const Gauge*, double>> gaugeValues;
  {
    // Gauges read outside the lock: they may take locks of their own.
    std::vector<const Gauge*> gauges;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      for (const Gauge& g : gauges_) gauges.push_back(&g);
    }
    for (const Gauge* g : gauges) gaugeValues.emplace_back(g, g->read());
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  std::string out;
  header(out, "mdhd_http_requests_total", "counter", "HTTP requests by route, method and status.");
  for (const auto& [key, byStatus] : requests_) {
    for (const auto& [status, n] : byStatus) {
      out += "mdhd_http_requests_total{route=\"" + escapeLabel(key.first) + "\",method=\"" +
             escapeLabel(key.second) + "\",status=\"" + std::to_string(status) + "\"} " +
             std::to_string(n) + "\n";
    }
  }
  header(out, "mdhd_http_request_duration_seconds", "histogram",
         "Time from routing a request to its reply.");
  requestSeconds_.render(out, "mdhd_http_request_duration_seconds", "");
  header(out, "mdhd_jobs_finished_total", "counter",
         "Jobs that left a worker, by outcome (done, failed, cancelled, requeued).");
  for (const auto& [outcome, n] : jobs_) {
    out += "mdhd_jobs_finished_total{outcome=\"" + escapeLabel(outcome) + "\"} " +
           std::to_string(n) + "\n";
  }
  header(out, "mdhd_job_duration_seconds", "histogram", "Wall time of a job on a worker.");
  jobSeconds_.render(out, "mdhd_job_duration_seconds", "");
  header(out, "mdhd_simulated_moves_total", "counter", "Motions simulated by finished jobs.");
  out += "mdhd_simulated_moves_total " + number(simulatedMoves_) + "\n";
  header(out, "mdhd_simulation_seconds_total", "counter",
         "Worker seconds spent on jobs (moves_total / this = simulation rate).");
  out += "mdhd_simulation_seconds_total " + number(simulationSeconds_) + "\n";
  header(out, "mdhd_simulation_moves_per_second", "gauge", "Simulation rate of the last job.");
  out += "mdhd_simulation_moves_per_second " + number(lastMovesPerSecond_) + "\n";
  for (const auto& [g, value] : gaugeValues) {
    header(out, g->name, "gauge", g->help);
    out += g->name + " " + number(value) + "\n";
  }
  for (const auto& [name, c] : counters_) {
    header(out, name, "counter", c.first);
    out += name + " " + number(c.second) + "\n";
  }
  return out;
}

}  // namespace mdhd::service
