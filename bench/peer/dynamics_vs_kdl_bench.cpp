// RNEA, gravity, mass matrix and the Jacobian at a pad point: tpf and orocos-kdl on the same arm.
// Run: build/release/bin/tpf_dynamics_bench (Release build). Figures: docs/performance.md.
#include <benchmark/benchmark.h>

#include <kdl/chaindynparam.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <kdl/chainjnttojacsolver.hpp>
#include <random>

#include "support/kdl_arm.hpp"
#include "tpf/core.hpp"

namespace {

constexpr int N = 4;
using Vec = tpf::JointVector<double, N>;

struct Fixture {
  tpf::Model<double, N> model =
      tpf::load_robot<double, N>(std::string(TPF_BENCH_DATA_DIR) + "/arm4.robot.json");
  tpf::Data<double, N> data;
  KDL::Chain chain =
      tpf::test::kdl_chain(std::string(TPF_BENCH_DATA_DIR) + "/arm4.urdf", "link1", "link5");
  std::vector<Vec> q, dq, ddq;  // a pool of states so that no branch predictor learns one
  Fixture() {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (int i = 0; i < 256; ++i) {
      Vec a, b, c;
      for (int j = 0; j < N; ++j)
        a(j) = u(rng), b(j) = u(rng), c(j) = u(rng);
      q.push_back(a), dq.push_back(b), ddq.push_back(c);
    }
  }
  static Fixture& get() {
    static Fixture f;
    return f;
  }
};

KDL::JntArray to_kdl(const Vec& v) {
  KDL::JntArray a(N);
  a.data = v;
  return a;
}

void BM_Rnea_tpf(benchmark::State& state) {
  Fixture& f = Fixture::get();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        tpf::rnea(f.model, f.data, f.q[i & 255], f.dq[i & 255], f.ddq[i & 255]));
    ++i;
  }
}
void BM_Rnea_kdl(benchmark::State& state) {
  Fixture& f = Fixture::get();
  KDL::ChainIdSolver_RNE solver(f.chain, KDL::Vector(0, 0, -9.81));
  std::vector<KDL::JntArray> q, dq, ddq;
  for (int i = 0; i < 256; ++i)
    q.push_back(to_kdl(f.q[i])), dq.push_back(to_kdl(f.dq[i])), ddq.push_back(to_kdl(f.ddq[i]));
  KDL::JntArray tau(N);
  KDL::Wrenches wrenches(f.chain.getNrOfSegments(), KDL::Wrench::Zero());
  std::size_t i = 0;
  for (auto _ : state) {
    solver.CartToJnt(q[i & 255], dq[i & 255], ddq[i & 255], wrenches, tau);
    benchmark::DoNotOptimize(tau.data.data());
    ++i;
  }
}

void BM_Gravity_tpf(benchmark::State& state) {
  Fixture& f = Fixture::get();
  std::size_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(tpf::compute_gravity(f.model, f.data, f.q[i++ & 255]));
}
void BM_Gravity_kdl(benchmark::State& state) {
  Fixture& f = Fixture::get();
  KDL::ChainDynParam dyn(f.chain, KDL::Vector(0, 0, -9.81));
  std::vector<KDL::JntArray> q;
  for (int i = 0; i < 256; ++i)
    q.push_back(to_kdl(f.q[i]));
  KDL::JntArray g(N);
  std::size_t i = 0;
  for (auto _ : state) {
    dyn.JntToGravity(q[i++ & 255], g);
    benchmark::DoNotOptimize(g.data.data());
  }
}

void BM_MassMatrix_tpf(benchmark::State& state) {
  Fixture& f = Fixture::get();
  std::size_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(tpf::compute_mass_matrix(f.model, f.data, f.q[i++ & 255]));
}
void BM_MassMatrix_kdl(benchmark::State& state) {
  Fixture& f = Fixture::get();
  KDL::ChainDynParam dyn(f.chain, KDL::Vector(0, 0, -9.81));
  std::vector<KDL::JntArray> q;
  for (int i = 0; i < 256; ++i)
    q.push_back(to_kdl(f.q[i]));
  KDL::JntSpaceInertiaMatrix M(N);
  std::size_t i = 0;
  for (auto _ : state) {
    dyn.JntToMass(q[i++ & 255], M);
    benchmark::DoNotOptimize(M.data.data());
  }
}

// Jacobian at the forearm_top pad centre, including the kinematics it needs.
const tpf::Vector3<double> kPadCenter(0.11, -0.057, 0.065);
constexpr int kPadLink = 3;

void BM_PadJacobian_tpf(benchmark::State& state) {
  Fixture& f = Fixture::get();
  tpf::Jacobian<double, N> J;
  std::size_t i = 0;
  for (auto _ : state) {
    tpf::forward_kinematics(f.model, f.data, f.q[i++ & 255]);
    tpf::point_jacobian(f.model, f.data, kPadLink, f.data.oMi[kPadLink].apply(kPadCenter), J);
    benchmark::DoNotOptimize(J.data());
  }
}
void BM_PadJacobian_kdl(benchmark::State& state) {
  Fixture& f = Fixture::get();
  KDL::ChainJntToJacSolver solver(f.chain);
  KDL::ChainFkSolverPos_recursive fk(f.chain);
  std::vector<KDL::JntArray> q;
  for (int i = 0; i < 256; ++i)
    q.push_back(to_kdl(f.q[i]));
  KDL::Jacobian J(N);
  KDL::Frame link_pose;
  const KDL::Vector center(kPadCenter.x(), kPadCenter.y(), kPadCenter.z());
  std::size_t i = 0;
  for (auto _ : state) {
    // JntToJac gives the Jacobian at the segment origin; the pad's offset from it, in the base
    // frame, needs the segment's pose: the same work tpf does.
    fk.JntToCart(q[i & 255], link_pose, kPadLink);
    solver.JntToJac(q[i & 255], J, kPadLink);
    J.changeRefPoint(link_pose.M * center);
    benchmark::DoNotOptimize(J.data.data());
    ++i;
  }
}

BENCHMARK(BM_Rnea_tpf);
BENCHMARK(BM_Rnea_kdl);
BENCHMARK(BM_Gravity_tpf);
BENCHMARK(BM_Gravity_kdl);
BENCHMARK(BM_MassMatrix_tpf);
BENCHMARK(BM_MassMatrix_kdl);
BENCHMARK(BM_PadJacobian_tpf);
BENCHMARK(BM_PadJacobian_kdl);

}  // namespace
