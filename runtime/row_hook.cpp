#include "runtime/row_hook.h"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <shared_mutex>
#include <unordered_map>
#include <vector>

namespace openplx::runtime::row_hook {

namespace {

// Registrations change rarely (attach, destroy) and are read at every step, from any thread.
std::shared_mutex registry_mutex;
std::unordered_map<const mjData*, std::vector<ConstraintRows*>>& registry() {
  static std::unordered_map<const mjData*, std::vector<ConstraintRows*>> rows;
  return rows;
}
std::atomic<mjfGeneric> chained{nullptr};  // the program's own callback, called first

void hook(const mjModel* m, mjData* d) {
  if (const mjfGeneric previous = chained.load(std::memory_order_acquire)) previous(m, d);
  const std::shared_lock lock(registry_mutex);
  auto it = registry().find(d);
  if (it == registry().end()) return;
  ConstraintRows::control(m, d, it->second.data(), it->second.size());
}

}  // namespace

void attach(const mjData* d, ConstraintRows* rows) {
  const std::unique_lock lock(registry_mutex);
  if (mjcb_control != hook) {
    chained.store(mjcb_control, std::memory_order_release);
    mjcb_control = hook;
  }
  registry()[d].push_back(rows);
}

void detach(const mjData* d, ConstraintRows* rows) {
  const std::unique_lock lock(registry_mutex);
  auto it = registry().find(d);
  if (it == registry().end()) return;
  std::vector<ConstraintRows*>& list = it->second;
  list.erase(std::remove(list.begin(), list.end(), rows), list.end());
  if (list.empty()) registry().erase(it);
}

bool installed() {
  return mjcb_control == hook;
}

}  // namespace openplx::runtime::row_hook
