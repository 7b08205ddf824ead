// The local side of the lease: epoch and how long it stands by the steady clock.
#include "host/lib/server/server_lease.h"

#include <fmt/format.h>  // fmt::format

namespace host::server {

using Clock = std::chrono::steady_clock;

namespace {

// Lapses a quarter of stale_after before others may take the server for dead: room for a
// slow renewal and for the clocks' rates to differ.
Clock::time_point lapse_time(Clock::time_point asked, std::chrono::milliseconds stale_after) {
  return asked + stale_after - stale_after / 4;
}

}  // namespace

ServerLease::ServerLease(JobStore& store, std::string owner, std::string holder,
                         std::chrono::milliseconds stale_after)
    : store_(store),
      owner_(std::move(owner)),
      holder_(std::move(holder)),
      stale_after_(stale_after) {}

Lease ServerLease::acquire() {
  const Clock::time_point asked = Clock::now();
  const Lease lease = store_.acquire_lease(owner_, holder_, stale_after_.count());
  valid_until_ = lapse_time(asked, stale_after_).time_since_epoch().count();
  epoch_ = lease.epoch;
  return lease;
}

ServerLease::Renewal ServerLease::renew() {
  const int64_t epoch = epoch_;
  if (epoch == 0) return Renewal::kLost;
  const Clock::time_point asked = Clock::now();
  try {
    if (!store_.renew_lease(Lease{owner_, epoch})) {
      int64_t expected = epoch;
      epoch_.compare_exchange_strong(expected, 0);  // unless acquire() took a new one meanwhile
      return Renewal::kLost;
    }
  } catch (const StoreError&) {
    return Renewal::kStoreAway;
  }
  if (epoch_ == epoch) valid_until_ = lapse_time(asked, stale_after_).time_since_epoch().count();
  return Renewal::kRenewed;
}

std::string ServerLease::why_not(int64_t epoch) const {
  const int64_t now_epoch = epoch_;
  if (now_epoch == 0 || now_epoch != epoch) {
    return fmt::format(
        "server '{}' lost its lease (epoch {}): another server took it for dead and "
        "interrupted its jobs; nothing more is sent under it",
        owner_, epoch);
  }
  if (Clock::now().time_since_epoch().count() > valid_until_) {
    return fmt::format(
        "server '{}' could not renew its lease in time (database away or the server was "
        "stopped): nothing more is sent under it",
        owner_);
  }
  return "";
}

Lease ServerLease::current() const {
  return Lease{owner_, epoch_};
}

}  // namespace host::server
