// A count and its noun as reports say it: "1 hole", "3 holes", "0 holes" (the singular for one
// only). Every report line that counts things (holes, tools, paths, passes, commands, layers)
// goes through it, so none says "1 holes".
#ifndef HOST_LIB_PLAN_COUNTED_H
#define HOST_LIB_PLAN_COUNTED_H

#include <cstddef>  // size_t
#include <string>   // std::string

namespace host {

// "1 hole" / "2 holes"; `plural` when adding "s" is wrong ("pass", "passes").
inline std::string counted(size_t n, const std::string& singular, const std::string& plural = "") {
  return std::to_string(n) + " " + (n == 1 ? singular : plural.empty() ? singular + "s" : plural);
}

}  // namespace host

#endif  // HOST_LIB_PLAN_COUNTED_H
