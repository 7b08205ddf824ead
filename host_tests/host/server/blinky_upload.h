// The blinky test board as a multipart upload, and its upload, for the server's board tests.
#pragma once

#include <cstdint>    // int64_t
#include <stdexcept>  // std::runtime_error
#include <string>     // std::string
#include <utility>    // std::pair
#include <vector>     // std::vector

#include "host_tests/host/server/server_test_rig.h"

namespace host::server::test {

inline std::string board_file(const std::string& name) {
  return read_file(std::filesystem::path(ENGRAVER_SOURCE_DIR) / "host_tests/host/server/data" /
                   name);
}

// blinky's top copper (under the name `copper`), drill and outline, and the fields `kv`.
inline httplib::MultipartFormDataItems blinky(
    const std::vector<std::pair<std::string, std::string>>& kv,
    const std::string& copper = "blinky-F.Cu.gbr") {
  httplib::MultipartFormDataItems form = {
      {"file", board_file("blinky-F.Cu.gbr"), copper, "application/octet-stream"},
      {"file", board_file("blinky.drl"), "blinky.drl", "application/octet-stream"},
      {"file", board_file("blinky-Edge.Cuts.gbr"), "blinky-Edge.Cuts.gbr",
       "application/octet-stream"}};
  for (const auto& [k, v] : kv) form.push_back({k, v, "", ""});
  return form;
}

// The new job's id; throws with the server's answer unless it is 201.
inline int64_t post(const ServerRig& server, const httplib::MultipartFormDataItems& form) {
  auto r = server.client().Post("/api/jobs", server.auth(), form);
  if (!r || r->status != 201)
    throw std::runtime_error("upload failed: " + (r ? r->body : std::string("no answer")));
  return nlohmann::json::parse(r->body)["id"].get<int64_t>();
}

}  // namespace host::server::test
