// A board job's files as one byte string, for the job store (a server sharing the queue
// fetches a job's input from there): "engraver-board 1\n", then per file "NAME SIZE\n",
// the bytes and "\n". Names are the archive's own (board.json, copper.top.gbr, ...).
#ifndef HOST_LIB_SERVER_BOARD_BUNDLE_H
#define HOST_LIB_SERVER_BOARD_BUNDLE_H

#include <string>   // std::string
#include <utility>  // std::pair
#include <vector>   // std::vector

namespace host::server {

using NamedFiles = std::vector<std::pair<std::string, std::string>>;  // name, bytes

std::string pack_board_bundle(const NamedFiles& files);
// Throws std::runtime_error when the bundle is damaged or names a file that is not an
// archive file (is_archive_file).
NamedFiles unpack_board_bundle(const std::string& bundle);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_BOARD_BUNDLE_H
