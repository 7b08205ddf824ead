// The files of one board read from memory into layers for plan_board: the server takes a
// board as several uploaded files (never paths), so the kind of each file comes from its
// name and content (pcb_file_names.h) and the readers see the text and the upload's name.
#ifndef HOST_LIB_PCB_BOARD_FILES_H
#define HOST_LIB_PCB_BOARD_FILES_H

#include <string>  // std::string
#include <vector>  // std::vector

#include "host/lib/pcb/board_job.h"
#include "host/lib/pcb/pcb_file_names.h"
#include "host/lib/pcb/pcb_layer.h"

namespace host::pcb {

// Gerber or Excellon from the file's name and first bytes; kNone for anything else.
PcbFileFormat board_file_format(const std::string& name, const std::string& text);

// What a file named or attributed as drill, whose content is Gerber, is told (OrCAD's .drd
// drill drawing): read_board_text reads no holes from it.
extern const char* const kGerberNotADrillFile;

// Reads one file. `kind` forces the layer kind (kUnknown: X2 TF.FileFunction, else the
// name). Throws PcbReadError with the reader's message (file and line), or "NAME: not a
// Gerber or Excellon file". Gerber content is never a drill layer: kind kDrill refuses it
// (kGerberNotADrillFile), a drill name or file function leaves it kUnknown with a warning.
PcbLayer read_board_text(const std::string& text, const std::string& name, LayerKind kind);
// The same from a file on disk (PcbReadError also when it cannot be read).
PcbLayer read_board_file(const std::string& path, LayerKind kind);

// The layers of one board by kind.
struct BoardFileSet {
  std::vector<PcbLayer> copper_top, copper_bottom, drill, outline;
  // Adds a read layer to its kind; false (nothing added) when its kind is kUnknown.
  bool add(PcbLayer layer);
  bool empty() const {
    return copper_top.empty() && copper_bottom.empty() && drill.empty() && outline.empty();
  }
  // The layers for plan_board; several drill files (plated, not plated) are merged into
  // *drill_storage. Throws PlanError when a copper or outline layer is given twice.
  BoardLayers layers(PcbLayer* drill_storage) const;
};

// A board's name from its files' names: their common start without trailing '-', '_', '.'
// ("blinky" from blinky-F.Cu.gbr and blinky.drl), else the first file's stem.
std::string board_name_from_files(const std::vector<std::string>& names);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_BOARD_FILES_H
