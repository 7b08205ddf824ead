// The last probe's result (#T), kept since power-up: what it found (0 none yet, 1 contact,
// 2 no contact), how many descents ended, and where. Background loop only.
#ifndef FIRMWARE_APP_PROBE_RECORD_H
#define FIRMWARE_APP_PROBE_RECORD_H

#include <stdint.h>  // int32_t, uint8_t, uint16_t
#include <string.h>  // memcpy, memset

#include "firmware/config/machine_config.h"  // kAxisCount
#include "firmware/protocol/messages.h"      // ProbeResultReply

namespace app {

class ProbeRecord {
 public:
  ProbeRecord() : result_(0), count_(0) { memset(at_um_, 0, sizeof at_um_); }
  void note(uint8_t result, const int32_t at_um[config::kAxisCount]) {
    result_ = result;
    count_ = (uint16_t)(count_ + 1U);
    memcpy(at_um_, at_um, sizeof at_um_);
  }
  int32_t z_um() const { return at_um_[config::kAxisZ]; }
  void fill(proto::ProbeResultReply* r) const {
    r->result = result_;
    r->probe_count = count_;
    r->x_um = at_um_[0];
    r->y_um = at_um_[1];
    r->z_um = at_um_[2];
  }

 private:
  uint8_t result_;
  uint16_t count_;
  int32_t at_um_[config::kAxisCount];
};

}  // namespace app

#endif  // FIRMWARE_APP_PROBE_RECORD_H
