// The textbook forms of forward kinematics, RNEA and CRBA, computed from the model's raw
// placements, axes and inertias on every call (Eigen's AngleAxis, the parallel-axis theorem per
// call, skew-matrix products): the reference the library's forms, which use the model's
// precomputed constants, are tested against. Test-only; not tuned.
#pragma once

#include "tpf/core.hpp"

namespace tpf::test::reference {

template <int N>
struct Workspace {
  std::array<Transform<double>, N + 1> liMi, oMi;
  std::array<Vector3<double>, N + 1> omega, domega, acc, force, moment;
};

template <int N>
void kinematics(const Model<double, N>& model, Workspace<N>& w, const JointVector<double, N>& q) {
  w.oMi[0] = Transform<double>{};
  for (int k = 1; k <= N; ++k) {
    const Matrix3<double> rotation =
        Eigen::AngleAxis<double>(q(k - 1), model.axes[k - 1]).toRotationMatrix();
    w.liMi[k].R = model.joint_placements[k - 1].R * rotation;
    w.liMi[k].p = model.joint_placements[k - 1].p;
    w.oMi[k] = w.oMi[k - 1] * w.liMi[k];
  }
}

/// τ = M(q)q̈ + C(q,q̇)q̇ + G(q), armature included.
template <int N>
JointVector<double, N> rnea(const Model<double, N>& model, const JointVector<double, N>& q,
                            const JointVector<double, N>& dq, const JointVector<double, N>& ddq) {
  Workspace<N> w;
  kinematics(model, w, q);
  w.omega[0].setZero();
  w.domega[0].setZero();
  w.acc[0] = -model.gravity;
  for (int k = 1; k <= N; ++k) {
    const Matrix3<double>& R = w.liMi[k].R;
    const Vector3<double>& p = w.liMi[k].p;
    const Vector3<double>& z = model.axes[k - 1];
    const Vector3<double> w_parent = R.transpose() * w.omega[k - 1];
    w.omega[k] = w_parent + z * dq(k - 1);
    w.domega[k] = R.transpose() * w.domega[k - 1] + z * ddq(k - 1) + w_parent.cross(z * dq(k - 1));
    const Vector3<double>& w0 = w.omega[k - 1];
    w.acc[k] = R.transpose() * (w.acc[k - 1] + w.domega[k - 1].cross(p) + w0.cross(w0.cross(p)));
    const Inertia<double>& body = model.inertias[k];
    const Vector3<double> h = body.first_moment();
    const Matrix3<double> I = body.about_origin();
    w.force[k] =
        body.mass * w.acc[k] + w.domega[k].cross(h) + w.omega[k].cross(w.omega[k].cross(h));
    w.moment[k] = I * w.domega[k] + w.omega[k].cross(I * w.omega[k]) + h.cross(w.acc[k]);
  }
  JointVector<double, N> tau;
  for (int k = N; k >= 1; --k) {
    if (k < N) {
      const Matrix3<double>& R = w.liMi[k + 1].R;
      const Vector3<double> f_child = R * w.force[k + 1];
      w.force[k] += f_child;
      w.moment[k] += R * w.moment[k + 1] + w.liMi[k + 1].p.cross(f_child);
    }
    tau(k - 1) = model.axes[k - 1].dot(w.moment[k]);
  }
  return tau + model.armature.cwiseProduct(ddq);
}

/// M(q), armature included, by composite rigid bodies with the parallel-axis theorem in
/// skew-matrix form: I_k += R I_{k+1} Rᵀ − m [p]×[p]× − [p]×[h]× − [h]×[p]×.
template <int N>
JointMatrix<double, N> mass_matrix(const Model<double, N>& model, const JointVector<double, N>& q) {
  Workspace<N> w;
  kinematics(model, w, q);
  std::array<double, N + 1> mass;
  std::array<Vector3<double>, N + 1> first_moment;
  std::array<Matrix3<double>, N + 1> inertia;
  for (int k = N; k >= 1; --k) {
    const Inertia<double>& body = model.inertias[k];
    mass[k] = body.mass;
    first_moment[k] = body.first_moment();
    inertia[k] = body.about_origin();
    if (k < N) {
      const Matrix3<double>& R = w.liMi[k + 1].R;
      const Vector3<double>& p = w.liMi[k + 1].p;
      const double m = mass[k + 1];
      const Vector3<double> h = R * first_moment[k + 1];
      const Matrix3<double> P = skew(p), H = skew(h);
      mass[k] += m;
      first_moment[k] += m * p + h;
      inertia[k] += R * inertia[k + 1] * R.transpose() - m * P * P - P * H - H * P;
    }
  }
  JointMatrix<double, N> M;
  for (int i = N; i >= 1; --i) {
    const Vector3<double>& z = model.axes[i - 1];
    Vector3<double> f = z.cross(first_moment[i]);
    Vector3<double> n = inertia[i] * z;
    M(i - 1, i - 1) = z.dot(n) + model.armature(i - 1);
    for (int j = i - 1; j >= 1; --j) {
      const Matrix3<double>& R = w.liMi[j + 1].R;
      n = R * n + w.liMi[j + 1].p.cross(R * f);
      f = R * f;
      M(j - 1, i - 1) = M(i - 1, j - 1) = model.axes[j - 1].dot(n);
    }
  }
  return M;
}

/// The regressor Y (N × 13N, tpf's column order) by carrying each link's 3 × 10 wrench matrices
/// [F; M] (f = F π_k, n = M π_k at its origin) down the chain to every joint j ≤ k:
/// M ← R M + [p]× R F, F ← R F; Y(j, π_k) = z_j · M in joint j's frame.
template <int N>
Regressor<double, N> regressor(const Model<double, N>& model, const JointVector<double, N>& q,
                               const JointVector<double, N>& dq,
                               const JointVector<double, N>& ddq) {
  Workspace<N> w;
  kinematics(model, w, q);
  Regressor<double, N> Y = Regressor<double, N>::Zero();
  Vector3<double> omega = Vector3<double>::Zero(), domega = Vector3<double>::Zero(),
                  acc = -model.gravity;
  for (int k = 1; k <= N; ++k) {
    const Matrix3<double>& R = w.liMi[k].R;
    const Vector3<double>& p = w.liMi[k].p;
    const Vector3<double>& z = model.axes[k - 1];
    acc = R.transpose() * (acc + domega.cross(p) + omega.cross(omega.cross(p)));
    const Vector3<double> w_parent = R.transpose() * omega;
    omega = w_parent + z * dq(k - 1);
    domega = R.transpose() * domega + z * ddq(k - 1) + w_parent.cross(z * dq(k - 1));
    auto L = [](const Vector3<double>& x) {  // I x = L(x) [Ixx Ixy Ixz Iyy Iyz Izz]ᵀ
      Eigen::Matrix<double, 3, 6> l;
      l << x.x(), x.y(), x.z(), 0, 0, 0, 0, x.x(), 0, x.y(), x.z(), 0, 0, 0, x.x(), 0, x.y(), x.z();
      return l;
    };
    Eigen::Matrix<double, 3, 10> F = Eigen::Matrix<double, 3, 10>::Zero();
    Eigen::Matrix<double, 3, 10> M = Eigen::Matrix<double, 3, 10>::Zero();
    F.col(0) = acc;
    F.middleCols<3>(1) = skew(domega) + skew(omega) * skew(omega);
    M.middleCols<3>(1) = -skew(acc);
    M.rightCols<6>() = L(domega) + skew(omega) * L(omega);
    for (int j = k; j >= 1; --j) {
      Y.template block<1, 10>(j - 1, 10 * (k - 1)) = model.axes[j - 1].transpose() * M;
      if (j > 1) {
        const Matrix3<double>& Rj = w.liMi[j].R;
        M = (Rj * M + skew(w.liMi[j].p) * Rj * F).eval();
        F = (Rj * F).eval();
      }
    }
  }
  for (int j = 0; j < N; ++j) {
    Y(j, 10 * N + j) = ddq(j);
    Y(j, 11 * N + j) = dq(j) > 0 ? 1.0 : (dq(j) < 0 ? -1.0 : 0.0);
    Y(j, 12 * N + j) = dq(j);
  }
  return Y;
}

}  // namespace tpf::test::reference
