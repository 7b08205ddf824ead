#include "host/lib/pcb/gerber_outline.h"

#include <algorithm>  // std::reverse
#include <cmath>      // std::hypot

namespace host::pcb {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

namespace {

bool near(const IntPoint& a, const IntPoint& b, double tol) {
  return std::hypot(static_cast<double>(a.X - b.X), static_cast<double>(a.Y - b.Y)) <= tol;
}

// Appends an unused stroke that starts or ends near `end` (reversed if needed); false if none.
bool extend(Path& chain, bool at_back, const std::vector<Path>& strokes, std::vector<bool>& used,
            double tol) {
  const IntPoint end = at_back ? chain.back() : chain.front();
  for (size_t k = 0; k < strokes.size(); ++k) {
    if (used[k]) continue;
    const Path& s = strokes[k];
    const bool front_fits = near(s.front(), end, tol);
    if (!front_fits && !near(s.back(), end, tol)) continue;
    used[k] = true;
    Path piece = s;
    // Oriented so that piece.front() meets `end`.
    if (!front_fits) std::reverse(piece.begin(), piece.end());
    if (at_back) {
      chain.insert(chain.end(), piece.begin() + 1, piece.end());
    } else {
      std::reverse(piece.begin(), piece.end());
      chain.insert(chain.begin(), piece.begin(), piece.end() - 1);
    }
    return true;
  }
  return false;
}

}  // namespace

Paths join_strokes(const std::vector<Path>& strokes_in, double join_nm) {
  std::vector<Path> strokes;
  for (const Path& s : strokes_in) {
    if (s.size() >= 2) strokes.push_back(s);
  }
  std::vector<bool> used(strokes.size(), false);
  Paths out;
  for (size_t k = 0; k < strokes.size(); ++k) {
    if (used[k]) continue;
    used[k] = true;
    Path chain = strokes[k];
    const bool closed_already = chain.size() > 2 && chain.front() == chain.back();
    if (!closed_already) {
      while (!(chain.size() > 2 && near(chain.front(), chain.back(), join_nm)) &&
             extend(chain, true, strokes, used, join_nm)) {
      }
      while (!(chain.size() > 2 && near(chain.front(), chain.back(), join_nm)) &&
             extend(chain, false, strokes, used, join_nm)) {
      }
      if (chain.size() > 2 && near(chain.front(), chain.back(), join_nm)) {
        chain.back() = chain.front();
      }
    }
    out.push_back(chain);
  }
  return out;
}

}  // namespace host::pcb
