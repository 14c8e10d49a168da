#pragma once
// Random vectors for tests, drawn in a fixed order. Function arguments are evaluated in an
// unspecified order (GCC: right to left, clang: left to right), so three draws written as the
// three arguments of one call give other data under another compiler; a test that passes with
// one may fail with the other (seen under clang's sanitizer build). The draws here come in the
// order z, y, x: GCC's order for those calls, so that the tests' data stayed what it was.
#include <Eigen/Core>

namespace viqu::testing {

// (fx(draw x), fy(draw y), fz(draw z)) with the draws made z first.
template <class Dist, class Gen>
Eigen::Vector3d RandomVector(Dist& dist, Gen& gen) {
  const double z = dist(gen);
  const double y = dist(gen);
  const double x = dist(gen);
  return {x, y, z};
}

}  // namespace viqu::testing
