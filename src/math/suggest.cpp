#include "chasles/suggest.h"

#include <algorithm>
#include <cctype>
#include <numeric>

namespace chasles {

int EditDistance(std::string_view a, std::string_view b) {
  // Three rows of the dynamic-programming table suffice: a swap looks two rows back.
  const size_t m = b.size();
  std::vector<int> before(m + 1), previous(m + 1), current(m + 1);
  std::iota(previous.begin(), previous.end(), 0);
  for (size_t i = 1; i <= a.size(); ++i) {
    current[0] = static_cast<int>(i);
    for (size_t j = 1; j <= m; ++j) {
      const int cost = a[i - 1] == b[j - 1] ? 0 : 1;
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        current[j] = std::min(current[j], before[j - 2] + 1);
      }
    }
    std::swap(before, previous);
    std::swap(previous, current);
  }
  return previous[m];
}

namespace {
std::string Lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}
}  // namespace

std::vector<std::string> SuggestNames(std::string_view name, const std::vector<std::string>& known,
                                      int max_count) {
  const std::string lname = Lower(name);
  const int n = static_cast<int>(lname.size());
  const int limit = n <= 2 ? 0 : n <= 4 ? 1 : n <= 8 ? 2 : n / 4;
  int best = limit + 1;
  std::vector<std::string> out;
  for (const std::string& candidate : known) {
    if (candidate == name) continue;
    const std::string lc = Lower(candidate);
    const int d = EditDistance(lname, lc);
    // A distance as long as either name is a replacement, not a typo.
    if (d > limit || d > best || d >= std::max<int>(n, static_cast<int>(lc.size()))) continue;
    if (d < best) {
      best = d;
      out.clear();
    }
    if (static_cast<int>(out.size()) < max_count &&
        std::find(out.begin(), out.end(), candidate) == out.end()) {
      out.push_back(candidate);
    }
  }
  return out;
}

std::string DidYouMeanHint(const std::vector<std::string>& suggestions) {
  if (suggestions.empty()) return "";
  std::string text = " (did you mean ";
  for (size_t i = 0; i < suggestions.size(); ++i) {
    if (i > 0) text += i + 1 == suggestions.size() ? " or " : ", ";
    text += "'" + suggestions[i] + "'";
  }
  return text + "?)";
}

std::string DidYouMean(std::string_view name, const std::vector<std::string>& known) {
  return DidYouMeanHint(SuggestNames(name, known));
}

}  // namespace chasles
