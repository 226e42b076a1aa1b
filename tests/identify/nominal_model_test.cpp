// The core nominal model: prediction identities, parameter file round trip and errors.
#include "tpf/estimation/nominal_model.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "support/allocation_counter.hpp"
#include "support/arm_fixture.hpp"
#include "tpf/friction/friction_file.hpp"

namespace tpf::test {
namespace {

using Nominal = NominalModel<double, kJoints>;

std::filesystem::path temp_path(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("tpf_nominal_" + std::to_string(::getpid()) + "_" + name);
}

Nominal twin_nominal() {
  const auto friction = load_stribeck_parameters<double, kJoints>(data_path("arm4.friction.json"));
  return nominal_from_model<kJoints>(arm(), friction);
}

TEST(NominalModel, RigidPartOfTheTrueModelEqualsRnea) {
  const Nominal nominal = twin_nominal();
  EXPECT_LT(nominal.base_count, 11 * kJoints);
  EXPECT_GT(nominal.base_count, 10);
  ArmData data, reference;
  RandomStates states(3);
  for (int s = 0; s < 20; ++s) {
    const Vec q = states.vector(2.0), dq = states.vector(1.0), ddq = states.vector(3.0);
    Vec rigid, friction;
    predict_effort(nominal, data, q, dq, ddq, rigid, friction);
    const Vec tau = rnea(arm(), reference, q, dq, ddq);
    EXPECT_LT((rigid - tau).norm(), 1e-7 * tau.norm()) << "state " << s;
    const Vec g = compute_gravity(arm(), reference, q).cwiseAbs();
    EXPECT_LT((friction - stribeck_friction(nominal.friction, dq, g)).norm(), 1e-12);
  }
}

TEST(NominalModel, AddedEffectsEnterTheRigidPart) {
  Nominal nominal = twin_nominal();
  nominal.added.get<JointSpring>().stiffness[1] = 40.0;
  nominal.added.get<JointOffset>().offset[1] = -5.0;
  nominal.added.get<PositionRipple>().add({2, 12.0, false, 30.0, -10.0});
  nominal.added.get<MotionCoupling>().velocity(0, 1) = 7.0;
  ArmData data;
  const Vec q(0.1, 0.2, 0.3, 0.4), dq(0.5, -0.5, 0.0, 0.2), ddq = Vec::Zero();
  Vec rigid, friction, rigid0, friction0;
  predict_effort(nominal, data, q, dq, ddq, rigid, friction);
  predict_effort(twin_nominal(), data, q, dq, ddq, rigid0, friction0);
  const Vec d = rigid - rigid0;
  EXPECT_NEAR(d[0], 7.0 * -0.5, 1e-9);
  EXPECT_NEAR(d[1], 40.0 * 0.2 - 5.0, 1e-9);
  EXPECT_NEAR(d[2], 30.0 * std::sin(12.0 * 0.3) - 10.0 * std::cos(12.0 * 0.3), 1e-9);
  EXPECT_NEAR(d[3], 0.0, 1e-12);
  EXPECT_EQ(friction, friction0);
}

TEST(NominalModel, AsymmetricAndNeighbourLoadFrictionEnterTheFriction) {
  Nominal nominal = twin_nominal();
  nominal.friction.coulomb_asymmetry[0] = 3.0;
  nominal.friction.viscous_asymmetry[1] = 2.0;
  nominal.friction.neighbour_load_coulomb(2, 1) = 0.5;
  nominal.friction.neighbour_load_viscous(3, 1) = 0.25;
  ArmData data, reference;
  const Vec q(0.1, 0.2, 0.3, 0.4), ddq = Vec::Zero();
  const double g2 = std::abs(compute_gravity(arm(), reference, q)[1]);
  ASSERT_GT(g2, 0.1);
  for (const double direction : {1.0, -1.0}) {
    const Vec dq = direction * Vec(0.5, -0.5, 0.3, 0.2);
    Vec rigid, friction, rigid0, friction0;
    predict_effort(nominal, data, q, dq, ddq, rigid, friction);
    predict_effort(twin_nominal(), data, q, dq, ddq, rigid0, friction0);
    const Vec d = friction - friction0;
    EXPECT_NEAR(d[0], 3.0, 1e-9);  // a_c·|sgn q̇|: the same push either way
    EXPECT_NEAR(d[1], 2.0 * 0.5, 1e-9);
    EXPECT_NEAR(d[2], 0.5 * g2 * direction, 1e-9);
    EXPECT_NEAR(d[3], 0.25 * g2 * 0.2 * direction, 1e-9);
    EXPECT_EQ(rigid, rigid0);
  }
}

TEST(NominalModel, PredictionIsAllocationFree) {
  const Nominal nominal = twin_nominal();
  ArmData data;
  Vec rigid, friction;
  const Vec q = Vec::Constant(0.3), dq = Vec::Constant(0.1), ddq = Vec::Constant(-0.2);
  AllocationCounter counter;
  for (int i = 0; i < 10; ++i)
    predict_effort(nominal, data, q, dq, ddq, rigid, friction);
  EXPECT_EQ(counter.count(), 0u);
}

TEST(NominalModel, ParameterFileRoundTripPredictsTheSame) {
  Nominal nominal = twin_nominal();
  nominal.friction.load_coulomb[2] = 3.0;
  nominal.added.get<JointSpring>().stiffness[1] = 40.0;
  nominal.added.get<PositionRipple>().add({3, 50.0, true, 1.0, 2.0});
  nominal.added.get<MotionCoupling>().acceleration(2, 0) = 0.25;
  nominal.added.get<JointOffset>().offset[0] = -2.0;
  nominal.friction.coulomb_asymmetry[1] = 0.5 * nominal.friction.coulomb[1];
  nominal.friction.neighbour_load_coulomb(0, 1) = 0.3;
  nominal.friction.neighbour_load_viscous(2, 3) = 0.1;
  const auto path = temp_path("roundtrip.json");
  save_nominal_model<kJoints>(path, nominal, "test", R"({"rmse": [1, 2, 3, 4]})");
  const Nominal loaded = load_nominal_model<kJoints>(path, data_path("arm4.robot.json"));
  std::filesystem::remove(path);
  EXPECT_EQ(loaded.base_count, nominal.base_count);
  EXPECT_EQ(loaded.added.get<PositionRipple>().count, 1);
  EXPECT_TRUE(loaded.added.get<PositionRipple>().terms[0].motor_side);
  EXPECT_EQ(loaded.friction.neighbour_load_coulomb, nominal.friction.neighbour_load_coulomb);
  ArmData data;
  RandomStates states(5);
  for (int s = 0; s < 10; ++s) {
    const Vec q = states.vector(2.0), dq = states.vector(1.0), ddq = states.vector(3.0);
    Vec r1, f1, r2, f2;
    predict_effort(nominal, data, q, dq, ddq, r1, f1);
    predict_effort(loaded, data, q, dq, ddq, r2, f2);
    EXPECT_LT((r1 - r2).norm(), 1e-9 * (1.0 + r1.norm()));
    EXPECT_LT((f1 - f2).norm(), 1e-12 * (1.0 + f1.norm()));
  }
}

// Writes `text` to a file, loads it and returns the error message ("" when it loads).
std::string load_error(const std::string& text) {
  const auto path = temp_path("bad.json");
  std::ofstream(path) << text;
  std::string message;
  try {
    load_nominal_model<kJoints>(path, data_path("arm4.robot.json"));
  } catch (const Error& e) {
    message = e.what();
  }
  std::filesystem::remove(path);
  return message;
}

TEST(NominalModel, BadParameterFilesNameTheFileAndField) {
  const Nominal nominal = twin_nominal();
  const auto path = temp_path("good.json");
  save_nominal_model<kJoints>(path, nominal);
  std::ifstream in(path);
  const nlohmann::json good = nlohmann::json::parse(in);
  std::filesystem::remove(path);

  auto with = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json j = good;
    edit(j);
    return load_error(j.dump());
  };
  EXPECT_EQ(with([](nlohmann::json&) {}), "");
  EXPECT_NE(with([](nlohmann::json& j) { j["joints"] = 3; }).find("joints: the file is for 3"),
            std::string::npos);
  EXPECT_NE(with([](nlohmann::json& j) {
              j["friction"].erase("viscous");
            }).find("friction.viscous: missing"),
            std::string::npos);
  EXPECT_NE(with([](nlohmann::json& j) {
              j["friction"]["coulomb"][1] = -1.0;
            }).find("friction.coulomb[1]: must be >="),
            std::string::npos);
  EXPECT_NE(with([](nlohmann::json& j) {
              j["rigid_body"][0]["name"] = "Qxx9";
            }).find("rigid_body[0].name: unknown rigid-body parameter 'Qxx9'"),
            std::string::npos);
  // Another arm's parameters, e.g. with the tools' default robot file where the user's was meant.
  EXPECT_NE(with([](nlohmann::json& j) {
              j["robot"] = "arm2";
            }).find("robot: 'arm2', but the robot file "),
            std::string::npos);
  // A missing base parameter would be 0: a link without weight.
  EXPECT_NE(with([](nlohmann::json& j) {
              j["rigid_body"].erase(j["rigid_body"].size() - 1);
            }).find("rigid_body: 23 parameters, but the robot file has 24 base parameters"),
            std::string::npos);
  EXPECT_NE(with([](nlohmann::json& j) {
              j["rigid_body"] = nlohmann::json::array();
            }).find("rigid_body: 0 parameters"),
            std::string::npos);
  EXPECT_NE(with([](nlohmann::json& j) { j["format"] = "tpf-robot"; }).find("format"),
            std::string::npos);
  EXPECT_NE(with([](nlohmann::json& j) { j["colour"] = 1; }).find("colour: unknown key"),
            std::string::npos);
  // Effects the run time cannot evaluate are refused by name, not silently ignored.
  EXPECT_NE(with([](nlohmann::json& j) {
              j["added_effects"]["thermal_viscous"] = {0, 0, 0.1, 0};
            })
                .find("added_effects.thermal_viscous: temperature-dependent friction is not "
                      "evaluated"),
            std::string::npos);
  EXPECT_NE(with([](nlohmann::json& j) {
              j["added_effects"]["effort_lead_s"] = 0.01;
            }).find("added_effects.effort_lead_s: a delay"),
            std::string::npos);
  EXPECT_EQ(with([](nlohmann::json& j) { j["added_effects"]["effort_lead_s"] = 0.0; }), "");
  EXPECT_NE(with([](nlohmann::json& j) {
              j["friction"]["neighbour_load_coulomb"] = {
                  {1, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
            }).find("the diagonal must be zero"),
            std::string::npos);
  // A joint's own motion is the rigid body's: a coupling diagonal would be silently dropped.
  EXPECT_NE(with([](nlohmann::json& j) {
              j["added_effects"]["coupling_acceleration"] = {
                  {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0.5, 0}, {0, 0, 0, 0}};
            }).find("added_effects.coupling_acceleration: the diagonal must be zero"),
            std::string::npos);
  EXPECT_NE(with([](nlohmann::json& j) {
              const nlohmann::json term = {
                  {"joint", 5}, {"cycles_per_rev", 3.0}, {"sin", 0.1}, {"cos", 0.0}};
              j["added_effects"]["ripple"] = nlohmann::json::array({term});
            }).find("added_effects.ripple[0].joint"),
            std::string::npos);
  EXPECT_NE(load_error("{\"format\": \"tpf-params\",\n oops").find("bad.json:2"),
            std::string::npos);
}

TEST(NominalModel, AModelWithANonFiniteValueIsNotWritten) {
  // What a log sample of 1e300 A makes of a fit: JSON would hold null, which no reader takes.
  Nominal nominal = twin_nominal();
  nominal.friction.viscous[1] = std::numeric_limits<double>::quiet_NaN();
  const auto path = temp_path("nan.json");
  try {
    save_nominal_model<kJoints>(path, nominal);
    FAIL() << "a NaN viscous coefficient was written";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("friction.viscous[1]: not finite"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace tpf::test
