// A board's files read from memory (what the server does with uploads): format and kind from
// the name or the content, the reader's message naming the upload, the layers for the
// planner (drill files merged, a layer given twice refused) and the board's name.
#include "host/lib/pcb/board_files.h"
#include "host/lib/pcb/pcb_file_names.h"

#include <gtest/gtest.h>

#include <unistd.h>  // getpid

#include <algorithm>  // std::find
#include <cstdio>     // std::remove
#include <fstream>    // std::ifstream
#include <iterator>   // std::istreambuf_iterator
#include <string>     // std::to_string

#include "host_tests/host/pcb/test_data.h"

namespace host::pcb {
namespace {

std::string text_of(const std::string& name) {
  std::ifstream in(test::data_file(name), std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(BoardFiles, FormatAndKindComeFromTheNameOrTheContent) {
  const std::string outline = text_of("outline-Edge.Cuts.gbr");
  const std::string drill = text_of("metric_lz.drl");
  EXPECT_EQ(board_file_format("a.gbr", outline), PcbFileFormat::kGerber);
  EXPECT_EQ(board_file_format("no-extension", outline), PcbFileFormat::kGerber);  // %FS
  EXPECT_EQ(board_file_format("holes.txt", drill), PcbFileFormat::kExcellon);     // M48
  EXPECT_EQ(board_file_format("notes.txt", "Remember to buy milk.\n"), PcbFileFormat::kNone);
  // M48 heads an Excellon file (after comments); in G-code it is "enable overrides".
  EXPECT_EQ(board_file_format("holes.txt", "; made by hand\n\nM48\nMETRIC\n%\nM30\n"),
            PcbFileFormat::kExcellon);
  EXPECT_EQ(board_file_format("prog.txt", "G21\nM48\nG0 X1 Y1\nG1 X2\nM2\n"), PcbFileFormat::kNone);

  EXPECT_EQ(read_board_text(outline, "my-Edge.Cuts.gbr", LayerKind::kUnknown).kind,
            LayerKind::kOutline);
  // The name is only a name: no file of that name exists, the text is what is read.
  const PcbLayer d = read_board_text(drill, "holes.txt", LayerKind::kUnknown);
  EXPECT_EQ(d.kind, LayerKind::kDrill);
  EXPECT_EQ(d.holes.size(), 3u);
  EXPECT_EQ(d.path, "holes.txt");
  // A forced kind wins over the name (how the server re-reads its archive).
  EXPECT_EQ(read_board_text(outline, "x.gbr", LayerKind::kCopperBottom).kind,
            LayerKind::kCopperBottom);
}

// A board folder reads a Gerber with a name that says nothing when its X2 file function
// says copper, drill or outline (board_cli.cpp); the same mapping as the reader's.
// The broad name table: the copper names of DipTrace, gEDA/pcb, Allegro/OrCAD, PADS and
// FAB 3000 (each was left out of a board folder); their silkscreen and masks are not copper.
TEST(BoardFiles, CopperNamesOfManyEdaPrograms) {
  const std::pair<const char*, LayerKind> names[] = {
      {"board_Top.gbr", LayerKind::kCopperTop},        // DipTrace
      {"board_Bottom.gbr", LayerKind::kCopperBottom},  // DipTrace
      {"Top.gbr", LayerKind::kCopperTop},
      {"board.top.gbr", LayerKind::kCopperTop},  // gEDA/pcb
      {"board.bottom.gbr", LayerKind::kCopperBottom},
      {"TOP.art", LayerKind::kCopperTop},  // Allegro / OrCAD
      {"BOTTOM.art", LayerKind::kCopperBottom},
      {"art01.pho", LayerKind::kCopperTop},  // PADS: layer 1
      {"board.tl", LayerKind::kCopperTop},   // FAB 3000
      {"board.bl", LayerKind::kCopperBottom},
      {"board_TopSilk.gbr", LayerKind::kUnknown},
      {"SOLDERMASK_TOP.art", LayerKind::kUnknown},
      {"board.topmask.gbr", LayerKind::kUnknown},
      {"board.bottompaste.gbr", LayerKind::kUnknown},
  };
  for (const auto& [name, kind] : names) {
    EXPECT_EQ(layer_kind_from_file_name(name), kind) << name;
    EXPECT_EQ(pcb_file_format(name, ""), PcbFileFormat::kGerber) << name;
  }
}

// A layer no job cuts says what it is, by whole words of its name or its extension: a
// project named "fabric" or "MaskRom" is copper (outside tester 21: fabric.top.gbr was left
// out as documentation, so the folder had "no copper layer").
TEST(BoardFiles, OtherLayersAreToldByWholeWordsOfTheirNames) {
  const std::pair<const char*, const char*> others[] = {{"board-F_SilkS.gbr", "silkscreen"},
                                                        {"board-B_Mask.gbr", "solder mask"},
                                                        {"board-F_Paste.gbr", "paste"},
                                                        {"board-F_Fab.gbr", "documentation"},
                                                        {"board.gto", "silkscreen"},
                                                        {"board.gbs", "solder mask"},
                                                        {"board.gtp", "paste"},
                                                        {"board_TopSilk.gbr", "silkscreen"},
                                                        {"board.bottompaste.gbr", "paste"},
                                                        {"tStop.gbr", "solder mask"},
                                                        {"board-In1.Cu.gbr", "inner copper"},
                                                        {"board-In2_Cu.gbr", "inner copper"},
                                                        {"board.g2", "inner copper"},
                                                        {"board.gp1", "inner copper"},
                                                        {"fabric.top.gbr", ""},
                                                        {"MaskRom_F_Cu.gbr", ""},
                                                        {"document_Bottom.gbr", ""},
                                                        {"FABRIC_TOP.art", ""}};
  for (const auto& [name, says] : others) EXPECT_EQ(other_layer_from_name(name), says) << name;
  EXPECT_EQ(layer_kind_from_file_name("fabric.top.gbr"), LayerKind::kCopperTop);
  EXPECT_EQ(layer_kind_from_file_name("fabric_Top.gbr"), LayerKind::kCopperTop);
  EXPECT_EQ(layer_kind_from_file_name("MaskRom_F_Cu.gbr"), LayerKind::kCopperTop);
  EXPECT_EQ(layer_kind_from_file_name("document_Bottom.gbr"), LayerKind::kCopperBottom);
  EXPECT_EQ(layer_kind_from_file_name("FABRIC_TOP.art"), LayerKind::kCopperTop);
  // The X2 file function says it first, whatever the name.
  EXPECT_EQ(other_layer_from_x2("%TF.FileFunction,Legend,Top*%"), "silkscreen");
  EXPECT_EQ(other_layer_from_x2("%TF.FileFunction,Soldermask,Bot*%"), "solder mask");
  EXPECT_EQ(other_layer_from_x2("%TF.FileFunction,Paste,Top*%"), "paste");
  EXPECT_EQ(other_layer_from_x2("%TF.FileFunction,Copper,L2,Inr*%"), "inner copper");
  EXPECT_EQ(other_layer_from_x2("%TF.FileFunction,Copper,L1,Top*%"), "");
  EXPECT_EQ(other_layer_from_x2("%FSLAX46Y46*%\n"), "");
}

// A .drd is Excellon (EAGLE) unless its content is Gerber: OrCAD writes its drill drawing
// as a Gerber .drd (gerbv's orcad/rs232_cm.drd, refused as Excellon: "unknown command '*'").
TEST(BoardFiles, ADrdWhoseContentIsGerberIsReadAsGerber) {
  const std::string orcad =
      "*\nG04 Mass Parameters ***\n*\n%ICAS*%\n%MOIN*%\nG74*%FSLAN2X34Y34*%\n"
      "%ADD10C,.01*%\nD10*\nX0Y0D03*\nM02*\n";
  EXPECT_EQ(pcb_file_format("RS232.DRD", orcad), PcbFileFormat::kGerber);
  EXPECT_EQ(read_board_text(orcad, "RS232.DRD", LayerKind::kUnknown).polygons_nm.size(), 1u);
  EXPECT_EQ(pcb_file_format("board.drd", "%\nINCH,TZ\nM48\nT1C0.032\n%\nT1\nX10000Y5000\nM30\n"),
            PcbFileFormat::kExcellon);  // old EAGLE
  EXPECT_EQ(pcb_file_format("board.drd", "M48\n;FORMAT %FS-like comment\nINCH\n"),
            PcbFileFormat::kExcellon);
  // A Gerber's comments may fill the head before its format statement (outside tester 25).
  EXPECT_EQ(pcb_file_format("holes.drl", "G04 a long header*\nG04 more of it*\n"),
            PcbFileFormat::kGerber);
  EXPECT_EQ(pcb_file_format("holes.drl", "; made by hand\nM48\nMETRIC\n"),
            PcbFileFormat::kExcellon);
}

// Gerber content is a picture of the holes, never the holes: a .drd (or an X2 drill file
// function) holding Gerber is no drill layer (it was one with no holes: "0 holes (no drill
// file)" with the file taken as the drill file), and naming it the drill file is refused.
TEST(BoardFiles, AGerberDrdIsNoDrillLayer) {
  const std::string orcad =
      "*\n%ICAS*%\n%MOIN*%\nG74*%FSLAN2X34Y34*%\n%ADD10C,.01*%\nD10*\nX0Y0D03*\nM02*\n";
  const PcbLayer l = read_board_text(orcad, "RS232.DRD", LayerKind::kUnknown);
  EXPECT_EQ(l.kind, LayerKind::kUnknown);
  EXPECT_NE(std::find(l.notes.begin(), l.notes.end(),
                      "warning: holds Gerber, not Excellon: no drill file"),
            l.notes.end());
  BoardFileSet set;
  EXPECT_FALSE(set.add(l));
  EXPECT_TRUE(set.drill.empty());
  const std::string x2 = "%FSLAX46Y46*%\n%MOMM*%\n%TF.FileFunction,Plated,1,2,PTH*%\nM02*\n";
  EXPECT_EQ(read_board_text(x2, "holes.gbr", LayerKind::kUnknown).kind, LayerKind::kUnknown);
  try {
    read_board_text(orcad, "RS232.DRD", LayerKind::kDrill);
    ADD_FAILURE() << "a Gerber file read as the drill file";
  } catch (const PcbReadError& e) {
    EXPECT_STREQ(e.what(), "RS232.DRD: holds Gerber, not Excellon: no drill file");
  }
}

TEST(BoardFiles, KindFromTheX2FileFunctionInAFilesHead) {
  EXPECT_EQ(layer_kind_from_x2("%FSLAX46Y46*%\n%TF.FileFunction,Copper,L1,Top*%\n"),
            LayerKind::kCopperTop);
  EXPECT_EQ(layer_kind_from_x2("G04 #@! TF.FileFunction,Copper,L2,Bot,Signal*\n"),
            LayerKind::kCopperBottom);  // KiCad 5's comment form
  EXPECT_EQ(layer_kind_from_x2("%TF.FileFunction, Profile ,NP*%"), LayerKind::kOutline);
  EXPECT_EQ(layer_kind_from_x2("%TF.FileFunction,NonPlated,1,2,NPTH*%"), LayerKind::kDrill);
  EXPECT_EQ(layer_kind_from_x2("%TF.FileFunction,Copper,L2,Inr*%"), LayerKind::kUnknown);
  EXPECT_EQ(layer_kind_from_x2("%TF.FileFunction,Legend,Top*%"), LayerKind::kUnknown);
  EXPECT_EQ(layer_kind_from_x2("%TF.FileFunction,Copper,L1,To"), LayerKind::kUnknown);  // cut off
  EXPECT_EQ(layer_kind_from_x2("%FSLAX46Y46*%\n%MOMM*%\n"), LayerKind::kUnknown);
  // Only where a block starts, as the reader takes it: a mention inside a comment is none
  // (outside tester 25: "G04 see %TF.FileFunction,Legend,Top*" left a copper file out).
  EXPECT_EQ(x2_file_function("G04 see %TF.FileFunction,Legend,Top*\n"), "");
  EXPECT_EQ(x2_file_function("G04 a TF.FileFunction,Legend,Top note*\n"), "");
  EXPECT_EQ(x2_file_function("G04 see %TF.FileFunction,Legend*\n%TF.FileFunction,Profile,NP*%"),
            "Profile,NP");
  EXPECT_EQ(x2_file_function("D10*%TF.FileFunction,Copper,L1,Top*%"), "Copper,L1,Top");
  EXPECT_EQ(x2_file_function("%MOMM*%\r\n  %TF.FileFunction,Copper,L1,Top*%"), "Copper,L1,Top");
  EXPECT_EQ(x2_file_function("G04 #@!TF.FileFunction,Copper,L2,Bot*"), "Copper,L2,Bot");
  EXPECT_EQ(x2_file_function("G4 #@! TF.FileFunction,Copper,L2,Bot*"), "Copper,L2,Bot");
  EXPECT_EQ(x2_file_function("G04 x #@! TF.FileFunction,Copper,L2,Bot*"), "");
  // What the reader takes from the whole file, the head alone gives.
  const std::string x2 = text_of("x2_attributes.gbr");
  EXPECT_EQ(layer_kind_from_x2(x2.substr(0, 4096)),
            read_board_text(x2, "x.gbr", LayerKind::kUnknown).kind);
}

// A UTF-8 byte-order mark before either format (outside tester 25: "unexpected '\xEF'").
TEST(BoardFiles, AByteOrderMarkIsNoPartOfTheFile) {
  const std::string bom = "\xEF\xBB\xBF";
  const std::string gerber = "%FSLAX46Y46*%\n%MOMM*%\n%ADD10C,1*%\nD10*\nX0Y0D03*\nM02*\n";
  const std::string drill = "M48\nMETRIC\nT1C0.8\n%\nT1\nX1.0Y1.0\nX2.0Y1.0\nM30\n";
  EXPECT_EQ(read_board_text(bom + gerber, "a.gbr", LayerKind::kUnknown).polygons_nm.size(), 1u);
  EXPECT_EQ(read_board_text(bom + drill, "a.drl", LayerKind::kUnknown).holes.size(), 2u);
  EXPECT_EQ(pcb_file_format("holes.txt", bom + drill), PcbFileFormat::kExcellon);  // by content
  EXPECT_EQ(read_board_text(bom + drill, "holes.txt", LayerKind::kUnknown).holes.size(), 2u);
  // From a file too (what `info`, `board` and a folder read).
  const std::string path = testing::TempDir() + "/bom_" + std::to_string(getpid()) + ".gbr";
  std::ofstream(path, std::ios::binary) << bom << gerber;
  EXPECT_EQ(read_board_file(path, LayerKind::kUnknown).polygons_nm.size(), 1u);
  std::remove(path.c_str());
}

TEST(BoardFiles, ErrorsNameTheUploadAndTheLine) {
  try {
    read_board_text("%FSLAX33Y33*%\n%MOMM*%\nD42*\nM02*\n", "up-F.Cu.gbr", LayerKind::kUnknown);
    FAIL() << "an undefined aperture was accepted";
  } catch (const PcbReadError& e) {
    EXPECT_NE(std::string(e.what()).find("up-F.Cu.gbr:3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_board_text("hello\n", "notes.txt", LayerKind::kUnknown), PcbReadError);
}

TEST(BoardFiles, LayersMergeDrillFilesAndRefuseALayerGivenTwice) {
  BoardFileSet set;
  EXPECT_TRUE(set.empty());
  EXPECT_TRUE(set.add(read_board_text(text_of("metric_lz.drl"), "a-PTH.drl", LayerKind::kUnknown)));
  EXPECT_TRUE(set.add(read_board_text(text_of("inch_tz.drl"), "a-NPTH.drl", LayerKind::kUnknown)));
  PcbLayer other;  // kind unknown: not a layer of the board
  EXPECT_FALSE(set.add(other));
  PcbLayer drill;
  const BoardLayers l = set.layers(&drill);
  ASSERT_EQ(l.drill, &drill);
  EXPECT_EQ(drill.holes.size(), set.drill[0].holes.size() + set.drill[1].holes.size());
  EXPECT_EQ(drill.path, "a-PTH.drl + a-NPTH.drl");
  EXPECT_EQ(l.copper_top, nullptr);

  const std::string outline = text_of("outline-Edge.Cuts.gbr");
  set.add(read_board_text(outline, "one-Edge.Cuts.gbr", LayerKind::kUnknown));
  EXPECT_NE(set.layers(&drill).outline, nullptr);
  set.add(read_board_text(outline, "two-Edge.Cuts.gbr", LayerKind::kUnknown));
  try {
    set.layers(&drill);
    FAIL() << "two outlines were accepted";
  } catch (const PlanError& e) {
    EXPECT_NE(std::string(e.what()).find("two-Edge.Cuts.gbr"), std::string::npos) << e.what();
  }
}

TEST(BoardFiles, BoardNameIsTheFilesCommonStart) {
  EXPECT_EQ(board_name_from_files({"blinky-F.Cu.gbr", "blinky.drl", "blinky-Edge.Cuts.gbr"}),
            "blinky");
  EXPECT_EQ(board_name_from_files({"Gerber_TopLayer.GTL", "Gerber_Drill_PTH.DRL"}), "Gerber");
  EXPECT_EQ(board_name_from_files({"top.gbr", "holes.drl"}), "top");  // nothing in common
  EXPECT_EQ(board_name_from_files({"amp-F.Cu.gbr"}), "amp-F.Cu");
  EXPECT_EQ(board_name_from_files({}), "board");
}

}  // namespace
}  // namespace host::pcb
