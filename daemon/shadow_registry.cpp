#include "daemon/shadow_registry.h"

#include <random>

namespace mdhd::shadow {

std::string ShadowRegistry::newId() {
  static std::mutex m;
  static std::mt19937_64 rng{std::random_device{}()};
  std::lock_guard lock(m);
  const std::uint64_t v = rng();
  static const char* kHex = "0123456789abcdef";
  std::string id = "sh-";
  for (int i = 15; i >= 0; --i) id += kHex[(v >> (4 * i)) & 0xF];
  return id;
}

std::shared_ptr<ShadowSession> ShadowRegistry::add(std::unique_ptr<ShadowSession> session) {
  std::shared_ptr<ShadowSession> shared(std::move(session));
  {
    std::lock_guard lock(mutex_);
    if (closing_.load()) return nullptr;
    std::size_t live = 0;
    for (const auto& [id, s] : shadows_) live += s->state() != ShadowState::kStopped;
    if (live >= max_shadows_) return nullptr;
    shadows_[shared->id()] = shared;
  }
  shared->start();
  return shared;
}

std::shared_ptr<ShadowSession> ShadowRegistry::find(const std::string& id) const {
  std::lock_guard lock(mutex_);
  const auto it = shadows_.find(id);
  return it == shadows_.end() ? nullptr : it->second;
}

bool ShadowRegistry::remove(const std::string& id) {
  std::shared_ptr<ShadowSession> gone;
  {
    std::lock_guard lock(mutex_);
    const auto it = shadows_.find(id);
    if (it == shadows_.end()) return false;
    gone = std::move(it->second);
    shadows_.erase(it);
  }
  gone->stop();  // outside the lock: joins its threads
  return true;
}

std::vector<std::shared_ptr<ShadowSession>> ShadowRegistry::all() const {
  std::lock_guard lock(mutex_);
  std::vector<std::shared_ptr<ShadowSession>> out;
  for (const auto& [id, s] : shadows_) out.push_back(s);
  return out;
}

std::size_t ShadowRegistry::running() const {
  std::lock_guard lock(mutex_);
  std::size_t n = 0;
  for (const auto& [id, s] : shadows_) n += s->state() != ShadowState::kStopped;
  return n;
}

void ShadowRegistry::stopAll() {
  closing_ = true;
  for (const auto& s : all()) s->stop();
}

bool ShadowRegistry::openStream() {
  std::size_t n = streams_.load();
  do {
    if (n >= max_streams_) return false;
  } while (!streams_.compare_exchange_weak(n, n + 1));
  return true;
}

}  // namespace mdhd::shadow
