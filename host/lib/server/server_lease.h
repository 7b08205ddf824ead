// This server's lease on its name in the job store, kept by the workshop's heartbeat. Work
// goes on under a lease only while it is valid by the local clock: it lapses a margin before
// another server may take this one for dead (stale_after after its last renewal), so a server
// that was frozen or cut off from the database stops sending before its jobs can be handed to
// another machine; and once another server has revoked it, the store refuses every change made
// under it (JobStore: claim, save_progress, finish).
#ifndef HOST_LIB_SERVER_SERVER_LEASE_H
#define HOST_LIB_SERVER_SERVER_LEASE_H

#include <atomic>  // std::atomic
#include <chrono>  // std::chrono
#include <mutex>   // std::mutex
#include <string>  // std::string

#include "host/lib/server/job_store.h"

namespace host::server {

class ServerLease {
 public:
  // holder: who this server is (host and data folder), see JobStore::acquire_lease.
  ServerLease(JobStore& store, std::string owner, std::string holder,
              std::chrono::milliseconds stale_after);

  // Takes the name with a new epoch. Throws NameInUse (another live server has it) or
  // StoreError.
  Lease acquire();
  enum class Renewal { kRenewed, kLost, kStoreAway };
  // Renews the current lease: kLost when the store says it is gone (revoked), kStoreAway when
  // the store did not answer (the lease lapses locally if that lasts).
  Renewal renew();
  // Empty when work may go on under `epoch` now; otherwise why not (for the machine log).
  std::string why_not(int64_t epoch) const;
  bool valid(int64_t epoch) const { return why_not(epoch).empty(); }
  Lease current() const;

 private:
  JobStore& store_;
  const std::string owner_;
  const std::string holder_;
  const std::chrono::milliseconds stale_after_;
  std::atomic<int64_t> epoch_{0};  // 0: none held
  std::atomic<std::chrono::steady_clock::rep> valid_until_{0};
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_SERVER_LEASE_H
