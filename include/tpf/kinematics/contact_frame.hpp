// The local contact frame of a pad: z along the pad's outward normal.
#pragma once

#include <cmath>

#include "tpf/model/data.hpp"

namespace tpf {

/// A frame fixed to the link whose z axis is the unit outward normal n (link coordinates). Its x
/// axis is the link axis least aligned with n, projected off n, so that shear components keep a
/// fixed meaning on the pad; y = z × x. Columns of the result are the frame's axes in link
/// coordinates.
template <typename S>
Matrix3<S> contact_frame_in_link(const Vector3<S>& n) {
  Eigen::Index least = 0;
  n.cwiseAbs().minCoeff(&least);
  const Vector3<S> z = n.normalized();
  Vector3<S> x = Vector3<S>::Unit(least);
  x = (x - x.dot(z) * z).normalized();
  Matrix3<S> R;
  R.col(0) = x;
  R.col(1) = z.cross(x);
  R.col(2) = z;
  return R;
}

/// The contact frame's axes in world coordinates: R_world = oMi[link].R · contact_frame_in_link(n).
template <typename S, int N>
Matrix3<S> contact_frame_in_world(const Data<S, N>& data, int link,
                                  const NoDeduce<Vector3<S>>& n_link) {
  return data.oMi[link].R * contact_frame_in_link(n_link);
}

}  // namespace tpf
