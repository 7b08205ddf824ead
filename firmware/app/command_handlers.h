// The application's command handlers, declared and dispatched from the message table's
// handler column: a new command is a table row (firmware/protocol/message_table.h) and the
// body of the handler it names (command_handlers.cpp). The rows of role kImmediate (#I, #?,
// #T) are answered by the dispatcher and have none.
#ifndef FIRMWARE_APP_COMMAND_HANDLERS_H
#define FIRMWARE_APP_COMMAND_HANDLERS_H

#include "firmware/protocol/codec.h"          // AnyCommand
#include "firmware/protocol/message_table.h"  // PROTO_MESSAGE_TABLE
#include "firmware/protocol/messages.h"       // the message structs

// NOLINTBEGIN(bugprone-macro-parentheses): Type is a type name, handler a member name.

// WITH(Type, letter_name, handler) for a row that has a handler (by its role), else nothing.
#define APP_IF_HANDLED(role, WITH, Type, name, handler) \
  APP_HANDLED_##role(WITH, Type, name, handler)
#define APP_HANDLED_kImmediate(WITH, Type, name, handler)
#define APP_HANDLED_kRealtime(WITH, Type, name, handler) WITH(Type, name, handler)
#define APP_HANDLED_kJobCommand(WITH, Type, name, handler) WITH(Type, name, handler)
#define APP_HANDLED_kSplineData(WITH, Type, name, handler) WITH(Type, name, handler)
#define APP_HANDLED_kJobMark(WITH, Type, name, handler) WITH(Type, name, handler)
#define APP_HANDLER_SKIP(...)

// Inside the class that owns the handlers: one declaration per handler of the table, and a
// static call_<handler> that hands it the decoded command (the routing table's entry).
#define APP_DECLARE_HANDLER(Type, name, handler)                                       \
  proto::ErrorCode handler(const proto::Type& c, uint8_t seq, uint8_t* detail);        \
  static proto::ErrorCode call_##handler(Application* app, const proto::AnyCommand& m, \
                                         uint8_t seq, uint8_t* detail) {               \
    return app->handler(m.m_##Type, seq, detail);                                      \
  }
#define APP_DECLARE_HANDLER_ROW(Type, name, letter, role, display, reply, handler, check) \
  APP_IF_HANDLED(role, APP_DECLARE_HANDLER, Type, name, handler)
#define APP_DECLARE_COMMAND_HANDLERS()                                             \
  PROTO_MESSAGE_TABLE(APP_DECLARE_HANDLER_ROW, APP_HANDLER_SKIP, APP_HANDLER_SKIP, \
                      APP_HANDLER_SKIP, APP_HANDLER_SKIP, APP_HANDLER_SKIP)

// The routing table's rows (a CommandCall initialiser), one per command row of the table in
// its order (proto::command_row()): its call_<handler>, 0 for the rows without a handler.
#define APP_ROUTE(Type, name, handler) &Application::call_##handler,
#define APP_ROUTE_ROW(Type, name, letter, role, display, reply, handler, check) \
  APP_ROUTE_##role(Type, name, handler)
#define APP_ROUTE_kImmediate(Type, name, handler) 0,
#define APP_ROUTE_kRealtime APP_ROUTE
#define APP_ROUTE_kJobCommand APP_ROUTE
#define APP_ROUTE_kSplineData APP_ROUTE
#define APP_ROUTE_kJobMark APP_ROUTE
#define APP_COMMAND_ROUTES()                                                               \
  PROTO_MESSAGE_TABLE(APP_ROUTE_ROW, APP_HANDLER_SKIP, APP_HANDLER_SKIP, APP_HANDLER_SKIP, \
                      APP_HANDLER_SKIP, APP_HANDLER_SKIP)

// NOLINTEND(bugprone-macro-parentheses)

#endif  // FIRMWARE_APP_COMMAND_HANDLERS_H
