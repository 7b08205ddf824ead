// Excellon drill reader: M48 header (METRIC/INCH with LZ/TZ and a digit format, KiCad's
// ";FORMAT={...}" comment, FMAT), tool table (T1C0.8), G90/G91, G05 drilling, slots (G85 and
// routed G00/M15/G01/M16), M71/M72, M30. Holes and slots in nanometres, whatever the file's
// units, so an inch drill file lines up with millimetre Gerbers.
#ifndef HOST_LIB_PCB_EXCELLON_READER_H
#define HOST_LIB_PCB_EXCELLON_READER_H

#include <string>  // std::string

#include "host/lib/pcb/pcb_layer.h"

namespace host::pcb {

// Reads a whole file. Throws PcbReadError naming the file, the line and the problem; never
// returns a partly read layer.
PcbLayer read_excellon_file(const std::string& path);

// The same for text in memory; `path` is used in messages.
PcbLayer read_excellon_text(const std::string& text, const std::string& path);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_EXCELLON_READER_H
