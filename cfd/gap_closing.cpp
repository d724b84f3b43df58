#include "cfd/gap_closing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <unordered_map>

#include "core/option_check.hpp"

namespace plumekit::cfd {

namespace {

constexpr Side kSides[] = {Side::Left, Side::Right, Side::Bottom, Side::Top};

struct Segment {
  Vec2 p, q;
  int obstacle;
};

// The obstacles' edges in square buckets `size` metres wide over the arena
// (edges beyond it go to the border buckets), in compressed rows.
class SegmentBuckets {
 public:
  SegmentBuckets(const Map& map, double size) : size_(size) {
    nx_ = std::max(1, static_cast<int>(std::ceil(map.width / size)));
    ny_ = std::max(1, static_cast<int>(std::ceil(map.height / size)));
    for (std::size_t o = 0; o < map.obstacles.size(); ++o) {
      const Polygon& poly = map.obstacles[o];
      for (std::size_t k = 0; k < poly.size(); ++k)
        segments_.push_back({poly[k], poly[(k + 1) % poly.size()], static_cast<int>(o)});
    }
    start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<int> fill(start_.begin(), start_.end() - 1);
      for (std::size_t s = 0; s < segments_.size(); ++s)
        for_buckets(box_of(segments_[s], 0.0), [&](std::size_t b) {
          if (pass == 0)
            ++start_[b + 1];
          else
            items_[static_cast<std::size_t>(fill[b]++)] = static_cast<int>(s);
        });
      if (pass == 0) {
        for (std::size_t b = 1; b < start_.size(); ++b)
          start_[b] += start_[b - 1];
        items_.resize(static_cast<std::size_t>(start_.back()));
      }
    }
  }

  const std::vector<Segment>& segments() const { return segments_; }
  static Box box_of(const Segment& s, double margin) {
    return {{std::min(s.p.x, s.q.x) - margin, std::min(s.p.y, s.q.y) - margin},
            {std::max(s.p.x, s.q.x) + margin, std::max(s.p.y, s.q.y) + margin}};
  }
  // Calls f(segment index) for each segment in a bucket that `box` overlaps
  // (a segment may come more than once).
  template <class F>
  void visit(const Box& box, F f) const {
    for_buckets(box, [&](std::size_t b) {
      for (int k = start_[b]; k < start_[b + 1]; ++k)
        f(items_[static_cast<std::size_t>(k)]);
    });
  }

 private:
  int clamp(double v, int n) const {
    return std::clamp(static_cast<int>(std::floor(v / size_)), 0, n - 1);
  }
  template <class F>
  void for_buckets(const Box& box, F f) const {
    const int i0 = clamp(box.lo.x, nx_), i1 = clamp(box.hi.x, nx_);
    const int j0 = clamp(box.lo.y, ny_), j1 = clamp(box.hi.y, ny_);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        f(static_cast<std::size_t>(j) * nx_ + i);
  }

  double size_;
  int nx_ = 1, ny_ = 1;
  std::vector<Segment> segments_;
  std::vector<int> start_, items_;
};

Vec2 closest_on_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  if (len2 == 0.0) return a;
  const double t = std::clamp(dot(p - a, ab) / len2, 0.0, 1.0);
  return a + t * ab;
}

struct Closest {
  double d = HUGE_VAL;
  Vec2 at;
  double overlap = 0.0;  // m: how long two parallel edges face each other
};

// The shortest distance between segments ab and cd, and the point midway
// between their closest points: for parallel edges that face each other, the
// middle of the stretch they share (a gap's middle rather than its end).
Closest segment_pair(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  if (segments_intersect(a, b, c, d)) return {0.0, a, 0.0};
  Closest best;
  auto consider = [&](Vec2 p, Vec2 s0, Vec2 s1) {
    const Vec2 q = closest_on_segment(p, s0, s1);
    const double dist = norm(q - p);
    if (dist < best.d) best = {dist, 0.5 * (p + q), 0.0};
  };
  consider(a, c, d);
  consider(b, c, d);
  consider(c, a, b);
  consider(d, a, b);
  const Vec2 ab = b - a, cd = d - c;
  const double len2 = dot(ab, ab);
  if (len2 > 0.0 && std::abs(cross(ab, cd)) <= 1e-12 * std::sqrt(len2 * dot(cd, cd))) {
    const double tc = dot(c - a, ab) / len2, td = dot(d - a, ab) / len2;
    const double lo = std::max(0.0, std::min(tc, td)), hi = std::min(1.0, std::max(tc, td));
    if (hi > lo) {
      const Vec2 p = a + 0.5 * (lo + hi) * ab;
      best.at = 0.5 * (p + closest_on_segment(p, c, d));
      best.overlap = (hi - lo) * std::sqrt(len2);
    }
  }
  return best;
}

// Keeps the shortest distance; among edge pairs at the same distance (to
// round-off), the place where edges face each other longest.
void merge(Closest& best, const Closest& c) {
  const bool tie = best.d < HUGE_VAL && std::abs(c.d - best.d) <= 1e-12 * std::max(c.d, best.d);
  if (!tie) {
    if (c.d < best.d) best = c;
    return;
  }
  if (c.overlap > best.overlap) best.at = c.at, best.overlap = c.overlap;
  best.d = std::min(best.d, c.d);
}

// Features closer than h * kGapTolerance touch: imported outlines that share
// an edge can come out 1e-15 m apart.
bool narrow(double d, double h) {
  return d > h * kGapTolerance && d < h * (1.0 - kGapTolerance);
}

// Feature ids: obstacles 0..P-1, then the four walls P..P+3 (Side order).
int wall_feature(const Map& map, Side side) {
  return static_cast<int>(map.obstacles.size()) + static_cast<int>(side);
}

GapReport make_report(const Map& map, int fa, int fb, const Closest& c) {
  GapReport r;
  r.a = fa;
  const int walls = static_cast<int>(map.obstacles.size());
  if (fb >= walls)
    r.wall = kSides[fb - walls];
  else
    r.b = fb;
  r.width = c.d;
  r.at = c.at;
  return r;
}

// The shortest distance from an obstacle to one wall (at a vertex), with the
// point midway between the wall and the middle of the nearest vertices (an
// edge along the wall: its middle).
Closest wall_gap(const Map& map, const Polygon& poly, Side side) {
  const bool vertical = side == Side::Left || side == Side::Right;
  auto distance = [&](Vec2 v) {
    return side == Side::Left     ? v.x
           : side == Side::Right  ? map.width - v.x
           : side == Side::Bottom ? v.y
                                  : map.height - v.y;
  };
  Closest best;
  for (Vec2 v : poly)
    best.d = std::min(best.d, distance(v));
  double lo = HUGE_VAL, hi = -HUGE_VAL;  // along the wall, over the nearest vertices
  for (Vec2 v : poly)
    if (distance(v) <= best.d + 1e-12 * std::max(1.0, std::abs(best.d))) {
      lo = std::min(lo, vertical ? v.y : v.x);
      hi = std::max(hi, vertical ? v.y : v.x);
    }
  const double along = 0.5 * (lo + hi);
  const double across = side == Side::Left     ? 0.5 * best.d
                        : side == Side::Right  ? map.width - 0.5 * best.d
                        : side == Side::Bottom ? 0.5 * best.d
                                               : map.height - 0.5 * best.d;
  best.at = vertical ? Vec2{across, along} : Vec2{along, across};
  return best;
}

// One obstacle inside another (no edge crossing) is not a gap: it is solid.
bool nested(const Map& map, int a, int b) {
  const Polygon &pa = map.obstacles[static_cast<std::size_t>(a)],
                &pb = map.obstacles[static_cast<std::size_t>(b)];
  return (!pb.empty() && covers(pa, pb[0])) || (!pa.empty() && covers(pb, pa[0]));
}

void sort_narrowest_first(const Map& map, std::vector<GapReport>& gaps) {
  auto other = [&](const GapReport& g) { return g.wall ? wall_feature(map, *g.wall) : g.b; };
  std::sort(gaps.begin(), gaps.end(), [&](const GapReport& x, const GapReport& y) {
    if (x.width != y.width) return x.width < y.width;
    if (x.a != y.a) return x.a < y.a;
    return other(x) < other(y);
  });
}

std::uint64_t pair_key(int a, int b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) |
         static_cast<std::uint32_t>(std::max(a, b));
}

// The obstacle pairs less than h apart (nearest points), through the buckets.
std::unordered_map<std::uint64_t, Closest> close_pairs(const SegmentBuckets& buckets, double h) {
  std::unordered_map<std::uint64_t, Closest> pairs;
  const std::vector<Segment>& segs = buckets.segments();
  std::vector<int> stamp(segs.size(), -1);
  for (std::size_t s = 0; s < segs.size(); ++s) {
    const Segment& e = segs[s];
    buckets.visit(SegmentBuckets::box_of(e, h), [&](int t) {
      const Segment& f = segs[static_cast<std::size_t>(t)];
      if (f.obstacle <= e.obstacle || stamp[static_cast<std::size_t>(t)] == static_cast<int>(s))
        return;
      stamp[static_cast<std::size_t>(t)] = static_cast<int>(s);
      const Closest c = segment_pair(e.p, e.q, f.p, f.q);
      if (c.d >= h) return;
      merge(pairs.try_emplace(pair_key(e.obstacle, f.obstacle)).first->second, c);
    });
  }
  return pairs;
}

std::vector<GapReport> narrow_gaps(const Map& map, const SegmentBuckets& buckets, double h) {
  std::vector<GapReport> gaps;
  for (const auto& [key, c] : close_pairs(buckets, h)) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    if (narrow(c.d, h) && !nested(map, a, b)) gaps.push_back(make_report(map, a, b, c));
  }
  for (std::size_t o = 0; o < map.obstacles.size(); ++o)
    for (Side side : kSides) {
      const Closest c = wall_gap(map, map.obstacles[o], side);
      if (narrow(c.d, h))
        gaps.push_back(make_report(map, static_cast<int>(o), wall_feature(map, side), c));
    }
  sort_narrowest_first(map, gaps);
  return gaps;
}

double cell_size(const GridShape& shape) {
  return std::max(shape.dx(), shape.dy());
}

// A feature near a point, and its distance.
struct Near {
  int feature;
  double d;
};

// The features (of those flagged in `involved`) less than h from p, each with
// its shortest distance.
void features_near(const Map& map, const SegmentBuckets& buckets, const std::vector<char>& involved,
                   Vec2 p, double h, std::vector<Near>& out) {
  out.clear();
  auto add = [&](int feature, double d) {
    if (d >= h) return;
    for (Near& n : out)
      if (n.feature == feature) return void(n.d = std::min(n.d, d));
    out.push_back({feature, d});
  };
  buckets.visit({{p.x - h, p.y - h}, {p.x + h, p.y + h}}, [&](int t) {
    const Segment& s = buckets.segments()[static_cast<std::size_t>(t)];
    if (involved[static_cast<std::size_t>(s.obstacle)])
      add(s.obstacle, distance_to_segment(p, s.p, s.q));
  });
  const double wall_d[] = {p.x, map.width - p.x, p.y, map.height - p.y};
  for (Side side : kSides)
    if (involved[static_cast<std::size_t>(wall_feature(map, side))])
      add(wall_feature(map, side), wall_d[static_cast<int>(side)]);
}

}  // namespace

std::string millimetre_coordinate(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  std::string s = buf;
  while (s.back() == '0')
    s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

std::vector<GapReport> find_narrow_gaps(const Map& map, const GridShape& shape) {
  const double h = cell_size(shape);
  return narrow_gaps(map, SegmentBuckets(map, h), h);
}

std::vector<GapReport> close_narrow_gaps(const Map& map, const GridShape& shape,
                                         std::vector<std::uint8_t>& solid,
                                         std::vector<int>* closed_by) {
  if (closed_by) closed_by->assign(shape.size(), -1);
  const double h = cell_size(shape);
  const SegmentBuckets buckets(map, h);
  std::vector<GapReport> gaps = narrow_gaps(map, buckets, h);
  if (gaps.empty()) return gaps;
  // Which features take part in a narrow gap, and which gap each pair is.
  std::vector<char> involved(map.obstacles.size() + 4, 0);
  std::unordered_map<std::uint64_t, std::size_t> gap_of;
  for (std::size_t g = 0; g < gaps.size(); ++g) {
    const int other = gaps[g].wall ? wall_feature(map, *gaps[g].wall) : gaps[g].b;
    involved[static_cast<std::size_t>(gaps[g].a)] = involved[static_cast<std::size_t>(other)] = 1;
    gap_of.emplace(pair_key(gaps[g].a, other), g);
  }
  std::vector<Near> near;
  for (int j = 0; j < shape.ny; ++j)
    for (int i = 0; i < shape.nx; ++i) {
      std::uint8_t& cell = solid[shape.index(i, j)];
      if (cell) continue;
      features_near(map, buckets, involved, shape.centre(i, j), h, near);
      for (std::size_t x = 0; x < near.size() && !cell; ++x)
        for (std::size_t y = x + 1; y < near.size() && !cell; ++y) {
          if (near[x].d + near[y].d >= h) continue;
          const auto it = gap_of.find(pair_key(near[x].feature, near[y].feature));
          if (it == gap_of.end()) continue;
          cell = 1;
          ++gaps[it->second].cells_closed;
          if (closed_by) (*closed_by)[shape.index(i, j)] = static_cast<int>(it->second);
        }
    }
  return gaps;
}

std::vector<GapReport> find_narrow_gaps_brute_force(const Map& map, const GridShape& shape) {
  const double h = cell_size(shape);
  std::vector<GapReport> gaps;
  const int n = static_cast<int>(map.obstacles.size());
  for (int a = 0; a < n; ++a) {
    const Polygon& p = map.obstacles[static_cast<std::size_t>(a)];
    for (int b = a + 1; b < n; ++b) {
      const Polygon& q = map.obstacles[static_cast<std::size_t>(b)];
      Closest best;
      for (std::size_t i = 0; i < p.size(); ++i)
        for (std::size_t j = 0; j < q.size(); ++j) {
          merge(best, segment_pair(p[i], p[(i + 1) % p.size()], q[j], q[(j + 1) % q.size()]));
        }
      if (narrow(best.d, h) && !nested(map, a, b)) gaps.push_back(make_report(map, a, b, best));
    }
    for (Side side : kSides) {
      const Closest c = wall_gap(map, p, side);
      if (narrow(c.d, h)) gaps.push_back(make_report(map, a, wall_feature(map, side), c));
    }
  }
  sort_narrowest_first(map, gaps);
  return gaps;
}

std::string describe_gap(const Map& map, const GapReport& gap) {
  std::ostringstream s;
  const Vec2 at = map.to_frame(gap.at);
  s << "obstacles[" << gap.a << "] and ";
  if (gap.wall)
    s << "the " << to_string(*gap.wall) << " wall";
  else
    s << "obstacles[" << gap.b << "]";
  s << ", " << compact(gap.width) << " m apart at (" << millimetre_coordinate(at.x) << ", "
    << millimetre_coordinate(at.y) << ")";
  return s.str();
}

double cell_keeping_gaps_open(const Map& map, double narrowest) {
  auto works = [&](double cell) {
    const GridShape s = GridShape::with_cell(map.width, map.height, cell);
    return cell_size(s) * (1.0 - kGapTolerance) <= narrowest;
  };
  double scale = std::pow(10.0, std::floor(std::log10(narrowest)) - 1);
  double cell = std::floor(narrowest / scale * (1.0 + 1e-9)) * scale;
  // Each side's count is rounded, which may stretch the cells: step down until they fit.
  for (int k = 0; k < 1000 && !works(cell); ++k) {
    if (cell - scale <= 0.0) scale /= 10.0;
    cell -= scale;
  }
  return cell;
}

ClosedGaps summarize_gaps(const Map& map, const std::vector<GapReport>& gaps) {
  ClosedGaps out;
  out.count = static_cast<int>(gaps.size());
  for (std::size_t k = 0; k < gaps.size() && k < kReportedGaps; ++k) {
    std::string between = describe_gap(map, gaps[k]);
    between.erase(between.find(", "));  // the width and place have their own fields
    out.narrowest.push_back({between, gaps[k].width, map.to_frame(gaps[k].at)});
  }
  if (!gaps.empty()) out.open_cell = cell_keeping_gaps_open(map, gaps.front().width);
  return out;
}

std::string closed_gaps_text(const ClosedGaps& gaps, double cell) {
  if (gaps.count == 0) return "";
  std::ostringstream s;
  s << "closed " << gaps.count << (gaps.count == 1 ? " gap" : " gaps") << " narrower than the "
    << compact(cell) << " m cell (open in the map)";
  for (std::size_t k = 0; k < gaps.narrowest.size(); ++k) {
    const ClosedGap& g = gaps.narrowest[k];
    s << (k == 0 ? ": " : "; ") << g.between << ", " << compact(g.width) << " m apart at ("
      << millimetre_coordinate(g.at.x) << ", " << millimetre_coordinate(g.at.y) << ")";
  }
  if (static_cast<std::size_t>(gaps.count) > gaps.narrowest.size())
    s << "; and " << gaps.count - static_cast<int>(gaps.narrowest.size()) << " wider";
  s << "; a cell of " << compact(gaps.open_cell) << " m keeps "
    << (gaps.count == 1 ? "it" : "them all") << " open";
  return s.str();
}

}  // namespace plumekit::cfd
