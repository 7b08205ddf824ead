// docs/protocol.md cannot drift from the message table: its command and reply tables (letter,
// name, kind, reply, fields with types and ranges, payload size) and the per-message field
// tables (offsets, names, types) must say what firmware/protocol/message_table.h declares.
#include <gtest/gtest.h>

#include <algorithm>  // std::min
#include <fstream>    // std::ifstream
#include <map>        // std::map
#include <regex>      // std::regex
#include <set>        // std::set
#include <string>     // std::string
#include <vector>     // std::vector

#include "firmware/protocol/messages.h"

#ifndef ENGRAVER_SOURCE_DIR
#error "ENGRAVER_SOURCE_DIR must point at the repository top"
#endif

namespace {

struct FieldDecl {
  std::string name;
  std::string wire;  // as the document spells it: u8, u16, i32
  long min = 0, max = 0;
  int bytes = 0;      // fixed size; 0 for text and arrays
  int max_bytes = 0;  // text and arrays: the most they can add
};

struct MessageDecl {
  std::string type;
  char letter = 0;
  bool reply = false;
  std::string kind, name, reply_text;
  std::vector<FieldDecl> fields;
  proto::CommandRole role = proto::CommandRole::kUnknown;
  int min_bytes() const {
    int n = 0;
    for (const auto& f : fields) n += f.bytes;
    return n;
  }
  int max_bytes() const {
    int n = 0;
    for (const auto& f : fields) n += f.bytes + f.max_bytes;
    return std::min(n, static_cast<int>(proto::kMaxPayload));
  }
};

std::string doc_wire(const std::string& wire) {
  return wire == "u16" || wire == "i32" ? wire : "u8";
}
int wire_bytes(const std::string& wire) {
  if (wire == "none") return 0;  // a count kept in the struct, not on the wire
  return wire == "u16" ? 2 : wire == "i32" ? 4 : 1;
}

int element_bytes(const std::string& element) {
  if (element == "point") return proto::kControlPointBytes;
  if (element == "rest") return 1;
  return proto::kKnotBytes;
}

std::vector<MessageDecl> declared() {
  std::vector<MessageDecl> all;
#define KIND_kImmediate "immediate"
#define KIND_kRealtime "real-time"
#define KIND_kJobCommand "queued"
#define KIND_kSplineData "queued"
#define KIND_kJobMark "queued"
#define T_CMD(Type, name, letter, role, display, reply, handler, check) \
  all.push_back({#Type, letter, false, KIND_##role, display, reply, {}, proto::CommandRole::role});
#define T_REPLY(Type, name, letter, display, check) \
  all.push_back({#Type, letter, true, "", display, "", {}, proto::CommandRole::kUnknown});
#define T_FIELD(Type, wire, field, lo, hi) \
  all.back().fields.push_back({#field, doc_wire(#wire), lo, hi, wire_bytes(#wire), 0});
#define T_TEXT(Type, count, field, most) all.back().fields.push_back({#field, "", 0, 0, 0, most});
#define T_ARRAY(Type, count, field, element, most) \
  all.back().fields.push_back({#field, "", 0, 0, 0, most * element_bytes(#element)});
#define T_END(Type)
  PROTO_MESSAGE_TABLE(T_CMD, T_REPLY, T_FIELD, T_TEXT, T_ARRAY, T_END)
  return all;
}

std::vector<std::string> read_doc() {
  std::ifstream in(std::string(ENGRAVER_SOURCE_DIR) + "/docs/protocol.md");
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(' ');
  const size_t b = s.find_last_not_of(' ');
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

// Cells of a markdown table row ("\|" inside a cell is not a separator).
std::vector<std::string> cells(std::string row) {
  for (size_t at; (at = row.find("\\|")) != std::string::npos;) row.replace(at, 2, "\x01");
  std::vector<std::string> out;
  size_t start = row.find('|') + 1;
  for (size_t bar; (bar = row.find('|', start)) != std::string::npos; start = bar + 1) {
    out.push_back(trim(row.substr(start, bar - start)));
  }
  return out;
}

// The table rows after the heading line that starts with `heading`, until a blank line.
std::vector<std::vector<std::string>> table_after(const std::vector<std::string>& doc,
                                                  const std::string& heading) {
  std::vector<std::vector<std::string>> rows;
  size_t i = 0;
  while (i < doc.size() && doc[i].rfind(heading, 0) != 0) ++i;
  if (i == doc.size()) return rows;
  ++i;
  while (i < doc.size() && doc[i].rfind("|", 0) != 0) ++i;
  for (i += 2; i < doc.size() && doc[i].rfind("|", 0) == 0; ++i) rows.push_back(cells(doc[i]));
  return rows;
}

struct DocField {
  std::string name, wire;
  bool has_range = false;
  long min = 0, max = 0;
};

// `name type` pairs (with a following "A..B" range when there is one), in order.
std::vector<DocField> doc_fields(const std::string& text) {
  static const std::regex re("`([a-z_0-9]+) (u8|u16|i32)`( (-?[0-9]+)\\.\\.([0-9]+))?");
  std::vector<DocField> out;
  for (std::sregex_iterator it(text.begin(), text.end(), re), end; it != end; ++it) {
    DocField f;
    f.name = (*it)[1];
    f.wire = (*it)[2];
    if ((*it)[3].matched) {
      f.has_range = true;
      f.min = std::stol((*it)[4]);
      f.max = std::stol((*it)[5]);
    }
    out.push_back(f);
  }
  return out;
}

// "... — 10", "— 0..16", "— 4 + 10·nc + 4·nk ≤ 64": the payload's smallest and largest size.
bool doc_sizes(const std::string& text, int* min, int* max) {
  const size_t dash = text.rfind("—");
  if (dash == std::string::npos) return false;
  const std::string s = text.substr(dash);
  std::smatch m;
  if (!std::regex_search(s, m, std::regex("([0-9]+)"))) return false;
  *min = *max = std::stoi(m[1]);
  std::smatch r;
  if (std::regex_search(s, r, std::regex("^— ([0-9]+)\\.\\.([0-9]+)"))) *max = std::stoi(r[2]);
  const size_t le = s.find("≤");
  if (le != std::string::npos) *max = std::stoi(s.substr(le + std::string("≤").size()));
  return true;
}

const MessageDecl* find(const std::vector<MessageDecl>& all, char letter, bool reply) {
  for (const auto& m : all) {
    if (m.letter == letter && m.reply == reply) return &m;
  }
  return nullptr;
}

// The fixed-size fields, in wire order (what the document names with `name type`).
std::vector<const FieldDecl*> scalar_fields(const MessageDecl& m) {
  std::vector<const FieldDecl*> out;
  for (const auto& f : m.fields) {
    if (f.bytes != 0) out.push_back(&f);
  }
  return out;
}

void expect_fields_match(const MessageDecl& m, const std::vector<DocField>& doc) {
  const auto declared = scalar_fields(m);
  ASSERT_EQ(doc.size(), declared.size()) << m.type << ": fields named in docs/protocol.md";
  for (size_t i = 0; i < doc.size(); ++i) {
    EXPECT_EQ(doc[i].name, declared[i]->name) << m.type << " field " << i;
    EXPECT_EQ(doc[i].wire, declared[i]->wire) << m.type << " " << doc[i].name;
    if (doc[i].has_range) {
      EXPECT_EQ(doc[i].min, declared[i]->min) << m.type << " " << doc[i].name;
      EXPECT_EQ(doc[i].max, declared[i]->max) << m.type << " " << doc[i].name;
    }
  }
}

void check_row_table(const MessageDecl& m, const std::vector<std::vector<std::string>>& rows,
                     const std::string& heading) {
  ASSERT_FALSE(rows.empty()) << "no table under " << heading;
  std::vector<DocField> doc;
  int offset = 0;
  const auto declared = scalar_fields(m);
  for (const auto& row : rows) {
    auto f = doc_fields(row[1]);
    if (f.size() != 1 || row[1] != "`" + f[0].name + " " + f[0].wire + "`") continue;
    std::smatch range;  // "1..3 ..." in the next cell
    if (row.size() > 2 &&
        std::regex_search(row[2], range, std::regex("^(-?[0-9]+)\\.\\.([0-9]+)"))) {
      f[0].has_range = true;
      f[0].min = std::stol(range[1]);
      f[0].max = std::stol(range[2]);
    }
    if (doc.size() < declared.size()) {
      EXPECT_EQ(std::stoi(row[0]), offset) << heading << " " << f[0].name << ": offset";
      offset += declared[doc.size()]->bytes;
    }
    doc.push_back(f[0]);
  }
  expect_fields_match(m, doc);
}

TEST(DocTable, CommandTableSaysWhatTheMessageTableDeclares) {
  const auto doc = read_doc();
  ASSERT_FALSE(doc.empty()) << "docs/protocol.md not found";
  const auto all = declared();
  const auto rows = table_after(doc, "## 2. Commands");
  std::set<char> documented;
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), 5u) << row[0];
    ASSERT_EQ(row[0].size(), 3u) << row[0];
    const char letter = row[0][1];
    documented.insert(letter);
    const MessageDecl* m = find(all, letter, false);
    ASSERT_NE(m, nullptr) << "docs/protocol.md lists #" << letter << ", the table does not";
    EXPECT_EQ(row[1], m->name) << "#" << letter;
    EXPECT_EQ(row[2], m->kind) << "#" << letter;
    EXPECT_EQ(row[4], m->reply_text) << "#" << letter;
    int min = -1, max = -1;
    ASSERT_TRUE(doc_sizes(row[3], &min, &max)) << "#" << letter << ": no '— size'";
    EXPECT_EQ(min, m->min_bytes()) << "#" << letter << " smallest payload";
    EXPECT_EQ(max, m->max_bytes()) << "#" << letter << " largest payload";
    if (row[3].find("see below") == std::string::npos) {
      expect_fields_match(*m, doc_fields(row[3]));
    }
  }
  for (const auto& m : all) {
    if (!m.reply) EXPECT_TRUE(documented.count(m.letter)) << m.type << " is not documented";
  }
}

TEST(DocTable, ReplyTableSaysWhatTheMessageTableDeclares) {
  const auto doc = read_doc();
  const auto all = declared();
  const auto rows = table_after(doc, "## 3. Replies");
  std::set<char> documented;
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), 4u) << row[0];
    const char letter = row[0][1];
    documented.insert(letter);
    const MessageDecl* m = find(all, letter, true);
    ASSERT_NE(m, nullptr) << "docs/protocol.md lists *" << letter << ", the table does not";
    EXPECT_EQ(row[1], m->name) << "*" << letter;
    int min = -1, max = -1;
    ASSERT_TRUE(doc_sizes(row[3], &min, &max)) << "*" << letter << ": no '— size'";
    EXPECT_EQ(min, m->min_bytes()) << "*" << letter;
    EXPECT_EQ(max, m->max_bytes()) << "*" << letter;
    if (row[3].find("below") == std::string::npos) expect_fields_match(*m, doc_fields(row[3]));
  }
  for (const auto& m : all) {
    if (m.reply) EXPECT_TRUE(documented.count(m.letter)) << m.type << " is not documented";
  }
}

TEST(DocTable, FieldTablesGiveEachFieldItsOffset) {
  const auto doc = read_doc();
  const auto all = declared();
  const std::map<std::string, std::pair<char, bool>> sections = {
      {"### `#B`", {'B', false}}, {"### `#D`", {'D', false}}, {"### `#K`", {'K', false}},
      {"### `#L`", {'L', false}}, {"### `*I`", {'I', true}},  {"### `*?`", {'?', true}},
      {"### `#Y`", {'Y', false}}, {"### `#T`", {'T', true}},  {"### `#A`", {'A', false}},
      {"### `#E`", {'E', false}}};
  for (const auto& s : sections) {
    const MessageDecl* m = find(all, s.second.first, s.second.second);
    ASSERT_NE(m, nullptr) << s.first;
    check_row_table(*m, table_after(doc, s.first), s.first);
  }
}

// The command letters ("#D", "`#H #R`") in doc between the end of `after` and the next
// `until`, as a set; "?" when `after` is not in the document.
std::set<char> doc_letters(const std::string& doc, const std::string& after,
                           const std::string& until) {
  const size_t a = doc.find(after);
  if (a == std::string::npos) return {'?'};
  const size_t from = a + after.size();
  const std::string text = doc.substr(from, doc.find(until, from) - from);
  static const std::regex re("#([A-Z?])");
  std::set<char> out;
  for (std::sregex_iterator it(text.begin(), text.end(), re), end; it != end; ++it) {
    out.insert((*it).str(1)[0]);
  }
  return out;
}

std::set<char> letters_of(const std::vector<MessageDecl>& all, proto::CommandRole role) {
  std::set<char> out;
  for (const auto& m : all) {
    if (!m.reply && m.role == role) out.insert(m.letter);
  }
  return out;
}

// The lists of docs/protocol.md that name commands by what they are (spline data, job
// commands, real-time frames) name exactly the commands of that role in the table.
TEST(DocTable, RoleListsNameTheTablesCommandsOfThatRole) {
  std::string doc;
  for (const auto& line : read_doc()) doc += trim(line) + " ";  // one line, as read
  const auto all = declared();
  const auto spline_data = letters_of(all, proto::CommandRole::kSplineData);
  const auto job_commands = letters_of(all, proto::CommandRole::kJobCommand);
  EXPECT_EQ(
      doc_letters(doc, "are the queued commands stored after a `#J`, except spline data (", ":"),
      spline_data);
  EXPECT_EQ(doc_letters(doc, "acknowledges a real-time frame (", ")"),
            letters_of(all, proto::CommandRole::kRealtime));
  EXPECT_EQ(doc_letters(doc, "`queue_free` counts command-queue slots; each ", " takes one"),
            job_commands);
  EXPECT_EQ(doc_letters(doc, "takes one (the job commands), ", " frames take none"), spline_data);
  EXPECT_EQ(doc_letters(doc, "the open spline), nor does ", " ("),
            letters_of(all, proto::CommandRole::kJobMark));
}

// command_role() and command_kind() say what the table's role column says.
TEST(DocTable, CommandRoleAndKindFollowTheRoleColumn) {
  for (const auto& m : declared()) {
    if (m.reply) continue;
    EXPECT_EQ(proto::command_role(static_cast<uint8_t>(m.letter)), m.role) << m.letter;
    const proto::FrameKind kind = proto::command_kind(static_cast<uint8_t>(m.letter));
    EXPECT_EQ(m.kind, kind == proto::FrameKind::kQueued     ? "queued"
                      : kind == proto::FrameKind::kRealtime ? "real-time"
                                                            : "immediate")
        << m.letter;
  }
  EXPECT_EQ(proto::command_role('a'), proto::CommandRole::kUnknown);
  EXPECT_EQ(proto::command_role('O'), proto::CommandRole::kUnknown);  // a reply letter only
}

// command_row() numbers the commands in table order (the codec's decode_command_row and the
// application's routes are indexed by it) and knows no other byte.
TEST(DocTable, CommandRowIsTheCommandsTableOrder) {
  std::set<uint8_t> letters;
  uint8_t row = 0;
  for (const auto& m : declared()) {
    if (m.reply) continue;
    EXPECT_EQ(proto::command_row(static_cast<uint8_t>(m.letter)), row) << m.letter;
    letters.insert(static_cast<uint8_t>(m.letter));
    ++row;
  }
  EXPECT_GT(row, 20);
  for (int b = 0; b < 256; ++b) {
    if (letters.count(static_cast<uint8_t>(b)) != 0) continue;
    EXPECT_EQ(proto::command_row(static_cast<uint8_t>(b)), proto::kNoCommandRow) << b;
  }
}

}  // namespace
