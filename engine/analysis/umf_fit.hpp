#pragma once
// The minimum fluidization velocity from a decreasing branch of the pressure-drop curve (the
// paper's Fig. 6, point E): where the plateau of the fluidized bed meets the defluidization line.
//
// Method: the points, sorted by velocity, are split at every possible place into a low part
// (the defluidized bed: a straight line dp = a + b U fitted by least squares) and a high part
// (the fluidized plateau: a constant, the mean). The split with the least total squared error
// wins (at least two points on each side); U_mf is where its line reaches its plateau.
#include <string>
#include <vector>

namespace fluidbed {

struct UmfFit {
  bool ok = false;
  double umf = 0.0;       // m/s
  double plateau = 0.0;   // Pa
  double intercept = 0.0, slope = 0.0;  // Pa, Pa s/m: the defluidization line
  int low_points = 0, high_points = 0;
  double rms_residual = 0.0;  // Pa
  std::string why;            // when !ok
};

UmfFit fit_umf(std::vector<double> u, std::vector<double> dp);

}  // namespace fluidbed
