// A machine of the workshop as given on the command line:
//   "tcp://192.168.1.50:10001 name=left work=297x210 tags=pen,brass"
// (the link address first, then key=value words).
#ifndef HOST_LIB_SERVER_MACHINE_SPEC_H
#define HOST_LIB_SERVER_MACHINE_SPEC_H

#include <stdexcept>  // std::invalid_argument
#include <string>     // std::string

#include "host/lib/server/job_record.h"

namespace host::server {

struct MachineSpec {
  std::string name;     // shown on the page and in the archive; default m1, m2, ...
  std::string address;  // tcp://HOST:PORT or serial:DEVICE[,BAUD]
  MachineFit fit;
};

// Throws std::invalid_argument naming the spec and the bad word. default_name is used when
// the spec has no name=.
MachineSpec parse_machine_spec(const std::string& spec, const std::string& default_name);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_MACHINE_SPEC_H
