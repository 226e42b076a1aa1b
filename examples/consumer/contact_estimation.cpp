// The estimator in a controller, with tpf::core only: the arm's estimator, its sizes and
// compensator named as types, is loaded at start-up from the files the offline tools write (nominal
// model: `tpf identify`; pads; estimator parameters: `tpf calibrate`; compensator weights: `tpf
// train`), then updated once per 400 Hz cycle. The "sensors" here are synthetic: the arm holds a
// pose for 1 s, then a hand presses the forearm's top pad (index 4) with ≈ 8 N, which also loads
// the joints. Sensor noise is added: a reading that never changes is what a frozen sensor gives,
// and the estimator flags it. Exits 1 if the estimator misses the press or reports a contact at
// rest. Usage: contact_estimation <data dir, e.g. data>
#include <cstdio>
#include <random>
#include <string>
#include <tpf/core.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <data dir with arm4.*.json and weights/>\n", argv[0]);
    return 2;
  }
  const std::string dir = std::string(argv[1]) + "/";
  // The arm, named as types: 4 joints, 11 pads, one 16-channel float network per joint.
  constexpr int kJoints = 4, kPads = 11, kPushedPad = 4;
  using Compensator = tpf::PerJointTcn<tpf::BFloat16Weights, 16>;
  try {
    // Start-up: may allocate and throw tpf::Error naming the file and field.
    const auto estimator = tpf::load_estimator<kJoints, kPads, Compensator>(
        {dir + "arm4.params.json", dir + "arm4.robot.json", dir + "arm4.pads.json",
         dir + "arm4.estimator.json", dir + "weights/arm4.tcn.json"});
    const auto& nominal = estimator->nominal();
    tpf::Data<double, kJoints> data(nominal.model);
    tpf::EstimatorSample<double, kJoints, kPads> sample;
    sample.q << 0.0, 0.6, -0.9, 0.3;  // a held pose [rad]
    tpf::JointVector<double, kJoints> rigid, friction;
    tpf::predict_effort(nominal, data, sample.q, sample.dq, sample.dq, rigid, friction);
    // The drives report motor current [mA]; the estimator computes in N·m.
    const tpf::JointVector<double, kJoints> holding =
        tpf::current_from_torque(nominal.model, rigid);  // mA at rest

    // Per cycle: no allocation, no exception. The push lowers joints 2–3's current (τ_ext > 0
    // there) and raises the pad's pressure (1.5 kPa/N on the twin's pads).
    std::mt19937 rng(1);
    std::normal_distribution<double> current_noise(0.0, 8.0), pressure_noise(0.0, 0.02);
    bool missed = false, false_alarm = false;
    tpf::JointVector<double, kJoints> current;  // [mA], as the drives report it
    for (int k = 0; k < 800; ++k) {
      const bool pushed = k >= 400;
      sample.t = k / 400.0;
      for (int j = 0; j < kJoints; ++j)
        current[j] = holding[j] + current_noise(rng);
      for (int p = 0; p < kPads; ++p)
        sample.pressure[p] = pressure_noise(rng);
      if (pushed) {
        current[1] -= 900.0;
        current[2] -= 400.0;
        sample.pressure[kPushedPad] += 12.0;
      }
      sample.effort = tpf::torque_from_current(nominal.model, current);  // τ = K_t·i [N·m]
      const tpf::EstimatorOutput<double, kJoints>& out = estimator->update(sample);
      if (k < 400 && out.contact) false_alarm = true;
      if (k == 799) missed = !out.contact || out.wrench.pad != kPushedPad;
      if (k % 100 == 99)
        std::printf(
            "t = %.2f s  contact %d  pad %2d  |F| %5.1f N  tau_ext [N*m] %6.2f %6.2f %6.2f "
            "%6.2f  status 0x%x\n",
            sample.t, out.contact, out.wrench.pad, out.wrench.force_world.norm(),
            out.external.torque[0], out.external.torque[1], out.external.torque[2],
            out.external.torque[3], out.status);
    }
    if (false_alarm || missed) {
      std::fprintf(stderr, "error: %s\n",
                   false_alarm ? "contact reported at rest" : "the press on pad 4 was not seen");
      return 1;
    }
  } catch (const tpf::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
