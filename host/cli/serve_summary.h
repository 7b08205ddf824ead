// The one-line summary of `engraver serve`, shared by the command (engraver-serve) and its
// forwarder in `engraver`, so both list it the same.
#ifndef HOST_CLI_SERVE_SUMMARY_H
#define HOST_CLI_SERVE_SUMMARY_H

namespace host::cli {

inline const char* const kServeSummary =
    "the workshop server: job queue, archive, machines, web page and JSON API";

// The executable beside `engraver` that holds the server (its libraries: HTTP, SQLite,
// PostgreSQL, libzip); `engraver serve ...` runs it as `engraver-serve serve ...`.
inline const char* const kServeExecutable = "engraver-serve";

}  // namespace host::cli

#endif  // HOST_CLI_SERVE_SUMMARY_H
