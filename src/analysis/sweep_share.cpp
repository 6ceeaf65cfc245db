// A sweep split over several processes (chasles/analysis/sweep.h).

#include "chasles/analysis/sweep.h"

#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {

namespace {

constexpr std::string_view kMagic = "chasles-sweep-part-1";

class Writer {
 public:
  template <typename T>
  void Raw(const T& v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    out_.append(b, sizeof(T));
  }
  void Text(const std::string& s) {
    Raw<std::uint64_t>(s.size());
    out_ += s;
  }
  std::string& out() { return out_; }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(std::string_view in) : in_(in) {}
  template <typename T>
  T Raw() {
    Need(sizeof(T));
    T v;
    std::memcpy(&v, in_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  std::string Text() {
    const auto n = Raw<std::uint64_t>();
    Need(n);
    std::string s(in_.substr(at_, n));
    at_ += n;
    return s;
  }
  /// A count of items of at least `item` bytes each, checked against what is left.
  std::uint64_t Count(size_t item) {
    const auto n = Raw<std::uint64_t>();
    if (n > (in_.size() - at_) / item) Fail();
    return n;
  }
  bool done() const { return at_ == in_.size(); }
  [[noreturn]] void Fail() const {
    throw InputError(fmt::format("a sweep part of {} bytes is cut short or malformed at byte {}",
                                 in_.size(), at_));
  }

 private:
  void Need(std::uint64_t n) const {
    if (n > in_.size() - at_) Fail();
  }
  std::string_view in_;
  size_t at_ = 0;
};

}  // namespace

SweepPart TakeSweepPart(const SweepTable& table, const SweepShare& share,
                        const SweepWarnings& warnings) {
  SweepPart part;
  const auto n = static_cast<std::int64_t>(table.rows.size());
  for (std::int64_t i = 0, m = share.Count(n); i < m; ++i) {
    SweepPoint p;
    p.k = share.Point(i);
    const auto r = static_cast<size_t>(p.k);
    p.values = table.rows[r];
    if (r < table.errors.size()) p.error = table.errors[r];
    if (const auto w = warnings.find(p.k); w != warnings.end()) p.warnings = w->second;
    part.points.push_back(std::move(p));
  }
  return part;
}

std::string EncodeSweepPart(const SweepPart& part) {
  Writer w;
  w.Text(std::string(kMagic));
  w.Raw<std::int32_t>(part.code);
  w.Text(part.message);
  w.Raw<std::int64_t>(part.failed_at);
  w.Raw<std::uint8_t>(part.check_failed ? 1 : 0);
  w.Raw<std::uint64_t>(part.points.size());
  for (const SweepPoint& p : part.points) {
    w.Raw<std::int64_t>(p.k);
    w.Raw<std::uint64_t>(p.values.size());
    for (const double v : p.values) w.Raw<double>(v);
    w.Text(p.error);
    w.Raw<std::uint64_t>(p.warnings.size());
    for (const std::string& s : p.warnings) w.Text(s);
  }
  return std::move(w.out());
}

SweepPart DecodeSweepPart(std::string_view bytes) {
  Reader r(bytes);
  if (r.Text() != kMagic) r.Fail();
  SweepPart part;
  part.code = r.Raw<std::int32_t>();
  part.message = r.Text();
  part.failed_at = r.Raw<std::int64_t>();
  part.check_failed = r.Raw<std::uint8_t>() != 0;
  // Each point is at least its index, two counts and an empty error's length: 32 bytes.
  for (std::uint64_t i = 0, n = r.Count(32); i < n; ++i) {
    SweepPoint p;
    p.k = r.Raw<std::int64_t>();
    for (std::uint64_t j = 0, m = r.Count(sizeof(double)); j < m; ++j) {
      p.values.push_back(r.Raw<double>());
    }
    p.error = r.Text();
    for (std::uint64_t j = 0, m = r.Count(sizeof(std::uint64_t)); j < m; ++j) {
      p.warnings.push_back(r.Text());
    }
    part.points.push_back(std::move(p));
  }
  if (!r.done()) r.Fail();
  return part;
}

const SweepPart* FirstFailure(const std::vector<SweepPart>& parts) {
  const SweepPart* first = nullptr;
  for (const SweepPart& p : parts) {
    if (p.code != 0 && (!first || p.failed_at < first->failed_at)) first = &p;
  }
  return first;
}

void MergeSweepParts(const std::vector<SweepPart>& parts, SweepTable* table,
                     SweepWarnings* warnings) {
  const size_t n = table->rows.size();
  std::vector<bool> given(n, false);
  warnings->clear();
  for (const SweepPart& part : parts) {
    for (const SweepPoint& p : part.points) {
      const auto r = static_cast<size_t>(p.k);
      if (p.k < 0 || r >= n || given[r]) {
        throw std::logic_error(
            fmt::format("sweep point {} given twice or outside the {} rows", p.k, n));
      }
      given[r] = true;
      table->rows[r] = p.values;
      if (!table->errors.empty()) table->errors[r] = p.error;
      if (!p.warnings.empty()) (*warnings)[p.k] = p.warnings;
    }
  }
  for (size_t r = 0; r < n; ++r) {
    if (!given[r]) throw std::logic_error(fmt::format("no process gave sweep point {}", r));
  }
  if (table->errors.empty()) {
    // A solve sweep: its warnings, one per failed check, in grid order.
    table->warnings.clear();
    for (const auto& [k, list] : *warnings) {
      table->warnings.insert(table->warnings.end(), list.begin(), list.end());
    }
    table->failed = !table->warnings.empty();
  }
}

}  // namespace chasles
