// The "job FILE" scenario: a drawing planned and streamed to the simulated machine, its
// TMC428 datagrams recorded (host_spi internal; built only with host/lib/sim).
#ifndef HOST_SPI_SCENARIO_JOB_H
#define HOST_SPI_SCENARIO_JOB_H

#include <cstddef>  // size_t
#include <string>   // std::string
#include <vector>   // std::vector

#include "hal/fake/spi/spi_record.h"  // fake::SpiRecord, fake::SpiTiming
#include "host/spi/capture.h"         // Error

namespace host::spi {

// Records the init and then at most max_after_init datagrams of the job (0 = the whole
// job). *note says where the recording stopped. Errors: E_OPEN, E_SCENARIO.
Error record_job(const std::string& drawing_path, size_t max_after_init,
                 std::vector<fake::SpiRecord>* out, fake::SpiTiming* timing, std::string* note);

}  // namespace host::spi

#endif  // HOST_SPI_SCENARIO_JOB_H
