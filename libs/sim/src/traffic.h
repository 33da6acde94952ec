#pragma once
// Private to libs/sim: the moving cars' lap geometry, shared by the lap plan (traffic.cpp) and the
// car-following (following.cpp).
#include "roadslam/sim/world.h"

namespace roadslam::sim {

/// The arc length of a car's lap that its lap coordinate u runs over: open roads are driven 15 m
/// clear of their ends (junctions in the grid layouts where the vehicle turns) and wrap: the car
/// leaves at one end and re-enters at the other, so it never turns around into the vehicle's lane.
double lapMargin(const Road& r, double len);

/// Length of the lap coordinate's range of \p car's road [m].
double lapLength(const Road& r);

/// Centre (x, y) and heading of travel of \p car at the road's arc length \p s [m, rad].
void carAt(const Road& r, const MovingCar& car, double s, double& x, double& y, double& hd);

}  // namespace roadslam::sim
