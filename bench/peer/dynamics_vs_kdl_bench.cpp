// RNEA, gravity, mass matrix and the Jacobian at a link point: tpf and orocos-kdl on the same
// robots and the same maths (KDL's joints carry tpf's armature as their rotor inertia; the peer
// tests check agreement to 1e-12): the 4-DoF arm and the 7-DoF Kinova Gen3.
// Run: taskset -c 1 build/release/bin/tpf_dynamics_bench --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true   (Release build). Figures: docs/performance.md.
#include <benchmark/benchmark.h>

#include <kdl/chaindynparam.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <kdl/chainjnttojacsolver.hpp>
#include <random>

#include "support/kdl_arm.hpp"
#include "tpf/core.hpp"

namespace {

constexpr int kPool = 256;  // a pool of states so that no branch predictor learns one

std::string data(const std::string& name) {
  return std::string(TPF_BENCH_DATA_DIR) + "/" + name;
}

/// One robot for both libraries, with a pool of random states and a point on link `point_link`.
template <int N>
struct Robot {
  using Vec = tpf::JointVector<double, N>;
  tpf::Model<double, N> model;
  KDL::Chain chain;
  int point_link;
  tpf::Vector3<double> point;  // in link `point_link`'s frame
  std::vector<Vec> q, dq, ddq;
  std::vector<KDL::JntArray> kq, kdq, kddq;

  Robot(const std::string& robot, const std::string& urdf, const std::string& base,
        const std::string& tip, int link, const tpf::Vector3<double>& p)
      : model(tpf::load_robot<double, N>(data(robot))),
        chain(
            tpf::test::with_armature(tpf::test::kdl_chain(data(urdf), base, tip), model.armature)),
        point_link(link),
        point(p) {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (int i = 0; i < kPool; ++i) {
      Vec a, b, c;
      for (int j = 0; j < N; ++j)
        a(j) = u(rng), b(j) = u(rng), c(j) = u(rng);
      q.push_back(a), dq.push_back(b), ddq.push_back(c);
      kq.push_back(to_kdl(a)), kdq.push_back(to_kdl(b)), kddq.push_back(to_kdl(c));
    }
  }
  static KDL::JntArray to_kdl(const Vec& v) {
    KDL::JntArray a(N);
    a.data = v;
    return a;
  }
  KDL::Vector kdl_gravity() const {
    return KDL::Vector(model.gravity.x(), model.gravity.y(), model.gravity.z());
  }
};

/// The 4-DoF arm; the point is the forearm_top pad's centre.
Robot<4>& arm4() {
  static Robot<4> r("arm4.robot.json", "arm4.urdf", "link1", "link5", 3,
                    tpf::Vector3<double>(0.11, -0.057, 0.065));
  return r;
}
/// The 7-DoF Kinova Gen3; the point is 5 cm off the bracelet.
Robot<7>& gen3() {
  static Robot<7> r("real/kinova-gen3/gen3.robot.json", "real/kinova-gen3/gen3.urdf", "base_link",
                    "end_effector_link", 7, tpf::Vector3<double>(0.0, 0.02, -0.05));
  return r;
}

template <int N, Robot<N>& (*robot)()>
void Rnea_tpf(benchmark::State& state) {
  Robot<N>& r = robot();
  tpf::Data<double, N> d;
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ % kPool;
    benchmark::DoNotOptimize(tpf::rnea(r.model, d, r.q[k], r.dq[k], r.ddq[k]));
  }
}
template <int N, Robot<N>& (*robot)()>
void Rnea_kdl(benchmark::State& state) {
  Robot<N>& r = robot();
  KDL::ChainIdSolver_RNE solver(r.chain, r.kdl_gravity());
  KDL::JntArray tau(N);
  KDL::Wrenches wrenches(r.chain.getNrOfSegments(), KDL::Wrench::Zero());
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ % kPool;
    solver.CartToJnt(r.kq[k], r.kdq[k], r.kddq[k], wrenches, tau);
    benchmark::DoNotOptimize(tau.data.data());
  }
}

template <int N, Robot<N>& (*robot)()>
void Gravity_tpf(benchmark::State& state) {
  Robot<N>& r = robot();
  tpf::Data<double, N> d;
  std::size_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(tpf::compute_gravity(r.model, d, r.q[i++ % kPool]));
}
template <int N, Robot<N>& (*robot)()>
void Gravity_kdl(benchmark::State& state) {
  Robot<N>& r = robot();
  KDL::ChainDynParam dyn(r.chain, r.kdl_gravity());
  KDL::JntArray g(N);
  std::size_t i = 0;
  for (auto _ : state) {
    dyn.JntToGravity(r.kq[i++ % kPool], g);
    benchmark::DoNotOptimize(g.data.data());
  }
}

template <int N, Robot<N>& (*robot)()>
void MassMatrix_tpf(benchmark::State& state) {
  Robot<N>& r = robot();
  tpf::Data<double, N> d;
  std::size_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(tpf::compute_mass_matrix(r.model, d, r.q[i++ % kPool]));
}
template <int N, Robot<N>& (*robot)()>
void MassMatrix_kdl(benchmark::State& state) {
  Robot<N>& r = robot();
  KDL::ChainDynParam dyn(r.chain, r.kdl_gravity());
  KDL::JntSpaceInertiaMatrix M(N);
  std::size_t i = 0;
  for (auto _ : state) {
    dyn.JntToMass(r.kq[i++ % kPool], M);
    benchmark::DoNotOptimize(M.data.data());
  }
}

// Jacobian at a point of a link, including the kinematics it needs.
template <int N, Robot<N>& (*robot)()>
void PointJacobian_tpf(benchmark::State& state) {
  Robot<N>& r = robot();
  tpf::Data<double, N> d;
  tpf::Jacobian<double, N> J;
  std::size_t i = 0;
  for (auto _ : state) {
    tpf::forward_kinematics(r.model, d, r.q[i++ % kPool], r.point_link);
    tpf::point_jacobian(r.model, d, r.point_link, d.oMi[r.point_link].apply(r.point), J);
    benchmark::DoNotOptimize(J.data());
  }
}
template <int N, Robot<N>& (*robot)()>
void PointJacobian_kdl(benchmark::State& state) {
  Robot<N>& r = robot();
  KDL::ChainJntToJacSolver solver(r.chain);
  KDL::ChainFkSolverPos_recursive fk(r.chain);
  KDL::Jacobian J(N);
  KDL::Frame link_pose;
  const KDL::Vector point(r.point.x(), r.point.y(), r.point.z());
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ % kPool;
    // JntToJac gives the Jacobian at the segment origin; the point's offset from it, in the base
    // frame, needs the segment's pose: the same work tpf does.
    fk.JntToCart(r.kq[k], link_pose, r.point_link);
    solver.JntToJac(r.kq[k], J, r.point_link);
    J.changeRefPoint(link_pose.M * point);
    benchmark::DoNotOptimize(J.data.data());
  }
}

#define TPF_PEER_BENCH(robot, n)                                               \
  BENCHMARK(Rnea_tpf<n, robot>)->Name(#robot "/Rnea/tpf");                     \
  BENCHMARK(Rnea_kdl<n, robot>)->Name(#robot "/Rnea/kdl");                     \
  BENCHMARK(Gravity_tpf<n, robot>)->Name(#robot "/Gravity/tpf");               \
  BENCHMARK(Gravity_kdl<n, robot>)->Name(#robot "/Gravity/kdl");               \
  BENCHMARK(MassMatrix_tpf<n, robot>)->Name(#robot "/MassMatrix/tpf");         \
  BENCHMARK(MassMatrix_kdl<n, robot>)->Name(#robot "/MassMatrix/kdl");         \
  BENCHMARK(PointJacobian_tpf<n, robot>)->Name(#robot "/FkPointJacobian/tpf"); \
  BENCHMARK(PointJacobian_kdl<n, robot>)->Name(#robot "/FkPointJacobian/kdl")

TPF_PEER_BENCH(arm4, 4);
TPF_PEER_BENCH(gen3, 7);

}  // namespace
