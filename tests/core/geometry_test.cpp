#include "core/geometry.hpp"

#include <gtest/gtest.h>

namespace plumekit {
namespace {

const Polygon kSquare{{0, 0}, {2, 0}, {2, 2}, {0, 2}};

TEST(Geometry, SignedAreaFollowsOrientation) {
  EXPECT_DOUBLE_EQ(signed_area(kSquare), 4.0);
  const Polygon cw(kSquare.rbegin(), kSquare.rend());
  EXPECT_DOUBLE_EQ(signed_area(cw), -4.0);
}

TEST(Geometry, LocateInsideOutsideAndBoundary) {
  EXPECT_EQ(locate(kSquare, {1, 1}), Location::Inside);
  EXPECT_EQ(locate(kSquare, {3, 1}), Location::Outside);
  EXPECT_EQ(locate(kSquare, {2, 1}), Location::Boundary);  // on an edge
  EXPECT_EQ(locate(kSquare, {0, 0}), Location::Boundary);  // at a vertex
  EXPECT_EQ(locate(kSquare, {-1, 0}), Location::Outside);  // on an edge's line, past its end
  // A ray through a vertex must not count it twice.
  const Polygon diamond{{1, 0}, {2, 1}, {1, 2}, {0, 1}};
  EXPECT_EQ(locate(diamond, {0.5, 1}), Location::Inside);
  EXPECT_EQ(locate(diamond, {-0.5, 1}), Location::Outside);
}

TEST(Geometry, LocateInConcavePolygon) {
  const Polygon u{{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  EXPECT_EQ(locate(u, {1.5, 2}), Location::Outside);  // in the U's notch
  EXPECT_EQ(locate(u, {0.5, 2}), Location::Inside);
  EXPECT_EQ(locate(u, {1.5, 1}), Location::Boundary);
}

TEST(Geometry, SegmentsIntersect) {
  EXPECT_TRUE(segments_intersect({0, 0}, {2, 2}, {0, 2}, {2, 0}));
  EXPECT_FALSE(segments_intersect({0, 0}, {1, 0}, {0, 1}, {1, 1}));
  EXPECT_TRUE(segments_intersect({0, 0}, {1, 0}, {1, 0}, {2, 5}));   // touch at an end
  EXPECT_TRUE(segments_intersect({0, 0}, {2, 0}, {1, 0}, {3, 0}));   // collinear overlap
  EXPECT_FALSE(segments_intersect({0, 0}, {1, 0}, {2, 0}, {3, 0}));  // collinear apart
}

TEST(Geometry, DistanceToSegment) {
  EXPECT_DOUBLE_EQ(distance_to_segment({1, 1}, {0, 0}, {2, 0}), 1.0);
  EXPECT_DOUBLE_EQ(distance_to_segment({3, 0}, {0, 0}, {2, 0}), 1.0);
  EXPECT_DOUBLE_EQ(distance_to_segment({0, 4}, {0, 0}, {0, 0}), 4.0);
}

TEST(Geometry, SimplePolygonsPass) {
  EXPECT_FALSE(simplicity_fault(kSquare));
  const Polygon l{{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}};
  EXPECT_FALSE(simplicity_fault(l));
  // Collinear consecutive vertices are fine.
  EXPECT_FALSE(simplicity_fault(Polygon{{0, 0}, {1, 0}, {2, 0}, {2, 1}, {0, 1}}));
}

TEST(Geometry, SimplicityFaultsAreNamed) {
  const auto bowtie = simplicity_fault({{0, 0}, {2, 2}, {2, 0}, {0, 2}});
  ASSERT_TRUE(bowtie);
  EXPECT_NE(bowtie->find("crosses"), std::string::npos) << *bowtie;
  EXPECT_NE(simplicity_fault({{0, 0}, {1, 0}})->find("at least 3"), std::string::npos);
  EXPECT_NE(simplicity_fault({{0, 0}, {1, 0}, {1, 0}, {0, 1}})->find("repeated"),
            std::string::npos);
  EXPECT_TRUE(simplicity_fault({{0, 0}, {1, 0}, {2, 0}}));  // all collinear
  // An edge that doubles back along the previous one.
  EXPECT_NE(simplicity_fault({{0, 0}, {2, 0}, {1, 0}, {1, 1}})->find("folds back"),
            std::string::npos);
  // Two non-adjacent edges touching at a point (a pinched polygon).
  const auto pinch = simplicity_fault({{0, 0}, {2, 0}, {1, 1}, {2, 2}, {0, 2}, {1, 1}});
  ASSERT_TRUE(pinch);
}

}  // namespace
}  // namespace plumekit
