// Kinetic and potential energy, for conservation checks and observers.
#pragma once

#include "tpf/dynamics/mass_matrix.hpp"

namespace tpf {

/// T = ½ q̇ᵀ M(q) q̇ [J], armature included.
template <typename S, int N>
S kinetic_energy(const Model<S, N>& model, Data<S, N>& data, const NoDeduce<JointVector<S, N>>& q,
                 const NoDeduce<JointVector<S, N>>& dq) {
  compute_mass_matrix(model, data, q);
  return S(0.5) * dq.dot(data.M * dq);
}

/// V = −Σ_k m_k gᵀ c_k [J], c_k the world centre of mass of link k (zero at the world origin).
template <typename S, int N>
S potential_energy(const Model<S, N>& model, Data<S, N>& data,
                   const NoDeduce<JointVector<S, N>>& q) {
  forward_kinematics(model, data, q);
  S v = S(0);
  for (int k = 1; k <= model.joint_count(); ++k) {
    const Inertia<S>& body = model.inertias[k];
    v -= body.mass * model.gravity.dot(data.oMi[k].apply(body.com));
  }
  return v;
}

}  // namespace tpf
