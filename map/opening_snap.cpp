#include "map/opening_snap.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

#include "core/error.hpp"

namespace plumekit {

namespace {

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, sep))
    parts.push_back(part);
  if (!text.empty() && text.back() == sep) parts.push_back("");
  return parts;
}

bool parse_number(const std::string& text, double& out) {
  std::size_t used = 0;
  try {
    out = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  while (used < text.size() && std::isspace(static_cast<unsigned char>(text[used])))
    ++used;
  return used == text.size() && std::isfinite(out);
}

// The occupancy along one pixel-edge line. Positions are pixel corners:
// u = column edge (0..cols), v = row edge counted up from the image's bottom.
struct Lines {
  const cv::Mat& occ;
  bool vertical;
  int along_extent() const { return vertical ? occ.rows : occ.cols; }
  int across_extent() const { return vertical ? occ.cols : occ.rows; }
  // The pixel `along` units along and `across` across: 0 free, 1 occupied or outside.
  bool blocked(int along, int across) const {
    const int c = vertical ? across : along;
    const int j = vertical ? along : across;
    if (c < 0 || j < 0 || c >= occ.cols || j >= occ.rows) return true;
    return occ.at<uchar>(occ.rows - 1 - j, c) != 0;
  }
  // +1: free on the + side of line `line` at unit `k`, -1: free on the - side, 0: no boundary.
  int side(int line, int k) const {
    if (k < 0 || k >= along_extent()) return 0;
    const bool minus = blocked(k, line - 1), plus = blocked(k, line);
    return minus == plus ? 0 : (plus ? -1 : 1);
  }
};

std::string metres(double m) {
  std::ostringstream s;
  s << std::setprecision(3) << m << " m";
  return s.str();
}

std::string pixels(double px) {
  std::ostringstream s;
  s << std::setprecision(3) << px << " px";
  return s.str();
}

[[noreturn]] void refuse(const OpeningRequest& r, const std::string& why) {
  throw OptionError(r.field, "'" + r.text + "': " + why);
}

struct Choice {
  int line = 0;
  int side = 0;
  int score = 0;
};

// The line within the tolerance with the most boundary along [klo, khi), the nearest on a tie.
Choice best_line(const Lines& lines, double line0, double tolerance_px, int klo, int khi) {
  Choice best;
  const int first = std::max(0, static_cast<int>(std::ceil(line0 - tolerance_px)));
  const int last =
      std::min(lines.across_extent(), static_cast<int>(std::floor(line0 + tolerance_px)));
  for (int line = first; line <= last; ++line) {
    int plus = 0, minus = 0;
    for (int k = klo; k < khi; ++k) {
      const int s = lines.side(line, k);
      plus += s > 0;
      minus += s < 0;
    }
    const Choice c{line, plus >= minus ? 1 : -1, std::max(plus, minus)};
    if (c.score > best.score || (c.score == best.score && c.score > 0 &&
                                 std::abs(line - line0) < std::abs(best.line - line0)))
      best = c;
  }
  return best;
}

}  // namespace

OpeningRequest parse_opening(const std::string& text, OpeningKind kind, const std::string& field) {
  OpeningRequest r;
  r.field = field;
  r.text = text;
  r.kind = kind;
  const std::vector<std::string> parts = split(text, ',');
  const bool inlet = kind == OpeningKind::Inlet;
  if (parts.size() < 4 || parts.size() > (inlet ? 6u : 4u))
    refuse(r, inlet ? "expected X1,Y1,X2,Y2[,SPEED[,PROFILE]] (metres, map frame; m/s; "
                      "uniform or parabolic)"
                    : "expected X1,Y1,X2,Y2 (metres, map frame)");
  double v[5] = {0, 0, 0, 0, 1.0};
  for (std::size_t k = 0; k < std::min<std::size_t>(parts.size(), 5); ++k)
    if (!parse_number(parts[k], v[k])) refuse(r, "'" + parts[k] + "' is not a finite number");
  r.from = {v[0], v[1]};
  r.to = {v[2], v[3]};
  r.speed = v[4];
  if (!(r.speed > 0)) refuse(r, "the speed must be a positive number of m/s");
  if (r.speed > kMaxInletSpeed)
    refuse(r, "the speed " + parts[4] + " m/s is too fast; an inlet blows " + kInletSpeedBound);
  if (parts.size() == 6) {
    if (parts[5] == "uniform")
      r.profile = Profile::Uniform;
    else if (parts[5] == "parabolic")
      r.profile = Profile::Parabolic;
    else
      refuse(r, "profile '" + parts[5] + "' is not uniform or parabolic");
  }
  return r;
}

SnappedOpening snap_opening(const OccupancyImage& image, const OpeningRequest& request,
                            double tolerance_px) {
  const double res = image.resolution;
  const Vec2 a = (1.0 / res) * (request.from - image.origin);
  const Vec2 b = (1.0 / res) * (request.to - image.origin);
  const bool vertical = std::abs(b.y - a.y) >= std::abs(b.x - a.x);
  const double across_a = vertical ? a.x : a.y, across_b = vertical ? b.x : b.y;
  const double along_a = vertical ? a.y : a.x, along_b = vertical ? b.y : b.x;
  if (std::abs(across_a - across_b) > tolerance_px)
    refuse(request, "not parallel to an axis (its ends differ by " +
                        metres(std::abs(across_a - across_b) * res) + " across); openings run " +
                        "along x or along y");
  const Lines lines{image.occupied, vertical};
  const int klo = std::max(0, static_cast<int>(std::lround(std::min(along_a, along_b))));
  const int khi =
      std::min(lines.along_extent(), static_cast<int>(std::lround(std::max(along_a, along_b))));
  if (khi - klo < 1)
    refuse(request, "shorter than one pixel (" + metres(res) + "), or outside the map");
  const double line0 = 0.5 * (across_a + across_b);
  const Choice c = best_line(lines, line0, tolerance_px, klo, khi);
  if (c.score == 0)
    refuse(request,
           "no boundary of the free space (an arena wall or an obstacle's edge with free "
           "space beside it) lies within " +
               pixels(tolerance_px) + " (" + metres(tolerance_px * res) + ") of it");
  // The longest run with the chosen free side, then grown past the request's ends.
  int start = klo, end = klo, run = klo;
  for (int k = klo; k <= khi; ++k) {
    if (k < khi && lines.side(c.line, k) == c.side) continue;
    if (k - run > end - start) start = run, end = k;
    run = k + 1;
  }
  // An end moves out only onto the stretch's own end (a door's jamb) within
  // the tolerance: a stretch that runs on stays cut where the user cut it, so
  // that a door split into two openings stays split.
  const int reach = static_cast<int>(std::floor(tolerance_px));
  int grown = start;
  while (grown > start - reach - 1 && lines.side(c.line, grown - 1) == c.side)
    --grown;
  if (grown >= start - reach) start = grown;
  grown = end;
  while (grown < end + reach + 1 && lines.side(c.line, grown) == c.side)
    ++grown;
  if (grown <= end + reach) end = grown;

  SnappedOpening s;
  s.request = request;
  Opening& o = s.opening;
  o.kind = request.kind;
  o.speed = request.speed;
  o.profile = request.profile;
  const double line = c.line * res;
  o.from = vertical ? Vec2{line, start * res} : Vec2{start * res, line};
  o.to = vertical ? Vec2{line, end * res} : Vec2{end * res, line};
  s.shift_m = (c.line - line0) * res;
  s.trimmed_m = (std::abs(along_b - along_a) - (end - start)) * res;
  return s;
}

}  // namespace plumekit
