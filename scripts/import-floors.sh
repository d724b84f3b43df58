#!/usr/bin/env bash
# The real floors of issue 17's evaluation, data/floors/*.json, from the ROS maps in REAL_MAPS
# (default data/real-maps; their README has the attribution): each map_server map imported in
# its own ROS map frame with the openings of docs/real-maps.md, and ground-truth sources and robot
# starts placed by hand in free space (docs/validation.md, "Floors"). Every coordinate is in the map
# frame. Run it to rebuild the committed files; it writes only data/floors/ (files plumekit wrote).
set -euo pipefail
cd "$(dirname "$0")/.."
real=${REAL_MAPS:-data/real-maps}
[ -x build/plumekit ] || bash scripts/build.sh
mkdir -p data/floors

# The TurtleBot3 arena: a closed 5.5 x 5 m hexagon with nine pillars; vents in its flat bottom and
# top walls. Sources by the walls, between pillars and in the vents' stream.
./build/plumekit map import-ros "$real/tb3_world/map.yaml" --name tb3_world --out data/floors/tb3_world.json \
  --inlet -1,-2.5,1,-2.5 --outlet -1,2.5,1,2.5 \
  --source=-2.0,0.5 --source=1.9,-0.6 --source=0.55,1.75 --source=-0.55,-1.7 --source=1.6,1.3 \
  --source=-1.6,-0.6 \
  --start=0.55,-0.55 --start=-1.9,-1.2 --start=2.0,0.6 --start=-0.55,1.75

# Nav2's depot (30.2 x 15.35 m): a hall with pallets and pillars, in through the left wall and out
# through the right one. Sources in the open hall, between pallets and by the walls.
./build/plumekit map import-ros "$real/depot/depot.yaml" --out data/floors/depot.json \
  --close-gaps 0.2 --inlet=-6.95,-3,-6.95,3 --outlet 22.95,-3,22.95,3 \
  --source 2,0 --source 10,3.5 --source 12.6,-4.6 --source 19,5.5 --source=-4,-5 --source 21.5,-1 \
  --start=-5,5 --start 5,-6 --start 20,0 --start 14,6

# Nav2's warehouse (30.18 x 50.22 m): in through a 0.75 m opening at the top-left corner, out
# through the 15 m doorway in the bottom wall. Sources in aisles, between racks and in the open.
./build/plumekit map import-ros "$real/warehouse/warehouse.yaml" --out data/floors/warehouse.json \
  --inlet=-14.8,25.22,-14.05,25.22 --outlet=-7.4,-25,7.6,-25 \
  --source=-12.5,-15 --source 2,0 --source 12,12 --source=-5,14 --source 2,-12 --source=-6,-20 \
  --start 12,22 --start 0,-24 --start=-13,2 --start 10,-8
