// Whether the server can listen where it was told, found before its data folder is touched: a
// serve that cannot listen must leave no folder, database or unprinted token behind.
#ifndef HOST_LIB_SERVER_LISTEN_CHECK_H
#define HOST_LIB_SERVER_LISTEN_CHECK_H

#include <string>  // std::string

namespace host::server {

// "cannot listen on 127.0.0.1:8080 (in use or not an address of this PC)".
std::string cannot_listen_text(const std::string& address, int port);

// Binds and listens on address:port (a numeric address) and lets go at once; throws
// std::runtime_error with cannot_listen_text when it cannot. Port 0 (any free port) always can.
void check_can_listen(const std::string& address, int port);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_LISTEN_CHECK_H
