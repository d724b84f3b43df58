#pragma once
// A grid roadmap over the inflated free space: the centres of a square
// lattice that lie in free space, each joined to its 8 neighbours when the
// segment between them stays free. One Dijkstra pass from the robot gives the
// travel distance to every node at once, which is what ranking goals spread
// over a whole floor needs (one planner query per goal would cost hundreds
// of queries per decision). Distances are along the lattice's 8 directions, so
// they exceed the shortest path's by at most about 8 % (1 / cos 22.5 deg).
#include <limits>
#include <vector>

#include "core/geometry.hpp"
#include "planner/free_space.hpp"

namespace plumekit::planner {

class GridRoadmap {
 public:
  // `spacing`: the lattice's cell, metres (> 0).
  GridRoadmap(const FreeSpace& space, double spacing);

  double spacing() const { return spacing_; }
  // The lattice's point (column 0, row 0); node k lies at origin() + spacing() (column, row).
  Vec2 origin() const { return first_; }
  std::size_t size() const { return nodes_.size(); }
  Vec2 node(std::size_t k) const { return nodes_[k]; }
  // Lattice column and row of node k.
  int column(std::size_t k) const { return cell_[k] % nx_; }
  int row(std::size_t k) const { return cell_[k] / nx_; }

  // Travel distance from `from` to every node: the straight segment to the
  // nearest nodes it sees free (up to one lattice cell away), then the
  // roadmap. Unreachable nodes get infinity. With `previous`, each node's predecessor on its
  // shortest way (-1 for a node reached straight from `from`, or unreached).
  std::vector<double> distances_from(Vec2 from, std::vector<int>* previous = nullptr) const;

  static constexpr double kUnreachable = std::numeric_limits<double>::infinity();

 private:
  struct Link {
    int to;
    double length;
  };
  const FreeSpace& space_;
  double spacing_;
  int nx_ = 0, ny_ = 0;
  Vec2 first_;  // the lattice's first point, (column 0, row 0)
  std::vector<Vec2> nodes_;
  std::vector<int> cell_;        // per node: its lattice cell j * nx + i
  std::vector<int> node_of_;     // per lattice cell: its node, or -1
  std::vector<int> link_begin_;  // per node, into links_ (CSR)
  std::vector<Link> links_;
};

}  // namespace plumekit::planner
