// `engraver serve`: the workshop server (job queue, archive, machines, web page and API).
#include <CLI/CLI.hpp>  // CLI::App

#include <fmt/format.h>  // fmt::format
#include <signal.h>      // sigaction
#include <unistd.h>      // gethostname

#include <atomic>      // std::atomic
#include <filesystem>  // std::filesystem::path, canonical
#include <iostream>    // std::cerr
#include <thread>      // std::thread

#include "host/cli/command_registry.h"
#include "host/cli/exit_codes.h"
#include "host/cli/option_ranges.h"  // range_check
#include "host/cli/serve_summary.h"
#include "host/lib/server/data_folder.h"
#include "host/lib/server/data_folder_lock.h"
#include "host/lib/server/http_api.h"
#include "host/lib/server/inbox_watcher.h"
#include "host/lib/server/job_intake.h"
#include "host/lib/server/listen_check.h"
#include "host/lib/server/machine_spec.h"
#include "host/lib/server/postgres_job_store.h"
#include "host/lib/server/sqlite_job_store.h"
#include "host/lib/server/web_files.h"
#include "host/lib/server/workshop.h"
#include "host/lib/stream/host_port.h"  // --listen as sim reads it; [::1]:8080 as printed

namespace host::cli {

namespace {

struct ServeArgs {
  std::string data = "engraver-data";
  std::string listen = "127.0.0.1:8080";
  std::vector<std::string> machines;
  std::string inbox;
  double max_upload_mb = 20.0;
  std::string web;  // "": installed beside the executable (ENGRAVER_WEB_FROM_BIN)
  int poll_ms = 100;
  std::string name;
  bool no_zero = false;
  std::string db;
  double stale_s = 30.0;
  std::vector<std::string> allowed_hosts;
  std::string archive;
};

// The job store: the data folder's SQLite file, or a PostgreSQL database shared by servers.
std::unique_ptr<server::JobStore> open_store(const std::string& db,
                                             const server::DataFolder& data) {
  if (db.empty() || db == "sqlite") {
    return std::make_unique<server::SqliteJobStore>(data.database().string());
  }
  return std::make_unique<server::PostgresJobStore>(db);
}

// --db names SQLite or a libpq connection (a URI, or key=value pairs, as libpq reads them
// without connecting): anything else is a usage error as the line is read, not a failed
// start after the data folder is made.
std::string db_check(const std::string& db) {
  const bool uri = db.rfind("postgresql://", 0) == 0 || db.rfind("postgres://", 0) == 0;
  if (db == "sqlite") return "";
  if (!uri && db.find('=') == std::string::npos) {
    return "'" + db +
           "' is neither 'sqlite' nor a PostgreSQL connection ('postgresql://host/db' or "
           "'host=... dbname=...')";
  }
  const std::string problem = server::postgres_conninfo_problem(db);
  return problem.empty() ? "" : "not a PostgreSQL connection: " + problem;
}

std::atomic<bool> g_stop_serve{false};
extern "C" void on_stop_serve(int) {
  g_stop_serve = true;
}

std::string host_name() {
  char buf[256] = {};
  if (gethostname(buf, sizeof buf - 1) != 0 || buf[0] == '\0') return "local";
  return buf;
}

// --listen's address and port, read as sim's --listen reads them; exit 2 for anything else.
HostPort listen_address(const std::string& listen) {
  try {
    return parse_host_port(listen, PortUse::kListen);
  } catch (const std::invalid_argument& e) {
    throw CommandFailure(kExitUsage, fmt::format("--listen: '{}': {}", listen, e.what()));
  }
}

// Binds the page's port; exit 2 when it cannot (in use, not this PC's), as sim's --listen.
int bind_listen_address(server::HttpApi& http, const std::string& listen) {
  try {
    return http.bind();
  } catch (const std::runtime_error& e) {
    throw CommandFailure(kExitUsage, fmt::format("--listen: '{}': {}", listen, e.what()));
  }
}

// The --machine specs, named m1, m2 ... where they give no name; exit 2 for a bad one.
std::vector<server::MachineSpec> parse_machines(const ServeArgs& a) {
  std::vector<server::MachineSpec> machines;
  for (size_t i = 0; i < a.machines.size(); ++i) {
    try {
      machines.push_back(server::parse_machine_spec(a.machines[i], fmt::format("m{}", i + 1)));
    } catch (const std::invalid_argument& e) {
      throw CommandFailure(kExitUsage, e.what());
    }
  }
  return machines;
}

// The workshop page's folder (--web, else beside this executable).
std::filesystem::path served_web_dir(const ServeArgs& a) {
  // The page must be there before anyone opens it: a missing one is an error now, not a
  // 500 later.
  std::filesystem::path web_dir = a.web;
  if (web_dir.empty()) {
    try {
      web_dir = server::web_dir_beside_executable(ENGRAVER_WEB_FROM_BIN);
    } catch (const std::exception& e) {
      throw CommandFailure(kExitUsage,
                           std::string(e.what()) + "; give the page's folder with --web");
    }
  }
  const std::string missing = server::missing_web_files(web_dir);
  if (!missing.empty()) {
    throw CommandFailure(
        kExitUsage, fmt::format("the web page: {} ({}; `cmake --install` puts it in "
                                "PREFIX/share/engraver/web beside PREFIX/bin/engraver, or "
                                "give the folder with --web)",
                                missing, a.web.empty() ? "looked beside this engraver" : "--web"));
  }
  return web_dir;
}

server::WorkshopOptions workshop_options(const ServeArgs& a) {
  server::WorkshopOptions wo;
  wo.owner = a.name.empty() ? host_name() : a.name;
  wo.sender.status_interval = std::chrono::milliseconds(a.poll_ms);
  wo.sender.zero_first = !a.no_zero;
  wo.stale_after = std::chrono::milliseconds(static_cast<int64_t>(a.stale_s * 1000));
  std::error_code ec;
  const std::filesystem::path folder = std::filesystem::canonical(a.data, ec);
  wo.holder = host_name() + ":" + (ec ? a.data : folder.string());
  wo.say = [](const std::string& line) { std::cerr << "engraver: " << line << "\n"; };
  return wo;
}

// What the server says when it starts: where, the token once, the machines.
void print_serving(const ServeArgs& a, const server::HttpApi& http, const std::string& address,
                   int bound, const std::string& owner, bool created, const std::string& token,
                   const std::vector<server::MachineSpec>& machines) {
  std::cerr << fmt::format("engraver: serving http://{}/ as '{}', data in {}, {} machine(s)\n",
                           host_port_text(address, bound), owner, a.data, machines.size());
  // The Host header's allow-list, not more listeners: loopback names are on it whichever
  // loopback the server listens on (a tunnel or proxy may name either).
  std::cerr << fmt::format(
      "engraver: answering requests whose Host header names {} (names "
      "it answers to; it listens only on --listen)\n",
      http.allowed_hosts().describe());
  if (created) {
    std::cerr << fmt::format(
        "engraver: access token (shown once; kept in {}/token): {}\n"
        "engraver: every request that changes anything needs it (the page asks for it)\n",
        a.data, token);
  }
  // The machine list as the machines' names on the page.
  for (const server::MachineSpec& m : machines) {
    std::cerr << fmt::format("engraver: machine {} at {}, work area {} x {} mm\n", m.name,
                             m.address, m.fit.work_width_mm, m.fit.work_height_mm);
  }
}

void run_serve(const ServeArgs& a) {
  const HostPort listen = listen_address(a.listen);
  const std::vector<server::MachineSpec> machines = parse_machines(a);
  const std::filesystem::path web_dir = served_web_dir(a);
  // A port in use or an address not this PC's: exit 2 before the data folder is made (a
  // token no one was shown, a database no server serves).
  try {
    server::check_can_listen(listen.host, listen.port);
  } catch (const std::runtime_error& e) {
    throw CommandFailure(kExitUsage, fmt::format("--listen: '{}': {}", a.listen, e.what()));
  }
  // Before anything in the folder is touched: one server per data folder.
  std::unique_ptr<server::DataFolderLock> folder_lock;
  try {
    folder_lock = std::make_unique<server::DataFolderLock>(a.data);
  } catch (const server::FolderInUse& e) {
    throw CommandFailure(kExitJobFailed, e.what());
  }
  server::DataFolder data(a.data, a.archive);
  const std::unique_ptr<server::JobStore> store_owner = open_store(a.db, data);
  server::JobStore& store = *store_owner;
  // The token is shown once, when it is made: a start that fails before showing it takes
  // it back, so the next start makes and shows one (it was kept unseen).
  bool created = false;
  const std::string token = data.token(&created);
  struct UnshownToken {
    std::filesystem::path path;
    ~UnshownToken() {
      std::error_code ec;
      if (!path.empty()) std::filesystem::remove(path, ec);
    }
  } unshown{created ? data.token_path() : std::filesystem::path()};

  const server::WorkshopOptions wo = workshop_options(a);
  server::Workshop workshop(store, data, machines, wo);
  server::JobIntake intake(store, data, workshop.fits(),
                           static_cast<size_t>(a.max_upload_mb * 1024 * 1024));
  server::HttpOptions ho;
  ho.address = listen.host;
  ho.port = listen.port;
  ho.web_dir = web_dir;
  ho.token = token;
  ho.allowed_hosts = a.allowed_hosts;
  server::HttpApi http(store, intake, workshop, data, ho);
  const int bound = bind_listen_address(http, a.listen);

  struct sigaction sa {};
  sa.sa_handler = on_stop_serve;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);

  try {
    workshop.start();
  } catch (const server::NameInUse& e) {
    throw CommandFailure(kExitJobFailed, e.what());
  }
  std::unique_ptr<server::InboxWatcher> inbox;
  if (!a.inbox.empty()) {
    server::JobPlanSettings settings;
    inbox = std::make_unique<server::InboxWatcher>(a.inbox, intake, settings,
                                                   std::chrono::milliseconds(1000),
                                                   [&workshop] { workshop.notify(true); });
    inbox->start();
  }
  std::thread serving([&http] { http.run(); });
  print_serving(a, http, ho.address, bound, wo.owner, created, token, machines);
  unshown.path.clear();
  while (!g_stop_serve) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::cerr << "engraver: stopping (running jobs are aborted and marked interrupted)\n";
  intake.stop();  // an upload being planned ends now (503), not when its planning would
  if (inbox) inbox->stop();
  http.stop();
  serving.join();
  workshop.stop();
}

void add_serve_commands(CLI::App& app) {
  auto args = std::make_shared<ServeArgs>();
  CLI::App* serve = app.add_subcommand("serve", kServeSummary);
  serve->add_option("--data", args->data, "data folder: job database, token, archive")
      ->capture_default_str();
  serve
      ->add_option("--listen", args->listen,
                   "ADDR:PORT of the page and API (loopback by default; a numeric address, IPv6 "
                   "in brackets: [::1]:8080; PORT in decimal, 080 is 80, 0 any free port)")
      ->capture_default_str();
  serve->add_option("--machine", args->machines,
                    "a machine: 'ADDRESS [name=NAME] [work=WxH] [tags=a,b]' (repeat the option)");
  serve->add_option("--inbox", args->inbox,
                    "watched folder: drawings, board zips and board sub-folders (Gerber/Excellon "
                    "files) dropped here become jobs");
  serve
      ->add_option("--max-upload-mb", args->max_upload_mb,
                   "largest upload accepted, MB (a board: all its files, unpacked)")
      ->check(range_check({"--max-upload-mb", 0.001, 1024.0, "MB", false}))
      ->capture_default_str();
  serve->add_option("--allowed-host", args->allowed_hosts,
                    "a name or address the page is opened with, besides the listen address, "
                    "localhost, 127.0.0.1, [::1] (and, listening on all addresses, the host "
                    "name and the PC's addresses); requests naming another Host get 403 "
                    "(repeat the option)");
  serve->add_option("--web", args->web,
                    "folder of the page's files (default: " ENGRAVER_WEB_FROM_BIN
                    " beside this engraver, where cmake --install puts them)");
  // Its range comes from the one option table (0: one status query always out, as send's).
  serve->add_option("--poll-ms", args->poll_ms, "status poll interval while a job runs")
      ->capture_default_str();
  serve->add_option("--name", args->name, "this server's name in the queue (default host name)");
  serve->add_flag("--no-zero", args->no_zero, "do not start manual zeroing if not zeroed");
  serve
      ->add_option("--db", args->db,
                   "job store: 'sqlite' (DATA/jobs.sqlite, default) or a PostgreSQL "
                   "connection ('postgresql://host/db' or 'host=... dbname=...') shared by "
                   "several servers; give each server its own --name")
      ->check(CLI::Validator(db_check, "", "db"));
  serve->add_option("--archive", args->archive,
                    "folder of the jobs' archives instead of DATA/jobs: give every server "
                    "of one --db queue the same (a network mount), so each serves every "
                    "job's files");
  serve
      ->add_option("--stale-s", args->stale_s,
                   "a server sharing the store and silent this long is taken for dead: its "
                   "lease is revoked and its running jobs become interrupted (a server stops "
                   "sending a quarter of this before, when it cannot renew its lease)")
      ->check(range_check({"--stale-s", 2.0, 3600.0, "s", false}))
      ->capture_default_str();
  serve->footer(
      "Example: engraver serve --data /srv/engraver --machine 'tcp://192.168.1.50:10001 "
      "name=left' --machine 'serial:/dev/ttyUSB0 name=right work=200x150 tags=brass'\n"
      "The token is printed once, on the first start; it is kept in DATA/token.\n"
      "Exit: 0 stopped by Ctrl-C or SIGTERM, 1 cannot start (the data folder used by another "
      "server, the database unreachable, another live server with this --name), 2 bad "
      "command line (a --listen port in use included) or page files missing "
      "(docs/user-guide.md, \"engraver serve\").");
  serve->callback([args] { run_serve(*args); });
}

const CommandRegistrar registrar("serve", {"serve"}, add_serve_commands);

}  // namespace

}  // namespace host::cli
