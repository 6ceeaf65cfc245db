// A unified diff of two texts (chasles/files/robot_writer.h), by Myers' O(ND) algorithm
// (E. W. Myers, "An O(ND) difference algorithm and its variations", Algorithmica 1, 1986):
// fixes change a few lines of a long file, so D is small.

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "chasles/files/robot_writer.h"

namespace chasles {

namespace {

std::vector<std::string_view> Lines(const std::string& text) {
  std::vector<std::string_view> out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = text.find('\n', at);
    const std::size_t stop = end == std::string::npos ? text.size() : end + 1;
    out.emplace_back(text.data() + at, stop - at);
    at = stop;
  }
  return out;
}

/// For each line of a and b, whether it is kept (true) or removed / added.
void Match(const std::vector<std::string_view>& a, const std::vector<std::string_view>& b,
           std::vector<bool>& keep_a, std::vector<bool>& keep_b) {
  const int n = static_cast<int>(a.size()), m = static_cast<int>(b.size());
  const int offset = n + m + 1;
  std::vector<int> v(2 * offset + 1, 0);
  std::vector<std::vector<int>> trace;
  int d_end = 0;
  for (int d = 0; d <= n + m; ++d) {
    trace.push_back(v);
    bool done = false;
    for (int k = -d; k <= d; k += 2) {
      int x = (k == -d || (k != d && v[offset + k - 1] < v[offset + k + 1]))
                  ? v[offset + k + 1]
                  : v[offset + k - 1] + 1;
      int y = x - k;
      while (x < n && y < m && a[x] == b[y]) ++x, ++y;
      v[offset + k] = x;
      if (x >= n && y >= m) done = true;
    }
    if (done) {
      d_end = d;
      break;
    }
  }
  keep_a.assign(n, false);
  keep_b.assign(m, false);
  int x = n, y = m;
  for (int d = d_end; d > 0; --d) {
    const std::vector<int>& vp = trace[d];
    const int k = x - y;
    const int pk = (k == -d || (k != d && vp[offset + k - 1] < vp[offset + k + 1])) ? k + 1 : k - 1;
    const int px = vp[offset + pk], py = px - pk;
    while (x > px && y > py) {  // the snake after the edit
      --x, --y;
      keep_a[x] = keep_b[y] = true;
    }
    x = px, y = py;
  }
  while (x > 0 && y > 0) {
    --x, --y;
    keep_a[x] = keep_b[y] = true;
  }
}

}  // namespace

std::string UnifiedDiff(const std::string& before, const std::string& after,
                        const std::string& before_name, const std::string& after_name) {
  if (before == after) return "";
  const std::vector<std::string_view> a = Lines(before), b = Lines(after);
  std::vector<bool> ka, kb;
  Match(a, b, ka, kb);
  // Walk both, emitting hunks around changes with 3 lines of context.
  struct Op {
    char tag;
    std::string_view line;
    int ia, ib;
  };
  std::vector<Op> ops;
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (i < a.size() && !ka[i]) {
      ops.push_back({'-', a[i], static_cast<int>(i), static_cast<int>(j)}), ++i;
    } else if (j < b.size() && !kb[j]) {
      ops.push_back({'+', b[j], static_cast<int>(i), static_cast<int>(j)}), ++j;
    } else {
      ops.push_back({' ', a[i], static_cast<int>(i), static_cast<int>(j)}), ++i, ++j;
    }
  }
  std::string out = fmt::format("--- {}\n+++ {}\n", before_name, after_name);
  constexpr std::size_t kContext = 3;
  std::size_t at = 0;
  while (at < ops.size()) {
    while (at < ops.size() && ops[at].tag == ' ') ++at;
    if (at == ops.size()) break;
    std::size_t start = at >= kContext ? at - kContext : 0, end = at;
    // Extend while the next change is within twice the context.
    for (std::size_t k = at; k < ops.size(); ++k) {
      if (ops[k].tag != ' ')
        end = k;
      else if (k - end > 2 * kContext)
        break;
    }
    const std::size_t stop = std::min(ops.size(), end + kContext + 1);
    int na = 0, nb = 0;
    for (std::size_t k = start; k < stop; ++k) na += ops[k].tag != '+', nb += ops[k].tag != '-';
    out += fmt::format("@@ -{},{} +{},{} @@\n", ops[start].ia + 1, na, ops[start].ib + 1, nb);
    for (std::size_t k = start; k < stop; ++k) {
      out += ops[k].tag;
      out += ops[k].line;
      if (ops[k].line.empty() || ops[k].line.back() != '\n')
        out += "\n\\ No newline at end of file\n";
    }
    at = stop;
  }
  return out;
}

}  // namespace chasles
