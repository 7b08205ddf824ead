// Which PCB file a path is, from its name and first bytes: the readers use it for the layer
// kind when the file does not say (no X2 TF.FileFunction), the CLI to pick a reader.
#ifndef HOST_LIB_PCB_PCB_FILE_NAMES_H
#define HOST_LIB_PCB_PCB_FILE_NAMES_H

#include <string>  // std::string

#include "host/lib/drawing/file_text.h"  // read_file_head
#include "host/lib/pcb/pcb_layer.h"

namespace host::pcb {

enum class PcbFileFormat { kNone, kGerber, kExcellon };

// Layer kind from the usual names: .GTL/.GBL/.GKO/.GM1/.GML/.CMP/.SOL, KiCad's -F.Cu/-B.Cu/
// -Edge.Cuts (also with '_'), .DRL/.XLN. kUnknown when the name says nothing.
LayerKind layer_kind_from_file_name(const std::string& path);

// Layer kind from the value of an X2 file function, the fields after "TF.FileFunction,":
// Copper,L1,Top / Copper,L2,Bot / Profile / Plated / NonPlated; kUnknown for any other
// (inner copper, silkscreen, mask, paste).
LayerKind layer_kind_from_file_function(const std::string& value);

// The value of a Gerber text's X2 file function ("Copper,L1,Top"), as the reader takes it:
// the body of a "%TF.FileFunction,...*%" block or of KiCad 5's "G04 #@! TF.FileFunction,...*"
// comment, each where a block starts (a mention inside another comment is none); "" when
// there is none or the text ends before its '*'.
std::string x2_file_function(const std::string& text);

// Layer kind from the X2 file function in the head of a Gerber file; kUnknown when there is
// none or it names no layer this machine cuts.
LayerKind layer_kind_from_x2(const std::string& head_text);

// What a Gerber file is when it is a layer no job cuts: from the X2 file function in its
// head ("silkscreen", "solder mask", "paste", "inner copper", "documentation"; "" when there
// is none or it names a layer that is cut), or from the words of its name or its extension
// (the same words but inner copper; whole words: "fabric.top.gbr" is copper).
std::string other_layer_from_x2(const std::string& head_text);
std::string other_layer_from_name(const std::string& path);

// The first few kB of `path` (empty if it cannot be opened): where formats and X2 file
// functions are found.
using host::read_file_head;

// Gerber or Excellon by extension, else by content (%FS / %MO, M48); kNone otherwise.
PcbFileFormat pcb_file_format(const std::string& path, const std::string& head_text);

// Reads the first few kB of `path` (empty if it cannot be opened) and calls the above.
PcbFileFormat pcb_file_format(const std::string& path);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_PCB_FILE_NAMES_H
