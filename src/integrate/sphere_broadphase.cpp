// The broadphase: a grid in the plane, each ball's box over its horizon, and the exact pair
// tests of the balls whose boxes overlap (docs/contact.md, "Event-driven spheres").
#include "integrate/internal/sphere_runner.h"

namespace chasles::sphere_events_detail {

// The ball's box in the plane over [t, horizon], its cells, and the exact tests against the
// balls whose boxes overlap it. The horizon is where the ball has moved about half a cell.
void Runner::RenewBox(int i, double t) {
  const auto iu = static_cast<size_t>(i);
  const Ball& b = balls_[iu];
  const Chain& c = chain_[iu];
  const Segment& s = c.At(t);
  const Vec3 v = s.Vel(t);
  const double speed = (v - w_.n.dot(v) * w_.n).norm();
  double h = s.phase == Phase::kRest ? kInf : t + 0.5 * cell_ / std::max(speed, 1e-300);
  h = std::min({h, c.known_until, options_.t_end});
  Box box;
  // A ball that is slow now may not stay slow (a backspin ball speeding up): the horizon is
  // shortened until the box covers at most 4 x 4 cells. Any box is correct (the pair tests
  // are exact); its size only sets the work.
  for (;;) {
    box = Box{kInf, -kInf, kInf, -kInf};
    for (int k = 0; k < c.count; ++k) {
      const Segment& sk = c.seg[static_cast<size_t>(k)];
      if (sk.end() < t && k + 1 < c.count) continue;  // over before t
      const double ta = std::max(t, sk.t0), tb = std::min(h, sk.end());
      if (ta > tb) break;
      Extend(w_.e1.dot(sk.r0), w_.e1.dot(sk.v0), w_.e1.dot(sk.a), ta - sk.t0, tb - sk.t0, box.lo1,
             box.hi1);
      Extend(w_.e2.dot(sk.r0), w_.e2.dot(sk.v0), w_.e2.dot(sk.a), ta - sk.t0, tb - sk.t0, box.lo2,
             box.hi2);
    }
    const double pad = b.R * (1.0 + 1e-9) + w_.tol.gap;
    box.lo1 -= pad, box.lo2 -= pad, box.hi1 += pad, box.hi2 += pad;
    const bool small = box.hi1 - box.lo1 <= 3.0 * cell_ && box.hi2 - box.lo2 <= 3.0 * cell_;
    if (small || !(h > t) || (h - t) < 1e-9 * std::max(1.0, std::abs(t))) break;
    h = t + 0.25 * (h - t);
  }
  // Move the ball's cell entries.
  RemoveFromGrid(i);
  std::array<int, 4>& cells = cells_of_[iu];
  cells = {Cell(box.lo1), Cell(box.hi1), Cell(box.lo2), Cell(box.hi2)};
  box_[iu] = box;
  horizon_[iu] = h;
  ++res_.stats.box_renewals;
  ++stamp_now_;
  stamp_[iu] = stamp_now_;
  for (int x = cells[0]; x <= cells[1]; ++x) {
    for (int y = cells[2]; y <= cells[3]; ++y) {
      std::vector<int>& v = grid_[CellKey(x, y)];
      for (const int j : v) {
        const auto ju = static_cast<size_t>(j);
        if (stamp_[ju] == stamp_now_) continue;
        stamp_[ju] = stamp_now_;
        if (box_[ju].Overlaps(box)) TestPair(i, j, t);
      }
      v.push_back(i);
    }
  }
  if (std::isfinite(h) && h < options_.t_end && h < c.known_until) {
    Schedule({h, Kind::kHorizon, i, -1, ver_[iu], 0, 0});
  }
  renewed_.push_back(i);
  renew_tick_[iu] = ++tick_;
}

void Runner::RemoveFromGrid(int i) {
  std::array<int, 4>& cells = cells_of_[static_cast<size_t>(i)];
  for (int x = cells[0]; x <= cells[1]; ++x) {
    for (int y = cells[2]; y <= cells[3]; ++y) {
      std::vector<int>& v = grid_[CellKey(x, y)];
      const auto it = std::find(v.begin(), v.end(), i);
      if (it != v.end()) {
        *it = v.back();
        v.pop_back();
      }
    }
  }
  cells = {0, -1, 0, -1};
}

// The outside balls whose boxes overlap `box`, in index order.
std::vector<int> Runner::BallsIn(const Box& box) const {
  std::vector<int> near;
  for (int x = Cell(box.lo1); x <= Cell(box.hi1); ++x) {
    for (int y = Cell(box.lo2); y <= Cell(box.hi2); ++y) {
      const auto it = grid_.find(CellKey(x, y));
      if (it == grid_.end()) continue;
      for (const int o : it->second) {
        if (box_[static_cast<size_t>(o)].Overlaps(box) &&
            std::find(near.begin(), near.end(), o) == near.end()) {
          near.push_back(o);
        }
      }
    }
  }
  std::sort(near.begin(), near.end());
  return near;
}

}  // namespace chasles::sphere_events_detail
