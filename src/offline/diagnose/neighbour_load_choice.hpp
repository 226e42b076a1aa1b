// Which other joint's gravity load the neighbour-load candidate of each joint takes
// (NeighbourLoadColumns), chosen on the declared model's residual before the candidate library's
// columns are built, as a ripple's frequency or a coupled motor's ratio is: two columns per joint
// instead of two per other joint, so that one real dependence is not diluted among all of them.
#pragma once

#include <Eigen/Core>

#include "offline/samples/joint_samples.hpp"

namespace tpf::offline {

/// Per joint j: the joint k ≠ j whose centred load, (|G_k| − mean)·sgn q̇_j and
/// (|G_k| − mean)·q̇_j (the part the declared Coulomb and viscous columns do not span), explains
/// most of j's `residual` (effort − the declared linear fit) by least squares on j's moving
/// training samples (≤ 20 000, evenly strided); −1 for one joint or fewer than 100 such samples.
/// `abs_gravity`: |G_k(q)| per sample and joint.
Eigen::VectorXi choose_neighbour_loads(const JointSamples& samples, const Eigen::MatrixXd& residual,
                                       const Eigen::MatrixXd& abs_gravity);

}  // namespace tpf::offline
