// DXF import through dxflib: entities to B-splines in mm (see docs/user-guide.md, "Import").
#ifndef HOST_LIB_DRAWING_DXF_IMPORT_H
#define HOST_LIB_DRAWING_DXF_IMPORT_H

#include <string>  // std::string

#include "host/lib/drawing/drawing.h"

namespace host {

// Reads an ASCII DXF file. Throws ImportError naming the file, the entity and the problem.
// progress (when given): the bytes checked, then the bytes read.
Drawing import_dxf(const std::string& path, const WorkProgress& progress = nullptr);

// The same for the file's bytes already in memory; `path` names it in messages.
Drawing import_dxf_text(const std::string& text, const std::string& path);
// The same, reporting progress (not an overload: the fuzz target takes import_dxf_text by name).
Drawing import_dxf_text_reporting(const std::string& text, const std::string& path,
                                  const WorkProgress& progress);

}  // namespace host

#endif  // HOST_LIB_DRAWING_DXF_IMPORT_H
