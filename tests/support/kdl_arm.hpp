// The same arm as a KDL chain, for peer comparisons in tests and benchmarks.
#pragma once

#include <Eigen/Core>
#include <kdl/chain.hpp>
#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <stdexcept>
#include <string>

namespace tpf::test {

/// The chain from `base` to `tip` of a URDF, as KDL parses it (no rotor inertia).
inline KDL::Chain kdl_chain(const std::string& urdf, const std::string& base,
                            const std::string& tip) {
  KDL::Tree tree;
  if (!kdl_parser::treeFromFile(urdf, tree)) throw std::runtime_error("KDL cannot parse " + urdf);
  KDL::Chain chain;
  if (!tree.getChain(base, tip, chain)) throw std::runtime_error("KDL: no chain in " + urdf);
  return chain;
}

/// The same chain with each moving joint's rotor inertia reflected to the output (KDL::Joint's
/// `inertia` argument, tpf's armature = rotor_inertia·gear_ratio² [kg·m²]), in joint order: KDL's
/// Newton–Euler then adds armature·q̈ and ChainDynParam its diagonal, the maths tpf does.
inline KDL::Chain with_armature(const KDL::Chain& rigid, const Eigen::VectorXd& armature) {
  if (static_cast<Eigen::Index>(rigid.getNrOfJoints()) != armature.size())
    throw std::runtime_error("KDL: one armature per moving joint expected");
  KDL::Chain chain;
  Eigen::Index j = 0;
  for (const KDL::Segment& s : rigid.segments) {
    const KDL::Joint& joint = s.getJoint();
    if (joint.getType() == KDL::Joint::Fixed) {
      chain.addSegment(s);
      continue;
    }
    const KDL::Joint geared(joint.getName(), joint.JointOrigin(), joint.JointAxis(),
                            joint.getType(), 1.0, 0.0, armature(j++));
    chain.addSegment(KDL::Segment(s.getName(), geared, s.getFrameToTip(), s.getInertia()));
  }
  return chain;
}

}  // namespace tpf::test
