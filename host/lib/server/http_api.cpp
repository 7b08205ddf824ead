// HTTP routes of the workshop server (cpp-httplib).
#include "host/lib/server/http_api.h"

#include "host/lib/server/board_height_map.h"
#include "host/lib/server/bounded_http_server.h"
#include "host/lib/server/connection_threads.h"
#include "host/lib/server/job_planning.h"  // release_freed_memory
#include "host/lib/server/job_record_fields.h"
#include "host/lib/server/listen_check.h"
#include "host/lib/server/map_source.h"
#include "host/lib/server/run_archive.h"
#include "host/lib/server/upload_numbers.h"
#include "host/lib/stream/host_port.h"  // host_port_text: [::1]:8080

#include <fmt/format.h>  // fmt::format
#include <httplib.h>     // httplib::Server

#include <nlohmann/json.hpp>  // nlohmann::json

#include <netinet/in.h>  // sockaddr_in, ntohs
#include <sys/socket.h>  // listen, getsockname, getsockopt, setsockopt

#include <cctype>       // std::isalnum
#include <charconv>     // std::from_chars
#include <cmath>        // std::isfinite
#include <cstdlib>      // std::strtod
#include <fstream>      // std::ofstream
#include <functional>   // std::function
#include <iterator>     // std::distance
#include <regex>        // std::regex
#include <set>          // std::set
#include <string_view>  // std::string_view

namespace host::server {

namespace fs = std::filesystem;

namespace {

void send_json(httplib::Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  // Messages may quote bytes of a broken upload: invalid UTF-8 is replaced, never thrown.
  res.set_content(body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace),
                  "application/json");
}

// An HTTP token (RFC 9110 5.6.2): what a header's name may be.
bool is_token(const std::string& name) {
  if (name.empty()) return false;
  for (const char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) &&
        std::string_view("!#$%&'*+-.^_`|~").find(c) == std::string_view::npos)
      return false;
  }
  return true;
}

void send_error(httplib::Response& res, int status, const std::string& why) {
  send_json(res, status, {{"error", why}});
}

// Equal strings in time independent of where they differ (token comparison).
bool same_secret(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

// "Bearer TOKEN" in Authorization, or X-Token.
std::string token_of(const httplib::Request& req) {
  const std::string auth = req.get_header_value("Authorization");
  if (auth.rfind("Bearer ", 0) == 0) return auth.substr(7);
  return req.get_header_value("X-Token");
}

bool parse_int(const std::string& s, int64_t* out) {
  const char* end = s.data() + s.size();
  const auto r = std::from_chars(s.data(), end, *out);
  return !s.empty() && r.ec == std::errc() && r.ptr == end;
}

nlohmann::json job_json(const JobRecord& j) {
  return job_record_json(j);
}

// Every field an upload may carry (multipart parts or query parameters); others are refused:
// the file parts, the job record's upload fields (job_record_fields.h), a board's fields.
const char* const kFileFields[] = {"file", "name"};
// A board's (board_planning.h, BoardSettings): a drawing that gives one is refused.
const char* const kBoardFields[] = {
    "side",          "tool_width_mm",   "allow_narrow_gaps", "passes",          "clearing_tool_mm",
    "narrow_passes", "align_holes",     "align_diameter_mm", "align_depth_mm",  "align_measured",
    "probe_first",   "height_map_from", "height_map_flip",   "probe_spacing_mm"};

}  // namespace

std::vector<std::string> upload_field_names() {
  std::vector<std::string> names(std::begin(kFileFields), std::end(kFileFields));
  for (size_t i = 0; i < kJobFieldCount; ++i) {
    if (kJobFields[i].source == FieldSource::kUpload) names.push_back(kJobFields[i].json_key);
  }
  names.insert(names.end(), std::begin(kBoardFields), std::end(kBoardFields));
  return names;
}

namespace {

// A form's part headers and boundaries on top of its files (the limit is the files').
constexpr size_t kFormFramingBytes = 64 * 1024;

std::string unknown_upload_field(const std::string& key) {
  static const std::vector<std::string> kNames = upload_field_names();
  for (const std::string& f : kNames) {
    if (key == f) return "";
  }
  std::string known;
  for (const std::string& f : kNames) known += (known.empty() ? "" : ", ") + f;
  return fmt::format("unknown field '{}' (an upload takes {})", key, known);
}

// An upload's body as read: the form's fields in memory; its files, or a raw body, each in a
// file of a staging folder as it arrives (a 72 MB drawing was held four times at once), gone
// with the body.
struct UploadBody {
  explicit UploadBody(fs::path staging) : folder(std::move(staging)) {}
  ~UploadBody() {
    std::error_code ec;
    fs::remove_all(folder, ec);
  }
  UploadBody(const UploadBody&) = delete;
  UploadBody& operator=(const UploadBody&) = delete;

  // A new file for the next part (or the raw body): its path.
  fs::path new_file() {
    out.close();
    const fs::path path = folder / fmt::format("part{}", file_count++);
    out.open(path, std::ios::binary);
    return path;
  }
  bool write(const char* data, size_t n) {
    out.write(data, static_cast<std::streamsize>(n));
    return static_cast<bool>(out);
  }
  // Every byte on disk: true, or the disk refused them.
  bool close() {
    if (!out.is_open()) return true;
    out.close();
    return static_cast<bool>(out);
  }

  bool multipart = false;
  httplib::MultipartFormDataItems parts;  // a file part's content is in its file, not here
  std::vector<fs::path> files;            // per part: its file ("" for a field)
  fs::path raw;                           // a raw body's file
  const fs::path folder;
  std::ofstream out;
  size_t file_count = 0;
};

// The upload's fields: multipart form (file + fields) or a raw body with query parameters.
struct UploadFields {
  Submission sub;
  std::string error;
};

// The query's keys as sent, once per time given: httplib's params keep a repeated field once
// when its values are equal, and read "=1" as a field named "1".
std::vector<std::string> query_keys(const std::string& target) {
  std::vector<std::string> keys;
  const size_t mark = target.find('?');
  if (mark == std::string::npos) return keys;
  const std::string query = target.substr(mark + 1, target.find('#', mark) - mark - 1);
  for (size_t from = 0; from <= query.size();) {
    const size_t amp = std::min(query.find('&', from), query.size());
    const std::string pair = query.substr(from, amp - from);
    if (!pair.empty())
      keys.push_back(httplib::detail::decode_url(pair.substr(0, pair.find('=')), true));
    from = amp + 1;
  }
  return keys;
}

// Every field known and given once (only a form's `file` parts repeat: a board's files; a
// second value would silently win or lose), each in one place only: "" or why not.
std::string check_field_names(const httplib::Request& req, const UploadBody& body) {
  std::set<std::string> seen;
  std::string error;
  auto check = [&](const std::string& key, bool repeats) {
    if (!error.empty()) return;
    error = unknown_upload_field(key);
    if (error.empty() && !seen.insert(key).second && !repeats) {
      error = fmt::format("field '{}' given more than once", key);
    }
  };
  for (const std::string& key : query_keys(req.target)) {
    if (error.empty() && key.empty()) error = "a query field without a name (nothing before '=')";
    check(key, false);
    // Read from one place only: what is given in the other would be ignored.
    if (error.empty() && body.multipart) {
      error = fmt::format("field '{}' in the query of a form upload (give it as a part)", key);
    }
    if (error.empty() && key == "file") {
      error = "field 'file' in the query (a raw upload's body is the file; ?name=FILE_NAME)";
    }
  }
  size_t file_parts = 0;
  bool named = false;  // an empty field counts as not given
  for (const auto& p : body.parts) {
    check(p.name, p.name == "file");
    if (p.name == "file") ++file_parts;
    if (p.name == "name" && !p.content.empty()) named = true;
  }
  // A form's one file names the job by its file name: a `name` part would be ignored.
  if (error.empty() && file_parts == 1 && named) {
    error =
        "field 'name' in a form upload of one file (the job is named by the file part's file "
        "name; 'name' names a board given as several file parts)";
  }
  return error;
}

// A field's value from the form's part or the query ("" when not given; the page's form
// sends its empty fields too, and an empty field counts as not given).
class UploadValues {
 public:
  UploadValues(const httplib::Request& req, const UploadBody& body) : req_(req), body_(body) {}
  std::string get(const std::string& key) const {
    std::string out;
    if (body_.multipart) {
      for (const auto& p : body_.parts) {
        if (p.name == key) out = p.content;
      }
    } else if (req_.has_param(key)) {
      out = req_.get_param_value(key);
    }
    return out;
  }
  bool given(const std::string& key) const { return !get(key).empty(); }

 private:
  const httplib::Request& req_;
  const UploadBody& body_;
};

// The file or files: one `file` part, a board's several, or a raw body named by ?name=.
std::string read_files(const httplib::Request& req, const UploadBody& body,
                       const UploadValues& values, Submission* sub) {
  if (!body.multipart) {
    if (!req.has_param("name")) return "raw upload without ?name=FILE_NAME";
    sub->name = req.get_param_value("name");
    sub->content_file = body.raw;
    return "";
  }
  std::vector<size_t> files;
  for (size_t i = 0; i < body.parts.size(); ++i) {
    if (body.parts[i].name == "file") files.push_back(i);
  }
  if (files.empty()) return "multipart upload without a 'file' part";
  // Several "file" parts: the files of one board (copper, drill, outline), read (small).
  if (files.size() == 1) {
    sub->name = body.parts[files[0]].filename;
    sub->content_file = body.files[files[0]];
  } else {
    for (const size_t i : files) {
      sub->files.push_back(UploadFile{body.parts[i].filename, read_file(body.files[i])});
    }
    sub->name = values.get("name");  // the board's name; "" takes it from the files
  }
  return "";
}

// The job record's upload fields (priority, tag, the plan settings), from the field table;
// their ranges are checked at intake (an inbox job's too), priority's here as well.
std::string read_record_fields(const UploadValues& values, Submission* sub) {
  JobRecord record;
  record.priority = sub->priority;
  record.tag = sub->tag;
  record.settings = sub->settings;
  for (size_t i = 0; i < kJobFieldCount; ++i) {
    const JobField& f = kJobFields[i];
    const std::string text = values.get(f.json_key);
    if (f.source != FieldSource::kUpload || text.empty()) continue;
    void* at = f.member(record);
    int64_t whole = 0;
    if (f.type == FieldType::kText) {
      *static_cast<std::string*>(at) = text;
    } else if (f.type == FieldType::kDouble) {
      const std::string why = read_decimal_field(f.json_key, text, static_cast<double*>(at));
      if (!why.empty()) return why;
    } else {
      const std::string why = read_whole_field(f.json_key, text, &whole);
      if (!why.empty()) return why;
      if (!field_range_error(f, static_cast<double>(whole)).empty())
        return field_range_error(f, NAN);
      *static_cast<int*>(at) = static_cast<int>(whole);
    }
  }
  sub->priority = record.priority;
  sub->tag = record.tag;
  sub->settings = record.settings;
  sub->feed_given = values.given("feed_mm_s");
  sub->tol_given = values.given("tol_mm");
  sub->margin_given = values.given("margin_mm");
  return "";
}

// X1,Y1,X2,Y2 (mm) into `out`: "" or why not.
std::string read_align_measured(const std::string& text, std::vector<double>* out) {
  size_t from = 0;
  while (true) {
    const size_t comma = text.find(',', from);
    double v = 0;
    if (!read_decimal_field("", text.substr(from, comma - from), &v).empty()) {
      return fmt::format("align_measured '{}' is not X1,Y1,X2,Y2 (finite numbers, mm)", text);
    }
    out->push_back(v);
    if (comma == std::string::npos) return "";
    from = comma + 1;
  }
}

// A board's fields (their ranges are checked at intake, with the command line's).
std::string read_board_fields(const UploadValues& values, BoardSettings* board) {
  board->side = values.get("side");
  board->align_holes = values.get("align_holes");
  board->height_map_flip = values.get("height_map_flip");
  if (board->height_map_flip.empty()) board->height_map_flip = "table";
  for (const auto& [key, flag] :
       {std::pair<const char*, bool*>{"allow_narrow_gaps", &board->allow_narrow_gaps},
        {"probe_first", &board->probe_first}}) {
    const std::string text = values.get(key);
    const std::string why = text.empty() ? "" : read_flag_field(key, text, flag);
    if (!why.empty()) return why;
  }
  int64_t passes = board->passes, narrow = board->narrow_passes;
  for (const auto& [key, value] : {std::pair<const char*, int64_t*>{"passes", &passes},
                                   {"narrow_passes", &narrow},
                                   {"height_map_from", &board->height_map_from}}) {
    const std::string text = values.get(key);
    const std::string why = text.empty() ? "" : read_whole_field(key, text, value);
    if (!why.empty()) return why;
    if (!text.empty() && (*value < -1000000000 || *value > 1000000000)) {
      return fmt::format("{} '{}' is outside -1000000000 .. 1000000000", key, text);
    }
  }
  // Given, the id of a job that probed: 0 or less is none, not "no map" (leave it out).
  const std::string from = values.get("height_map_from");
  if (!from.empty() && board->height_map_from < 1) {
    return fmt::format(
        "height_map_from '{}' is not a job id (the id of a board job uploaded with "
        "probe_first=1; leave the field out to cut without a map)",
        from);
  }
  board->passes = static_cast<int>(passes);
  board->narrow_passes = static_cast<int>(narrow);
  const std::string measured = values.get("align_measured");
  if (!measured.empty()) {
    const std::string why = read_align_measured(measured, &board->align_measured_mm);
    if (!why.empty()) return why;
  }
  for (const auto& [key, value] :
       {std::pair<const char*, double*>{"tool_width_mm", &board->tool_width_mm},
        {"clearing_tool_mm", &board->clearing_tool_mm},
        {"align_diameter_mm", &board->align_diameter_mm},
        {"align_depth_mm", &board->align_depth_mm},
        {"probe_spacing_mm", &board->probe_spacing_mm}}) {
    const std::string text = values.get(key);
    const std::string why = text.empty() ? "" : read_decimal_field(key, text, value);
    if (!why.empty()) return why;
  }
  return "";
}

UploadFields upload_fields(const httplib::Request& req, const UploadBody& body) {
  UploadFields u;
  const UploadValues values(req, body);
  u.error = check_field_names(req, body);
  if (u.error.empty()) u.error = read_files(req, body, values, &u.sub);
  if (u.error.empty()) u.error = read_record_fields(values, &u.sub);
  if (!u.error.empty()) return u;
  for (const char* key : kBoardFields) {
    if (values.given(key)) u.sub.board_fields.push_back(key);
  }
  u.error = read_board_fields(values, &u.sub.board);
  return u;
}

// Why a body is not JSON, in plain words: where it goes wrong and what stands there.
std::string json_problem(const std::string& body, size_t byte) {
  if (body.find_first_not_of(" \t\r\n") == std::string::npos) return "the body is empty";
  if (byte > body.size()) return "the body ends before the JSON value does";
  const size_t at = byte == 0 ? 0 : byte - 1;  // nlohmann counts from 1
  std::string near = body.substr(at, 16);
  for (char& c : near) {
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';
  }
  return fmt::format("unexpected text at byte {}: '{}'", at + 1, near);
}

// The JSON object of a request body, or an error.
bool body_object(const httplib::Request& req, httplib::Response& res, nlohmann::json* out) {
  // The parser stops at a NUL byte; whatever follows it would be ignored, not refused.
  const size_t nul = req.body.find('\0');
  if (nul != std::string::npos) {
    send_error(res, 400, fmt::format("malformed JSON: a NUL byte at byte {}", nul + 1));
    return false;
  }
  // A key given twice would silently take its last value ({"action": "hold", "action":
  // "abort"}): refused, as for upload fields.
  std::set<std::string> keys;
  std::string twice;
  const auto note_key = [&](int depth, nlohmann::json::parse_event_t event, nlohmann::json& key) {
    if (event == nlohmann::json::parse_event_t::key && depth == 1 && twice.empty() &&
        !keys.insert(key.get<std::string>()).second) {
      twice = key.get<std::string>();
    }
    return true;
  };
  try {
    *out = nlohmann::json::parse(req.body, note_key);
  } catch (const nlohmann::json::parse_error& e) {
    send_error(res, 400, "malformed JSON: " + json_problem(req.body, e.byte));
    return false;
  } catch (const nlohmann::json::exception& e) {
    // A number beyond a double (1e400): the parser's out_of_range, without its tag.
    const std::string what = e.what();
    send_error(res, 400, "malformed JSON: " + what.substr(what.find(']') + 2));
    return false;
  }
  if (!out->is_object()) {
    send_error(res, 400, "expected a JSON object");
    return false;
  }
  if (!twice.empty()) {
    send_error(res, 400, fmt::format("key '{}' given more than once", twice));
    return false;
  }
  return true;
}

// The keys of `body` not among `known` (a misspelt "percnet" is refused, not ignored).
bool known_keys(const nlohmann::json& body, const std::vector<const char*>& known,
                httplib::Response& res) {
  for (const auto& item : body.items()) {
    bool ok = false;
    for (const char* k : known) ok = ok || item.key() == k;
    if (ok) continue;
    std::string list;
    for (const char* k : known) list += std::string(list.empty() ? "" : ", ") + k;
    send_error(res, 400, fmt::format("unknown key '{}' (this request takes {})", item.key(), list));
    return false;
  }
  return true;
}

// A job's request: POST /api/jobs/<id>/<what> with a JSON object of the known keys only.
// The handler gets the job's id and the body; a malformed body or an unknown key is answered
// 400 here.
using JobRequest = std::function<void(int64_t id, nlohmann::json& body, httplib::Response& res)>;
void post_job_request(httplib::Server& s, const char* what, std::vector<const char*> known,
                      JobRequest handler) {
  s.Post(fmt::format(R"(/api/jobs/(\d{{1,18}})/{})", what),
         [known, handler](const httplib::Request& req, httplib::Response& res) {
           const int64_t id = std::stoll(req.matches[1]);
           nlohmann::json body;
           if (!body_object(req, res, &body) || !known_keys(body, known, res)) return;
           handler(id, body, res);
         });
}

// A 409's words: the job's state, then why the request does not apply in it.
std::string refused_in_state(JobStore& store, int64_t id, const std::string& why) {
  const std::optional<JobRecord> job = store.get(id);
  if (!job) return fmt::format("no job {}", id);
  return fmt::format("job {} is {}: {}", id, state_name(job->state), why);
}

// The machine action a control request names (hold, resume, abort, probe_ready, override with
// its percent); false, with the error answered, for anything else.
bool machine_control(const std::string& action, const nlohmann::json& body, httplib::Response& res,
                     JobControl* c, int* percent) {
  if (action == "hold") {
    *c = JobControl::kHold;
  } else if (action == "resume") {
    *c = JobControl::kResume;
  } else if (action == "abort") {
    *c = JobControl::kAbort;
  } else if (action == "probe_ready") {
    *c = JobControl::kConfirmProbe;
  } else if (action == "override") {
    *c = JobControl::kOverride;
    if (!body.contains("percent") || !body["percent"].is_number_integer()) {
      send_error(res, 400, "override needs \"percent\": 10 .. 200");
      return false;
    }
    const int64_t p = body["percent"];
    if (p < 10 || p > 200) {
      send_error(res, 400, "percent must be 10 .. 200");
      return false;
    }
    *percent = static_cast<int>(p);
  } else {
    send_error(res, 400, "unknown action '" + action + "'");
    return false;
  }
  return true;
}

// The methods a known path answers ("" for a path the server does not have): a request with
// another method gets 405 naming them (Allow), not a 404 that says the path is unknown.
std::string allowed_methods(const std::string& path) {
  static const std::regex kGet(
      R"(/|/app\.js|/style\.css|/api/status|/api/events|/api/jobs/\d{1,18}(/path|/files/[a-z.]{1,24}|/runs/[1-9]\d{0,5}/[a-z.]{1,16})?)");
  static const std::regex kPost(R"(/api/jobs/\d{1,18}/(control|priority))");
  if (path == "/api/jobs") return "GET, HEAD, POST";
  if (std::regex_match(path, kGet)) return "GET, HEAD";
  if (std::regex_match(path, kPost)) return "POST";
  return "";
}

}  // namespace

HttpApi::HttpApi(JobStore& store, JobIntake& intake, Workshop& workshop, const DataFolder& data,
                 HttpOptions options)
    : store_(store),
      intake_(intake),
      workshop_(workshop),
      data_(data),
      options_(std::move(options)),
      hosts_(options_.address, options_.allowed_hosts),
      http_(std::make_unique<BoundedHttpServer>()) {
  // A thread per connection: an open page's event stream holds its thread for as long as
  // the page is open, and must not take one that a control request needs.
  http_->new_task_queue = [] { return new ConnectionThreads(); };
  // The listening socket, to widen its backlog once bound (see widen_backlog). Reusable
  // after a restart (SO_REUSEADDR), but not shared: httplib's default, SO_REUSEPORT, let a
  // second server bind a port one already listened on, and the two split its requests.
  http_->set_socket_options([this](int fd) {
    const int yes = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    listen_fd_ = fd;
  });
  // httplib answers 413 beyond this (having read the body: see route_checks).
  http_->set_payload_max_length(upload_limit_bytes());
  routes();
}

HttpApi::~HttpApi() {
  stop();
}

int HttpApi::bind() {
  int port = options_.port;
  if (port == 0) {
    port = http_->bind_to_any_port(options_.address);
  } else if (!http_->bind_to_port(options_.address, port)) {
    port = -1;
  }
  if (port <= 0) {
    throw std::runtime_error(cannot_listen_text(options_.address, options_.port));
  }
  widen_backlog(port);
  hosts_.set_port(port);
  return port;
}

// Debian's libcpp-httplib listens with a backlog of 5, built in: a burst of connections
// (pages opening, a script) overflowed it, and each connection past it waited for the
// client's SYN retry a second later. listen() again on the bound socket sets a new backlog.
void HttpApi::widen_backlog(int port) {
  const int fd = listen_fd_;
  sockaddr_storage a{};
  socklen_t n = sizeof a;
  int listening = 0;
  socklen_t m = sizeof listening;
  if (fd < 0 || ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n) != 0 ||
      ::getsockopt(fd, SOL_SOCKET, SO_ACCEPTCONN, &listening, &m) != 0 || !listening) {
    return;
  }
  // Only the socket httplib bound for us: a listener on `port`.
  const int bound = a.ss_family == AF_INET ? ntohs(reinterpret_cast<const sockaddr_in&>(a).sin_port)
                    : a.ss_family == AF_INET6
                        ? ntohs(reinterpret_cast<const sockaddr_in6&>(a).sin6_port)
                        : -1;
  if (bound == port) ::listen(fd, kListenBacklog);
}

void HttpApi::run() {
  http_->listen_after_bind();
}

void HttpApi::stop() {
  stopping_ = true;
  http_->stop();
}

std::string HttpApi::event_text(uint64_t version) {
  std::lock_guard<std::mutex> lock(event_mutex_);
  // Every open page waits for the same change: one snapshot serves them all.
  if (event_version_ != version || event_.empty()) {
    event_ = "data: " +
             workshop_.snapshot().dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) +
             "\n\n";
    event_version_ = version;
  }
  return event_;
}

nlohmann::json HttpApi::job_answer(const JobRecord& j) const {
  nlohmann::json out = job_json(j);
  out["height_map"] = has_height_map(j);
  const int64_t map_job = height_map_job_of(data_, j);
  out["height_map_job"] = map_job != 0 ? nlohmann::json(map_job) : nlohmann::json();
  std::string waiting = map_wait_of(store_, data_, j, [this](const std::string& machine) {
    return workshop_.availability(machine);
  });
  if (waiting.empty()) waiting = workshop_.unzeroed_wait(j);
  out["waiting"] = waiting;
  return out;
}

void HttpApi::send_control_answer(int64_t id, const std::string& action,
                                  httplib::Response& res) const {
  // Every action answers alike: the job as it stands now and what was asked for (a machine
  // action is carried out after the answer: the job's state may not show it yet).
  const std::optional<JobRecord> job = store_.get(id);
  nlohmann::json out = job ? job_answer(*job) : nlohmann::json{{"id", id}};
  out["requested"] = action;
  send_json(res, 200, out);
}

bool HttpApi::has_height_map(const JobRecord& j) const {
  // A board job's map in its archive (probed, or taken over from another job).
  std::error_code ec;
  return is_board_job(j) && fs::exists(data_.job_dir(j.key) / kHeightMapFile, ec);
}

void HttpApi::routes() {
  route_checks();
  route_page();
  route_status();
  route_jobs();
  route_job_files();
  route_upload();
  route_control();
  route_priority();
}

bool HttpApi::refused_from_headers(const httplib::Request& req, httplib::Response& res) const {
  // httplib keeps "Content-Length : 5" as a header named "Content-Length ", which a proxy
  // in front may have read as the length (the message's framing then differs).
  for (const auto& header : req.headers) {
    if (!is_token(header.first)) {
      send_error(res, 400,
                 fmt::format("header name '{}' is not a token (a space before its colon, or a "
                             "continued line?)",
                             header.first));
      return true;
    }
  }
  // Which one would a proxy have checked? An empty one counts (httplib dropped it).
  if (req.get_header_value_count("Host") > 1 || host_header_lines() > 1) {
    send_error(res, 400, "the Host header is given twice");
    return true;
  }
  if (!req.has_header("Host")) {  // HTTP/1.1 asks a server to refuse it so (RFC 9112 §3.2)
    send_error(res, 400,
               "the request has no Host header (or an empty one): it names the server it is for");
    return true;
  }
  const std::string host = req.get_header_value("Host");
  if (!hosts_.allows(host)) {
    send_error(res, 403,
               fmt::format("Host '{}' is not a name of this server (it answers to {}; "
                           "serve --allowed-host NAME adds one)",
                           host, hosts_.describe()));
    return true;
  }
  // A known path with a method it does not take: 405 before the token is asked for.
  const std::string allow = allowed_methods(req.path);
  if (!allow.empty() && (", " + allow + ",").find(", " + req.method + ",") == std::string::npos) {
    res.set_header("Allow", allow);
    send_error(res, 405, fmt::format("{} takes {}, not {}", req.path, allow, req.method));
    return true;
  }
  // A body's length said one way only, in plain digits (httplib read "0x10" as 0 and took
  // the rest for the next request; an unreadable one was read without end).
  const size_t lengths = req.get_header_value_count("Content-Length");
  if (lengths > 1) {
    send_error(res, 400, "Content-Length is given twice");
    return true;
  }
  if (lengths == 1 && req.has_header("Transfer-Encoding")) {
    send_error(res, 400, "the body's length is given twice (Content-Length and Transfer-Encoding)");
    return true;
  }
  const int64_t declared = lengths == 1 ? declared_length(req) : 0;
  if (declared < 0) {
    send_error(res, 400,
               fmt::format("Content-Length '{}' is not a length in bytes",
                           req.get_header_value("Content-Length")));
    return true;
  }
  if (req.method == "GET" || req.method == "HEAD") return false;
  if (!same_secret(token_of(req), options_.token)) {
    send_error(res, 401, "missing or wrong token (Authorization: Bearer TOKEN)");
    return true;
  }
  // A length no body can have: httplib would wait for it (a length just past the limit is
  // read and thrown away, so that a client that does not wait for 100 Continue hears the
  // 413 rather than a reset connection).
  if (declared == INT64_MAX) {
    send_error(res, 413, upload_limit_text());
    return true;
  }
  return false;
}

int64_t HttpApi::declared_length(const httplib::Request& req) {
  const std::string length = req.get_header_value("Content-Length");
  uint64_t declared = 0;
  const char* end = length.data() + length.size();
  const auto parsed = std::from_chars(length.data(), end, declared);
  if (length.empty() || parsed.ptr != end || length[0] < '0' || length[0] > '9') return -1;
  // Digits past 2^63 - 1 are a length too: too large for any limit.
  if (parsed.ec == std::errc::result_out_of_range || declared > INT64_MAX) return INT64_MAX;
  return parsed.ec == std::errc() ? static_cast<int64_t>(declared) : -1;
}

size_t HttpApi::upload_limit_bytes() const {
  return intake_.max_bytes() + kFormFramingBytes;  // multipart framing on top of the files
}

std::string HttpApi::upload_limit_text() const {
  return fmt::format("upload larger than the limit of {} bytes (--max-upload-mb)",
                     intake_.max_bytes());
}

// Before every route: the Host check, 405 for a wrong method, the token; the error body.
void HttpApi::route_checks() {
  httplib::Server& s = *http_;
  // Before any handler runs: the Host must be one of this server's names (a page from
  // another site gets nowhere through a name that resolves here), and the token guards
  // every method but GET/HEAD.
  s.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    return refused_from_headers(req, res) ? httplib::Server::HandlerResponse::Handled
                                          : httplib::Server::HandlerResponse::Unhandled;
  });
  // A client that asks before it sends the body (Expect: 100-continue, as curl does for a
  // large one) hears the same refusals from the headers, and a 413 for a declared length
  // past the limit, before any byte of the body: httplib would say 100 Continue, then read
  // the whole body to throw it away. Connection: close, since the body is not read.
  s.set_expect_100_continue_handler([this](const httplib::Request& req, httplib::Response& res) {
    if (!refused_from_headers(req, res)) {
      // A form's parts take some framing beyond the files; a raw body is the file.
      const bool form = req.get_header_value("Content-Type").rfind("multipart/form-data", 0) == 0;
      const int64_t declared = req.has_header("Content-Length") ? declared_length(req) : 0;
      if (declared <= static_cast<int64_t>(form ? upload_limit_bytes() : intake_.max_bytes()))
        return 100;
      send_error(res, 413, upload_limit_text());
    }
    return res.status;  // answered with Connection: close, as every answer is
  });
  s.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (!res.body.empty()) return;
    const char* why = res.status == 413   ? "upload larger than the limit"
                      : res.status == 404 ? "no such resource"
                                          : "bad request";
    send_error(res, res.status, why);
  });
}

// The page's files.
void HttpApi::route_page() {
  httplib::Server& s = *http_;
  struct WebFile {
    const char* route;
    const char* file;
    const char* type;
  };
  static const WebFile kWeb[] = {{"/", "index.html", "text/html; charset=utf-8"},
                                 {"/app.js", "app.js", "text/javascript; charset=utf-8"},
                                 {"/style.css", "style.css", "text/css; charset=utf-8"}};
  for (const WebFile& w : kWeb) {
    s.Get(w.route, [this, w](const httplib::Request&, httplib::Response& res) {
      try {
        res.set_content(read_file(options_.web_dir / w.file), w.type);
      } catch (const std::exception& e) {
        send_error(res, 500, e.what());
      }
    });
  }
}

// The workshop's state, once or as server-sent events.
void HttpApi::route_status() {
  httplib::Server& s = *http_;
  s.Get("/api/status", [this](const httplib::Request&, httplib::Response& res) {
    send_json(res, 200, workshop_.snapshot());
  });
  s.Get("/api/events", [this](const httplib::Request&, httplib::Response& res) {
    // Counted while the response (and so the stream) lives.
    auto slot =
        std::shared_ptr<std::atomic<int>>(&open_streams_, [](std::atomic<int>* n) { --*n; });
    if (++open_streams_ > options_.max_event_streams) {
      res.set_header("Retry-After", "10");
      return send_error(res, 503,
                        fmt::format("too many open event streams (at most {}); try again later",
                                    options_.max_event_streams));
    }
    res.set_header("Cache-Control", "no-cache");
    auto seen = std::make_shared<uint64_t>(~uint64_t{0});
    res.set_chunked_content_provider(
        "text/event-stream", [this, seen, slot](size_t, httplib::DataSink& sink) {
          if (stopping_) return false;
          *seen = workshop_.wait_change(*seen, std::chrono::milliseconds(1000));
          if (stopping_) return false;
          const std::string event = event_text(*seen);
          return sink.write(event.data(), event.size());
        });
  });
}

// The jobs: the list, one job, a running job's path.
void HttpApi::route_jobs() {
  httplib::Server& s = *http_;
  s.Get("/api/jobs", [this](const httplib::Request& req, httplib::Response& res) {
    std::string state;
    if (req.has_param("state")) {
      state = req.get_param_value("state");
      try {
        state_from_name(state);
      } catch (const std::exception& e) {
        return send_error(res, 400, e.what());
      }
    }
    int64_t limit = 200;
    if (req.has_param("limit") &&
        (!parse_int(req.get_param_value("limit"), &limit) || limit < 1 || limit > 10000)) {
      return send_error(res, 400, "limit must be 1 .. 10000");
    }
    nlohmann::json jobs = nlohmann::json::array();
    for (const JobRecord& j : store_.list(state, static_cast<size_t>(limit)))
      jobs.push_back(job_answer(j));
    send_json(res, 200, {{"jobs", jobs}});
  });
  s.Get(R"(/api/jobs/(\d{1,18}))", [this](const httplib::Request& req, httplib::Response& res) {
    const auto job = store_.get(std::stoll(req.matches[1]));
    if (!job) return send_error(res, 404, "no such job");
    nlohmann::json j = job_answer(*job);
    j["runs"] = run_count(data_.job_dir(job->key));  // runs/1 .. runs/N in its archive
    send_json(res, 200, j);
  });
  s.Get(R"(/api/jobs/(\d{1,18})/path)",
        [this](const httplib::Request& req, httplib::Response& res) {
          const int64_t id = std::stoll(req.matches[1]);
          const std::shared_ptr<const std::string> path = workshop_.live_path(id);
          if (!path) {
            return send_error(res, 404,
                              fmt::format("job {} is not cutting on a machine of this server (its "
                                          "path is served while it runs)",
                                          id));
          }
          res.set_content(*path, "application/json");
        });
}

// Why a job's archive file is not there: servers on one queue keep the jobs they ran in
// their own archive unless they share one (--archive); a job running on this server has
// its run's report.json once the run ends (an outside tester was sent to "server 'a'" by
// server 'a' itself).
std::string HttpApi::missing_file_text(const JobRecord& job, const std::string& file) const {
  if (job.owner.empty()) return "the job has no " + file + " (yet)";
  if (job.owner == workshop_.owner()) {
    if (job.state != JobState::kRunning) return "the job has no " + file;
    return fmt::format("the job has no {} yet: it is running on this server (machine '{}'){}", file,
                       job.machine,
                       file == "report.json" ? "; a run's report.json is written when it ends, "
                                               "its machine.log as it runs"
                                             : "");
  }
  return fmt::format(
      "the job has no {} here (yet); it {} on server '{}', whose archive holds "
      "the files of its runs unless the servers share one (serve --archive)",
      file, job.state == JobState::kRunning ? "is running" : "ran", job.owner);
}

// A job's archive files and its runs' files.
void HttpApi::route_job_files() {
  httplib::Server& s = *http_;
  s.Get(R"(/api/jobs/(\d{1,18})/files/([a-z.]{1,24}))",
        [this](const httplib::Request& req, httplib::Response& res) {
          const std::string file = req.matches[2];
          if (!is_archive_file(file)) return send_error(res, 404, "no such archive file");
          const auto job = store_.get(std::stoll(req.matches[1]));
          if (!job) return send_error(res, 404, "no such job");
          const bool svg = file.size() > 4 && file.compare(file.size() - 4, 4, ".svg") == 0;
          const std::string type = svg                                       ? "image/svg+xml"
                                   : file == "plot.png"                      ? "image/png"
                                   : file.find(".json") != std::string::npos ? "application/json"
                                                                             : "text/plain";
          // A run's files: the newest run's.
          const fs::path dir = data_.job_dir(job->key);
          const fs::path path = is_run_file(file) ? run_file(dir, 0, file) : dir / file;
          try {
            res.set_content(read_file(path), type);
          } catch (const std::exception&) {
            send_error(res, 404, missing_file_text(*job, file));
          }
        });
  s.Get(R"(/api/jobs/(\d{1,18})/runs/([1-9]\d{0,5})/([a-z.]{1,16}))",
        [this](const httplib::Request& req, httplib::Response& res) {
          const std::string file = req.matches[3];
          if (!is_run_file(file))
            return send_error(res, 404, "a run holds machine.log, report.json");
          const auto job = store_.get(std::stoll(req.matches[1]));
          if (!job) return send_error(res, 404, "no such job");
          const int run = std::stoi(req.matches[2]);
          try {
            res.set_content(read_file(run_file(data_.job_dir(job->key), run, file)),
                            file == "report.json" ? "application/json" : "text/plain");
          } catch (const std::exception&) {
            // The newest run of a job running here: its report comes when it ends.
            const bool running_here = job->state == JobState::kRunning &&
                                      job->owner == workshop_.owner() &&
                                      run == run_count(data_.job_dir(job->key));
            send_error(res, 404,
                       running_here ? missing_file_text(*job, file)
                                    : fmt::format("the job has no run {} with a {}", run, file));
          }
        });
}

// A new job.
void HttpApi::route_upload() {
  httplib::Server& s = *http_;
  // ---- Changes (token checked above) ----
  // Read by the handler itself: httplib would cap a body sent as a form (curl --data-binary
  // without a Content-Type) at 8 KB and parse it as form fields.
  s.Post("/api/jobs", [this](const httplib::Request& req, httplib::Response& res,
                             const httplib::ContentReader& read) {
    UploadBody body(data_.new_staging_dir());
    body.multipart = req.is_multipart_form_data();
    bool ok = false;
    bool written = true;
    // Counted as it arrives: a chunked body has no length for httplib to refuse (300 MB went
    // to disk under a 12 MB limit), and a body still trickling in must not hold a server that
    // stops (it waited for the last byte).
    const size_t limit = upload_limit_bytes();
    size_t received = 0;
    auto take = [&](size_t n) {
      received += n;
      return received <= limit && !stopping_;
    };
    if (body.multipart) {
      ok = read(
          [&](const httplib::MultipartFormData& part) {
            written = written && body.close();
            body.parts.push_back(part);
            body.files.push_back(part.name == "file" ? body.new_file() : fs::path());
            return written;
          },
          [&](const char* data, size_t n) {
            if (!take(n)) return false;
            if (!body.files.back().empty()) return written = body.write(data, n);
            body.parts.back().content.append(data, n);
            return true;
          });
    } else {
      body.raw = body.new_file();
      ok = read(
          [&](const char* data, size_t n) { return take(n) && (written = body.write(data, n)); });
    }
    written = body.close() && written;
    if (!written) return send_error(res, 500, "the upload could not be written to the data folder");
    if (stopping_) {
      return send_error(res, 503,
                        "the server is stopping: not queued (send it again once the server is "
                        "back)");
    }
    if (!ok) {
      if (res.status == 413 || received > limit) {
        return send_error(res, 413, upload_limit_text());
      }
      return send_error(res, 400, "the upload's body could not be read");
    }
    const UploadFields u = upload_fields(req, body);
    if (!u.error.empty()) return send_error(res, 400, u.error);
    const IntakeResult r = intake_.submit(u.sub);
    release_freed_memory();  // the upload's plan, in this connection's arena
    if (r.status != 201) return send_error(res, r.status, r.error);
    workshop_.notify(true);
    const auto job = store_.get(r.id);
    send_json(res, 201, job ? job_answer(*job) : nlohmann::json{{"id", r.id}});
  });
}

// A job's control actions: the store's (cancel, requeue, continue), the machine's.
void HttpApi::route_control() {
  post_job_request(*http_, "control", {"action", "percent"},
                   [this](int64_t id, nlohmann::json& body, httplib::Response& res) {
                     if (!body.contains("action") || !body["action"].is_string()) {
                       return send_error(res, 400,
                                         "expected {\"action\": \"hold|resume|abort|override|"
                                         "cancel|requeue|continue|probe_ready\"}");
                     }
                     const std::string action = body["action"];
                     if (body.contains("percent") && action != "override") {
                       return send_error(res, 400, "percent goes with the override action only");
                     }
                     if (!store_.get(id)) return send_error(res, 404, "no such job");
                     if (store_control(id, action, res)) return;
                     JobControl c;
                     int percent = 0;
                     if (!machine_control(action, body, res, &c, &percent)) return;
                     const ControlResult r = workshop_.control(id, c, percent);
                     if (r.status != 200) return send_error(res, r.status, r.error);
                     send_control_answer(id, action, res);
                   });
}

// A queued job's priority.
void HttpApi::route_priority() {
  post_job_request(*http_, "priority", {"priority"},
                   [this](int64_t id, nlohmann::json& body, httplib::Response& res) {
                     const JobField& priority = *job_field_by_json_key("priority");
                     if (!body.contains("priority") || !body["priority"].is_number_integer() ||
                         !field_range_error(priority, body["priority"].get<double>()).empty()) {
                       return send_error(res, 400,
                                         fmt::format("expected {{\"priority\": {} .. {}}}",
                                                     priority.lowest, priority.highest));
                     }
                     if (!store_.get(id)) return send_error(res, 404, "no such job");
                     if (!store_.set_priority(id, body["priority"].get<int>())) {
                       return send_error(
                           res, 409,
                           refused_in_state(store_, id, "only a queued job's priority can change"));
                     }
                     workshop_.notify(true);
                     send_json(res, 200, job_answer(*store_.get(id)));
                   });
}

std::string HttpApi::requeue_without_map_source(int64_t id, bool continue_job) {
  const std::optional<JobRecord> job = store_.get(id);
  if (!job) return "";
  const bool takes = continue_job
                         ? job->state == JobState::kInterrupted
                         : job->state == JobState::kInterrupted ||
                               job->state == JobState::kAborted || job->state == JobState::kFailed;
  if (!takes) return "";
  const MapSource source = map_source_of(store_, data_, *job);
  if (source.ended_why.empty()) return "";
  if (!source.source_ended) return "queued again, it would fail at once: " + source.ended_why;
  // What brings the map back: a cancelled source cannot be requeued (nor an ended one
  // continued: that is for an interrupted job).
  const std::optional<JobRecord> from = store_.get(source.from);
  const std::string first =
      from && from->state == JobState::kCancelled
          ? fmt::format(
                "job {} was cancelled: upload its side again with probe_first=1, then "
                "this side with height_map_from naming it",
                source.from)
          : fmt::format(
                "requeue job {} first, which probes the blank again, then requeue this "
                "job",
                source.from);
  return fmt::format(
      "it cuts with job {}'s height map, and {}: queued again, it would fail at "
      "once ({})",
      source.from, source.ended_why, first);
}

bool HttpApi::store_control(int64_t id, const std::string& action, httplib::Response& res) {
  auto done = [&](bool ok, const std::string& why) {
    if (!ok) return send_error(res, 409, refused_in_state(store_, id, why));
    workshop_.notify(true);
    send_control_answer(id, action, res);
  };
  if (action == "requeue" || action == "continue") {
    // Its map source ended without a map: queued again, it would fail again at once (asked
    // only where the store would take the action: its own refusal says why otherwise).
    const std::string no_map = requeue_without_map_source(id, action == "continue");
    if (!no_map.empty()) {
      send_error(res, 409, refused_in_state(store_, id, no_map));
      return true;
    }
  }
  if (action == "cancel") {
    done(store_.cancel(id), "only a queued job can be cancelled");
  } else if (action == "requeue") {
    done(store_.requeue(id, false), "only an interrupted, aborted or failed job can be re-queued");
  } else if (action == "continue" && !workshop_.can_continue()) {
    send_error(res, 501,
               "continuing from the first uncut curve needs send --resume "
               "(protocol v2); re-queue the job to run it from the start");
  } else if (action == "continue") {
    done(store_.requeue(id, true), "only an interrupted job with a known curve can be continued");
  } else {
    return false;
  }
  return true;
}

}  // namespace host::server
