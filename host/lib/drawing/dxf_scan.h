// A syntax check of an ASCII DXF file before dxflib reads it: group codes are integers,
// numbers are finite, counts are sane, the file is complete. dxflib reports none of this.
#ifndef HOST_LIB_DRAWING_DXF_SCAN_H
#define HOST_LIB_DRAWING_DXF_SCAN_H

#include <string>  // std::string

namespace host {

// Throws ImportError naming the file, the line, the entity and the problem; returns
// normally when dxflib can safely be given the file.
void check_dxf_syntax(const std::string& path);

// True when the file starts like a DXF (ASCII or binary).
bool looks_like_dxf(const std::string& path);

}  // namespace host

#endif  // HOST_LIB_DRAWING_DXF_SCAN_H
