#include "support/spelling.h"

#include <algorithm>
#include <cctype>

namespace spire {

size_t editDistance(std::string_view a, std::string_view b) {
  const size_t n = a.size();
  const size_t m = b.size();
  std::vector<size_t> prev2(m + 1), prev(m + 1), cur(m + 1);
  for (size_t j = 0; j <= m; ++j) prev[j] = 2 * j;
  for (size_t i = 1; i <= n; ++i) {
    cur[0] = 2 * i;
    for (size_t j = 1; j <= m; ++j) {
      const bool same =
          std::tolower(static_cast<unsigned char>(a[i - 1])) == std::tolower(static_cast<unsigned char>(b[j - 1]));
      // A case-only difference costs less than a real typo but is not free.
      const size_t subst = a[i - 1] == b[j - 1] ? 0 : (same ? 1 : 2);
      cur[j] = std::min({prev[j] + 2, cur[j - 1] + 2, prev[j - 1] + subst});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) cur[j] = std::min(cur[j], prev2[j - 2] + 2);
    }
    prev2.swap(prev);
    prev.swap(cur);
  }
  return prev[m] / 2 + prev[m] % 2;
}

std::optional<std::string> closestSpelling(std::string_view name, const std::vector<std::string_view>& candidates) {
  const size_t limit = std::max<size_t>(1, (name.size() + 2) / 3);
  std::optional<std::string> best;
  size_t bestDistance = limit + 1;
  for (std::string_view candidate : candidates) {
    if (candidate == name || candidate.empty()) continue;
    const size_t lengthGap =
        candidate.size() > name.size() ? candidate.size() - name.size() : name.size() - candidate.size();
    if (lengthGap > limit) continue;
    const size_t d = editDistance(name, candidate);
    if (d < bestDistance) {
      bestDistance = d;
      best = std::string(candidate);
    }
  }
  return best;
}

}  // namespace spire
