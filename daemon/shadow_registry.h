#pragma once
// The service's live shadows by id, with the caps that keep them from eating the
// daemon: how many shadows run at once and how many event streams are open
// (each open stream holds an HTTP thread). Shadows are live state in memory: a
// restart of the daemon ends them (docs/shadow.md).
#include <atomic>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "daemon/shadow_session.h"

namespace mdhd::shadow {

class ShadowRegistry {
 public:
  ShadowRegistry(std::size_t max_shadows, std::size_t max_streams)
      : max_shadows_(max_shadows), max_streams_(max_streams) {}
  ~ShadowRegistry() { stopAll(); }

  // Starts and registers a shadow under a new id; nullptr when max_shadows are
  // running (stopped ones do not count).
  std::shared_ptr<ShadowSession> add(std::unique_ptr<ShadowSession> session);
  // A new id for a session ("sh-" and 16 hex digits).
  static std::string newId();
  std::shared_ptr<ShadowSession> find(const std::string& id) const;
  // Forgets a shadow (stopping it); false when there is none of that id.
  bool remove(const std::string& id);
  std::vector<std::shared_ptr<ShadowSession>> all() const;
  std::size_t running() const;
  // Stops every shadow (their streams end) and refuses new ones: before the
  // HTTP server stops, so that no stream holds it up.
  void stopAll();
  bool closing() const { return closing_.load(); }

  // An event stream slot; false when max_streams are open.
  bool openStream();
  void closeStream() { --streams_; }
  std::size_t streams() const { return streams_.load(); }

 private:
  std::size_t max_shadows_;
  std::size_t max_streams_;
  mutable std::mutex mutex_;
  std::map<std::string, std::shared_ptr<ShadowSession>> shadows_;
  std::atomic<std::size_t> streams_{0};
  std::atomic<bool> closing_{false};
};

}  // namespace mdhd::shadow
