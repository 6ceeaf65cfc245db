#include "unified_diff.h"

#include <algorithm>
#include <vector>

#include <fmt/format.h>

namespace chasles::cli {

namespace {

/// The lines of `text`, each with its '\n' (the last one may have none).
std::vector<std::string_view> Lines(std::string_view text) {
  std::vector<std::string_view> lines;
  for (size_t begin = 0; begin < text.size();) {
    const size_t end = text.find('\n', begin);
    const size_t stop = end == std::string_view::npos ? text.size() : end + 1;
    lines.push_back(text.substr(begin, stop - begin));
    begin = stop;
  }
  return lines;
}

enum class Op { kKeep, kDelete, kInsert };

/// A shortest edit script from a to b (E. W. Myers, "An O(ND) difference algorithm and its
/// variations", Algorithmica 1, 1986): the greedy forward search over diagonals k = x - y, the
/// furthest-reaching x of each diagonal kept for every d, then traced back. Time O((N+M) D),
/// memory O(D²) (each d keeps only diagonals -d-1 ... d+1).
std::vector<Op> EditScript(const std::vector<std::string_view>& a,
                           const std::vector<std::string_view>& b) {
  const int n = static_cast<int>(a.size());
  const int m = static_cast<int>(b.size());
  // trace[d][k + d + 1]: the furthest x on diagonal k before step d.
  std::vector<std::vector<int>> trace;
  std::vector<int> v(3, 0);  // diagonals -1..1 before step 0: V[1] = 0
  int d = 0;
  for (;; ++d) {
    trace.push_back(v);
    std::vector<int> next(static_cast<size_t>(2 * d + 5), 0);
    const auto at = [](const std::vector<int>& w, int k, int width) {
      return w[static_cast<size_t>(k + width)];
    };
    bool done = false;
    for (int k = -d; k <= d && !done; k += 2) {
      const bool down = k == -d || (k != d && at(v, k - 1, d + 1) < at(v, k + 1, d + 1));
      int x = down ? at(v, k + 1, d + 1) : at(v, k - 1, d + 1) + 1;
      int y = x - k;
      while (x < n && y < m && a[static_cast<size_t>(x)] == b[static_cast<size_t>(y)]) ++x, ++y;
      next[static_cast<size_t>(k + d + 2)] = x;
      done = x >= n && y >= m;
    }
    if (done) break;
    v = std::move(next);
  }
  // Back from (n, m): each step d came down (an insertion) or right (a deletion) from diagonal
  // k + 1 or k - 1, after a run of equal lines.
  std::vector<Op> ops;
  int x = n, y = m;
  for (; d > 0; --d) {
    const std::vector<int>& w = trace[static_cast<size_t>(d)];
    const auto at = [&w, d](int k) { return w[static_cast<size_t>(k + d + 1)]; };
    const int k = x - y;
    const bool down = k == -d || (k != d && at(k - 1) < at(k + 1));
    const int prev_k = down ? k + 1 : k - 1;
    const int prev_x = at(prev_k);
    const int prev_y = prev_x - prev_k;
    const int mid_x = down ? prev_x : prev_x + 1;
    for (; x > mid_x; --x, --y) ops.push_back(Op::kKeep);
    ops.push_back(down ? Op::kInsert : Op::kDelete);
    x = prev_x;
    y = prev_y;
  }
  for (; x > 0; --x) ops.push_back(Op::kKeep);
  std::reverse(ops.begin(), ops.end());
  return ops;
}

/// One line of a hunk: its mark and text, and the marker for a last line without '\n'.
std::string HunkLine(char mark, std::string_view line) {
  std::string out(1, mark);
  out += line;
  if (line.empty() || line.back() != '\n') out += "\n\\ No newline at end of file\n";
  return out;
}

/// "a,b" of a hunk header: GNU diff writes "a" for one line and "a-1,0" for none.
std::string Range(int first, int count) {
  if (count == 1) return fmt::format("{}", first + 1);
  return fmt::format("{},{}", count == 0 ? first : first + 1, count);
}

}  // namespace

std::string UnifiedDiff(std::string_view before, std::string_view after, const std::string& from,
                        const std::string& to) {
  constexpr int kContext = 3;
  const std::vector<std::string_view> a = Lines(before), b = Lines(after);
  const std::vector<Op> ops = EditScript(a, b);
  std::string out;
  // Each op's line numbers in a and in b.
  std::vector<int> ia(ops.size() + 1), ib(ops.size() + 1);
  for (size_t i = 0; i < ops.size(); ++i) {
    ia[i + 1] = ia[i] + (ops[i] != Op::kInsert ? 1 : 0);
    ib[i + 1] = ib[i] + (ops[i] != Op::kDelete ? 1 : 0);
  }
  const auto n = static_cast<int>(ops.size());
  for (int i = 0; i < n;) {
    if (ops[static_cast<size_t>(i)] == Op::kKeep) {
      ++i;
      continue;
    }
    // A hunk: from kContext lines before this change to kContext after the last change that
    // is at most 2 kContext kept lines further on.
    const int begin = std::max(0, i - kContext);
    int end = i;
    for (int keep = 0; end < n && keep <= 2 * kContext; ++end) {
      keep = ops[static_cast<size_t>(end)] == Op::kKeep ? keep + 1 : 0;
    }
    while (end > i && ops[static_cast<size_t>(end - 1)] == Op::kKeep) --end;
    end = std::min(n, end + kContext);
    if (out.empty()) out = fmt::format("--- {}\n+++ {}\n", from, to);
    const auto sb = static_cast<size_t>(begin), se = static_cast<size_t>(end);
    out += fmt::format("@@ -{} +{} @@\n", Range(ia[sb], ia[se] - ia[sb]),
                       Range(ib[sb], ib[se] - ib[sb]));
    for (int j = begin; j < end; ++j) {
      const auto sj = static_cast<size_t>(j);
      const Op op = ops[sj];
      out += op == Op::kInsert   ? HunkLine('+', b[static_cast<size_t>(ib[sj])])
             : op == Op::kDelete ? HunkLine('-', a[static_cast<size_t>(ia[sj])])
                                 : HunkLine(' ', a[static_cast<size_t>(ia[sj])]);
    }
    i = end;
  }
  return out;
}

}  // namespace chasles::cli
