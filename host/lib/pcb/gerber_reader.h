// Gerber RS-274X reader: the current spec with X2 attributes, aperture macros, regions,
// polarity and step-and-repeat, plus the deprecated forms real files carry (accepted with a
// note). Copper becomes non-overlapping Clipper polygons in nanometres; an outline layer
// keeps its strokes' centre lines.
#ifndef HOST_LIB_PCB_GERBER_READER_H
#define HOST_LIB_PCB_GERBER_READER_H

#include <string>  // std::string

#include "host/lib/pcb/pcb_layer.h"

namespace host::pcb {

struct GerberOptions {
  // Used when neither X2 TF.FileFunction nor the file name says what the layer is (the
  // command line's --layer).
  LayerKind kind_if_unknown = LayerKind::kUnknown;
  // The kind the user named (--top, --outline...): wins over X2 and the name (an explicit
  // option always does), and decides how the file is read (copper or outline strokes).
  LayerKind forced_kind = LayerKind::kUnknown;
  // Largest distance between a flattened arc or circle and the true curve (inscribed
  // polygons, so copper is at most this much smaller than drawn).
  double arc_tolerance_nm = 500;
  // Refuse an arc whose start and end radii differ by more than this (a centre rounded to
  // 3-decimal inches is up to 18 um off, and Protel boards show 53 um; beyond 0.1 mm the
  // file does not say where its copper is).
  // Small arcs may be off by up to half their start radius, at most 1 mm (gerbv reads such
  // files, e.g. its jj/l1-3.grb with 0.255 and 0.136 mm; the copper covers both readings).
  double max_arc_radius_mismatch_nm = 100000;
  // Refuse files whose copper needs more polygon vertices than this before the union (a
  // step-and-repeat of a large block can ask for any amount of memory).
  size_t max_vertices = 20000000;
  // Refuse files whose polarity changes make the reader re-clip more copper vertices than
  // this in all. Each change re-clips the copper it touches, so a step-and-repeat of
  // overlapping copies with clear objects costs the square of the copies (the default is
  // minutes of work; a real board with hundreds of clear objects on a pour needs a few
  // hundred million at most).
  size_t max_reclipped_vertices = 500000000;
};

// Reads a whole file. Throws PcbReadError naming the file, the line and the problem; never
// returns a partly read layer.
PcbLayer read_gerber_file(const std::string& path, const GerberOptions& options = {});

// The same for text already in memory; `path` is used in messages and for the layer kind.
PcbLayer read_gerber_text(const std::string& text, const std::string& path,
                          const GerberOptions& options = {});

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_GERBER_READER_H
