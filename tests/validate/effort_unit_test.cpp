// One unit inside: motor current becomes N·m where it enters (effort_unit.hpp, log reading), the
// same motion logged in mA or in N·m gives the same estimate, and files of the earlier format
// (efforts in the log's unit) are refused by the loaders and converted exactly by `tpf upgrade`.
#include "tpf/model/effort_unit.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "offline/compensator_training/tcn_parameters.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "offline/samples/joint_samples.hpp"
#include "offline/upgrade/upgrade_files.hpp"
#include "support/arm_fixture.hpp"
#include "tpf/common/error.hpp"
#include "tpf/estimation/compensator_weight_files.hpp"
#include "tpf/estimation/estimator.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"
#include "tpf/friction/friction_file.hpp"
#include "tpf/nn/tcn_weight_file.hpp"

namespace tpf::test {
namespace {

namespace fs = std::filesystem;
using offline::Log;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("tpf_effort_unit_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}
void write_json(const fs::path& p, const nlohmann::json& j) {
  std::ofstream(p) << j.dump(1);
}

TEST(EffortUnit, CurrentAndTorqueConvertWithTheRobotFilesTorqueConstants) {
  const Vec kt = arm().torque_constant;
  const Vec i(1000.0, -500.0, 250.0, 0.0);  // mA
  const Vec tau = torque_from_current(arm(), i);
  for (int j = 0; j < kJoints; ++j)
    EXPECT_DOUBLE_EQ(tau[j], kt[j] * i[j] / 1000.0);
  EXPECT_LT((current_from_torque(arm(), tau) - i).cwiseAbs().maxCoeff(), 1e-12);

  const DriveUnits ma = drive_units(arm(), EffortUnit::Milliampere);
  const DriveUnits nm = drive_units(arm(), EffortUnit::NewtonMetre);
  EXPECT_STREQ(ma.name(), "mA");
  EXPECT_STREQ(nm.name(), "N*m");
  Eigen::MatrixXd e(2, kJoints);
  e << i.transpose(), 2 * i.transpose();
  const Eigen::MatrixXd t = ma.to_torque(e);
  EXPECT_LT((t.row(0).transpose() - tau).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((ma.to_effort(t) - e).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(nm.to_torque(e), e);
  EXPECT_DOUBLE_EQ(ma.to_effort(1, 0.5), 500.0 / kt[1]);
  EXPECT_THROW(ma.to_torque(Eigen::MatrixXd::Zero(2, 3)), Error);
  EXPECT_EQ(effort_unit_of_column("i"), EffortUnit::Milliampere);
  EXPECT_EQ(effort_unit_of_column("tau"), EffortUnit::NewtonMetre);
  EXPECT_THROW(effort_unit_of_column("amps"), Error);
  EXPECT_THROW(parse_effort_unit("A"), Error);
}

/// 2 s at 400 Hz of every joint swinging, the effort a smooth function of time: in i<j> [mA]
/// (`torque` false) or the same effort as tau<j> = K_t·i/1000 [N·m].
Log swinging_log(bool torque) {
  Log log;
  log.source = torque ? "swing-tau.csv" : "swing-i.csv";
  log.meta.set("rate_hz", "400");
  for (const char* prefix : {"q", "dq", torque ? "tau" : "i"})
    for (int j = 1; j <= kJoints; ++j)
      log.columns.push_back(prefix + std::to_string(j));
  log.columns.insert(log.columns.begin(), "t");
  log.values.resize(800, 1 + 3 * kJoints);
  for (int k = 0; k < 800; ++k) {
    const double t = k / 400.0;
    log.values(k, 0) = t;
    for (int j = 0; j < kJoints; ++j) {
      const double w = 1.0 + 0.3 * j;
      const double i = 300.0 * std::sin(1.7 * t + j) + 40.0 * std::cos(9.0 * t);
      log.values(k, 1 + j) = 0.2 * std::sin(w * t);
      log.values(k, 1 + kJoints + j) = 0.2 * w * std::cos(w * t);
      log.values(k, 1 + 2 * kJoints + j) = torque ? arm().torque_constant[j] * i / 1000.0 : i;
    }
  }
  return log;
}

TEST(EffortUnit, ALogInMilliamperesAndTheSameLogInNewtonMetresGiveTheSameEstimate) {
  const auto nominal = nominal_from_model<kJoints>(
      arm(), load_stribeck_parameters<double, kJoints>(data_path("arm4.friction.json")));
  EstimatorParameters<double, kJoints> p;
  p.nominal_sigma = p.fused_sigma = Vec::Constant(0.3);  // N·m
  p.static_dead_band = Vec::Constant(0.05);
  // The offline tools' estimator: joint and pad counts at run time.
  using E = Estimator<double, Eigen::Dynamic, Eigen::Dynamic>;
  const NominalModelX any_arm = joint_count_cast<Eigen::Dynamic>(nominal);
  const auto any_p = joint_count_cast<Eigen::Dynamic>(p);
  auto from_ma = std::make_unique<E>(any_arm, std::vector<Pad>{}, any_p);
  auto from_nm = std::make_unique<E>(any_arm, std::vector<Pad>{}, any_p);
  const auto a = offline::estimator_samples(swinging_log(false), any_arm.model, 0);
  const auto b = offline::estimator_samples(swinging_log(true), any_arm.model, 0);
  ASSERT_EQ(a.size(), b.size());
  double worst = 0.0, largest = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_LT((a[k].effort - b[k].effort).cwiseAbs().maxCoeff(), 1e-12) << "row " << k;
    const auto& x = from_ma->update(a[k]);
    const auto& y = from_nm->update(b[k]);
    worst = std::max(worst, (x.residual - y.residual).cwiseAbs().maxCoeff());
    worst = std::max(worst, (x.external.torque - y.external.torque).cwiseAbs().maxCoeff());
    largest = std::max(largest, x.residual.cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(largest, 0.5);  // the residual is not trivially zero: it has something to agree on

  // The offline samples: effort in N·m whatever the log held; the unit is kept for reports.
  const auto sa = offline::extract_joint_samples(swinging_log(false), arm().torque_constant);
  const auto sb = offline::extract_joint_samples(swinging_log(true), arm().torque_constant);
  EXPECT_EQ(sa.units.unit, EffortUnit::Milliampere);
  EXPECT_EQ(sb.units.unit, EffortUnit::NewtonMetre);
  EXPECT_LT((sa.effort - sb.effort).cwiseAbs().maxCoeff(), 1e-12);
}

/// The model of data/arm4 with a little of every effect, in N·m.
NominalModel<double, kJoints> model_with_effects() {
  auto nominal = nominal_from_model<kJoints>(
      arm(), load_stribeck_parameters<double, kJoints>(data_path("arm4.friction.json")));
  nominal.friction.coulomb_asymmetry[1] = 0.1;
  nominal.friction.neighbour_load_coulomb(0, 2) = 0.02;
  nominal.added.get<JointSpring>().stiffness[1] = 0.4;
  nominal.added.get<JointOffset>().offset[2] = -0.3;
  nominal.added.get<MotionCoupling>().velocity(3, 0) = 0.05;
  nominal.added.get<PositionRipple>().add({1, 8.0, false, 0.12, -0.04});
  return nominal;
}

/// `j` (a version-2 parameter file) written as version 1 in mA: what tpf wrote before.
nlohmann::json as_version_1(nlohmann::json j, const Vec& k) {
  const auto scale = [&](nlohmann::json& a) {
    for (int r = 0; r < kJoints; ++r)
      if (a[r].is_array())
        for (auto& x : a[r])
          x = x.get<double>() * k[r];
      else
        a[r] = a[r].get<double>() * k[r];
  };
  for (const char* key :
       {"coulomb", "static", "viscous", "load_coulomb", "load_viscous", "coulomb_asymmetry",
        "viscous_asymmetry", "neighbour_load_coulomb", "neighbour_load_viscous"})
    scale(j["friction"][key]);
  for (const char* key :
       {"spring_stiffness", "offset", "coupling_velocity", "coupling_acceleration"})
    if (j["added_effects"].contains(key)) scale(j["added_effects"][key]);
  for (auto& r : j["added_effects"]["ripple"]) {
    const int joint = r["joint"].get<int>() - 1;
    r["sin"] = r["sin"].get<double>() * k[joint];
    r["cos"] = r["cos"].get<double>() * k[joint];
  }
  j["version"] = 1;
  j.erase("torque_unit");
  j["effort_unit"] = "mA";
  j["effort_per_newton_metre"] = std::vector<double>(k.data(), k.data() + kJoints);
  return j;
}

TEST(EffortUnit, OldParameterFilesAreRefusedNamingTheFileAndConvertedExactlyByUpgrade) {
  TempDir dir;
  const auto nominal = model_with_effects();
  const fs::path params = dir.path / "arm4.params.json";
  save_nominal_model<kJoints>(params, nominal, "test");
  const Vec k = current_from_torque(arm(), Vec::Ones().eval());  // mA per N·m
  write_json(params, as_version_1(read_json(params), k));

  // An estimator file of the old version: σ's and band in mA.
  EstimatorParameters<double, kJoints> p;
  p.nominal_sigma = Vec(0.9, 1.2, 0.6, 0.3);
  p.fused_sigma = Vec(0.2, 0.3, 0.15, 0.05);
  p.static_dead_band = Vec::Constant(0.1);
  const fs::path estimator = dir.path / "arm4.estimator.json";
  save_estimator_parameters<kJoints>(estimator, p, "test");
  nlohmann::json e = read_json(estimator);
  for (const char* key : {"nominal_sigma", "fused_sigma", "static_dead_band"})
    for (int j = 0; j < kJoints; ++j)
      e[key][j] = e[key][j].get<double>() * k[j];
  e["version"] = 2;
  e.erase("torque_unit");
  write_json(estimator, e);

  try {
    load_nominal_model<kJoints>(params, data_path("arm4.robot.json"));
    ADD_FAILURE() << "a version-1 parameter file loaded";
  } catch (const Error& error) {
    const std::string m = error.what();
    EXPECT_NE(m.find(params.string()), std::string::npos) << m;
    EXPECT_NE(m.find("version"), std::string::npos) << m;
    EXPECT_NE(m.find("tpf upgrade"), std::string::npos) << m;
  }
  EXPECT_THROW(load_estimator_parameters<kJoints>(estimator), Error);

  const auto lines = offline::upgrade_files({params, estimator, {}});
  EXPECT_EQ(lines.size(), 2u);
  const auto loaded = load_nominal_model<kJoints>(params, data_path("arm4.robot.json"));
  ArmData d1, d2;
  for (int s = 0; s < 20; ++s) {
    const Vec q = Vec::Constant(0.1 * s - 1.0), dq = Vec::Constant(0.05 * s - 0.5);
    const Vec ddq = Vec::Constant(0.3 * s - 3.0);
    Vec r1, f1, r2, f2;
    predict_effort(nominal, d1, q, dq, ddq, r1, f1);
    predict_effort(loaded, d2, q, dq, ddq, r2, f2);
    EXPECT_LT((r1 - r2).cwiseAbs().maxCoeff(), 1e-9 * (1 + r1.norm())) << "state " << s;
    EXPECT_LT((f1 - f2).cwiseAbs().maxCoeff(), 1e-12 * (1 + f1.norm())) << "state " << s;
  }
  const auto q = load_estimator_parameters<kJoints>(estimator);
  EXPECT_LT((q.nominal_sigma - p.nominal_sigma).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((q.fused_sigma - p.fused_sigma).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((q.static_dead_band - p.static_dead_band).cwiseAbs().maxCoeff(), 1e-14);
  // Converted once: a second upgrade is refused (the parameter file is no longer version 1).
  EXPECT_THROW(offline::upgrade_files({params, {}, {}}), Error);
}

TEST(EffortUnit, UpgradeConvertsPerJointWeightsToNewtonMetres) {
  TempDir dir;
  const fs::path params = dir.path / "m.params.json";
  save_nominal_model<kJoints>(params, model_with_effects(), "test");
  const Vec k = current_from_torque(arm(), Vec::Ones().eval());
  write_json(params, as_version_1(read_json(params), k));

  // Per-joint networks as trained in mA: inputs τ̂_fric,s, τ_fric,nom and the output in mA.
  offline::TcnArchitecture a;
  a.inputs = 5;
  a.outputs = 1;
  a.hidden = 16;
  std::vector<nlohmann::json> originals;
  for (int j = 0; j < kJoints; ++j) {
    offline::TcnParameters net = offline::init_tcn_parameters(a, 10 + j);
    net.input_mean = Eigen::VectorXd::LinSpaced(5, -1.0, 1.0);
    net.input_std = Eigen::VectorXd::LinSpaced(5, 0.5, 2.0);
    const fs::path path = joint_weight_path(dir.path / "w.json", j);
    write_tcn_weight_file(path.string(), offline::to_weight_file(net));
    originals.push_back(read_json(path));
    nlohmann::json old = originals.back();
    for (int c : {3, 4}) {
      old["normalisation"]["mean"][c] = old["normalisation"]["mean"][c].get<double>() * k[j];
      old["normalisation"]["std"][c] = old["normalisation"]["std"][c].get<double>() * k[j];
    }
    for (const char* t : {"head_low.weight", "head_low.bias", "head_high.weight", "head_high.bias"})
      for (auto& x : old["tensors"][t]["values"])
        x = x.get<double>() * k[j];
    old["version"] = 1;
    write_json(path, old);
    EXPECT_THROW(read_tcn_weight_file(path.string()), Error) << "version 1 must be refused";
  }
  offline::upgrade_files({params, {}, dir.path / "w.json"});
  for (int j = 0; j < kJoints; ++j) {
    const nlohmann::json now = read_json(joint_weight_path(dir.path / "w.json", j));
    const nlohmann::json& was = originals[static_cast<std::size_t>(j)];
    EXPECT_EQ(now["version"], 2);
    for (const char* key : {"mean", "std"})
      for (int c = 0; c < 5; ++c)
        EXPECT_NEAR(now["normalisation"][key][c].get<double>(),
                    was["normalisation"][key][c].get<double>(), 1e-12);
    for (const char* t : {"head_low.weight", "head_low.bias", "head_high.weight", "head_high.bias",
                          "blocks.0.conv.weight"})
      for (std::size_t i = 0; i < was["tensors"][t]["values"].size(); ++i)
        EXPECT_NEAR(now["tensors"][t]["values"][i].get<double>(),
                    was["tensors"][t]["values"][i].get<double>(), 1e-12)
            << t << " " << i;
    EXPECT_NO_THROW(read_tcn_weight_file(joint_weight_path(dir.path / "w.json", j).string()));
  }
}

}  // namespace
}  // namespace tpf::test
