#pragma once
// The analytic VLP-16 sweep over a straight road with curbs and boxes (libs/preprocess's test
// fixture): the expected boundaries are the curb lines themselves.
#include "../../preprocess/tests/synthetic_road.h"

namespace roadslam::boundary::test {
using preprocess::fixtures::Box;
using preprocess::fixtures::castSweep;
using preprocess::fixtures::parkingAisle;
using preprocess::fixtures::Road;
}  // namespace roadslam::boundary::test
