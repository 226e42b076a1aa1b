#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>

#include "support/arm_fixture.hpp"
#include "support/temp_dir.hpp"

namespace tpf::test {
namespace {

namespace fs = std::filesystem;

/// This test program's files, removed at its end.
const TempDir kFiles("model_tests");

/// Writes `text` to a fresh file in the test folder and returns its path.
fs::path write(const std::string& name, const std::string& text) {
  std::ofstream(kFiles / name) << text;
  return kFiles / name;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

const char* kLink = R"(<link name="%s"><inertial><mass value="1"/><origin xyz="0 0 0.1"/>
  <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>)";

std::string link(const std::string& name) {
  std::string s = kLink;
  return s.replace(s.find("%s"), 2, name);
}

std::string joint(const std::string& name, const std::string& type, const std::string& parent,
                  const std::string& child) {
  return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent +
         "\"/><child link=\"" + child +
         "\"/><origin xyz=\"0 0 0.2\"/><axis xyz=\"0 1 0\"/>"
         "<limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"1\"/></joint>";
}

TEST(Loading, TheArmHasFourJointsWithPublishedMassesAndPositiveArmature) {
  const Arm& model = arm();
  EXPECT_EQ(model.joint_names[0], "joint1");
  EXPECT_EQ(model.link_names[4], "link5");
  EXPECT_DOUBLE_EQ(model.inertias[2].mass, 1.3026);  // link k moves with joint k: [2] is URDF link3
  EXPECT_NEAR(model.armature(0), 3.33e-6 * 501.923 * 501.923, 1e-9);
  EXPECT_DOUBLE_EQ(model.current_limit(3), 15900);
  EXPECT_EQ(load_pads(data_path("arm4.pads.json"), model).size(), 11u);
}

TEST(Loading, WrongJointCountIsRefusedNamingTheFile) {
  const std::string msg = message_of([] { load_robot<double, 3>(data_path("arm4.robot.json")); });
  EXPECT_NE(msg.find("arm4.urdf"), std::string::npos) << msg;
  EXPECT_NE(msg.find("has 4 joints"), std::string::npos) << msg;
}

TEST(Loading, PlanarJointIsRefusedNamingTheJoint) {
  const fs::path p = write("planar.urdf", "<robot name=\"r\">" + link("a") + link("b") +
                                              joint("slide", "planar", "a", "b") + "</robot>");
  const std::string msg = message_of([&] { load_urdf_chain(p); });
  EXPECT_NE(msg.find("planar.urdf"), std::string::npos) << msg;
  EXPECT_NE(msg.find("joint 'slide'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("is planar"), std::string::npos) << msg;
}

TEST(Loading, BranchingTreeIsRefusedNamingTheLink) {
  const fs::path p = write("branch.urdf", "<robot name=\"r\">" + link("a") + link("b") + link("c") +
                                              joint("j1", "revolute", "a", "b") +
                                              joint("j2", "revolute", "a", "c") + "</robot>");
  const std::string msg = message_of([&] { load_urdf_chain(p); });
  EXPECT_NE(msg.find("link 'a'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("branches"), std::string::npos) << msg;
}

TEST(Loading, MalformedXmlIsRefusedNamingTheFile) {
  const fs::path p = write("broken.urdf", "<robot name=\"r\"><link name=\"a\">");
  const std::string msg = message_of([&] { load_urdf_chain(p); });
  EXPECT_NE(msg.find("broken.urdf"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not a valid URDF"), std::string::npos) << msg;
}

TEST(Loading, AMassThatIsNotANumberIsRefusedNotDropped) {
  // urdfdom logs the bad value and goes on without the link's <inertial>: a massless link.
  for (const std::string value : {"heavy", "nan"}) {
    std::string b = link("b");
    b.replace(b.find("value=\"1\""), 9, "value=\"" + value + "\"");
    const fs::path p = write("mass.urdf", "<robot name=\"r\">" + link("a") + b +
                                              joint("j1", "revolute", "a", "b") + "</robot>");
    const std::string msg = message_of([&] { load_urdf_chain(p); });
    EXPECT_NE(msg.find("mass.urdf"), std::string::npos) << msg;
    EXPECT_NE(msg.find("mass [" + value + "] is not a float"), std::string::npos) << msg;
  }
}

TEST(Loading, JointLimitsReversedAreRefusedAndAContinuousJointHasNoVelocityLimit) {
  const auto with_limit = [](const std::string& type, const std::string& limit) {
    std::string j = joint("j1", type, "a", "b");
    const std::size_t at = j.find("<limit");
    return j.replace(at, j.find("/>", at) + 2 - at, limit);
  };
  const fs::path p =
      write("limits.urdf",
            "<robot name=\"r\">" + link("a") + link("b") +
                with_limit("revolute",
                           "<limit lower=\"2.5\" upper=\"-2.5\" velocity=\"1\" effort=\"10\"/>") +
                "</robot>");
  const std::string msg = message_of([&] { load_urdf_chain(p); });
  EXPECT_NE(msg.find("joint 'j1': <limit> lower 2.5"), std::string::npos) << msg;
  // Without <limit> the twin's drive clamped the speed to 0: the joint never moved.
  const fs::path c = write("continuous.urdf", "<robot name=\"r\">" + link("a") + link("b") +
                                                  with_limit("continuous", "") + "</robot>");
  const ChainDescription chain = load_urdf_chain(c);
  ASSERT_EQ(chain.joints.size(), 1u);
  EXPECT_EQ(chain.joints[0].velocity_limit, std::numeric_limits<double>::infinity());
  EXPECT_EQ(chain.joints[0].effort_limit, std::numeric_limits<double>::infinity());
}

TEST(Loading, FixedLinksAreFoldedIntoTheirMovingParent) {
  // b carries a fixed child f of 1 kg at 0.2 m: the chain has one joint, link b weighs 2 kg.
  const fs::path p = write("fixed.urdf", "<robot name=\"r\">" + link("a") + link("b") + link("f") +
                                             joint("j1", "revolute", "a", "b") +
                                             joint("tool", "fixed", "b", "f") + "</robot>");
  const ChainDescription chain = load_urdf_chain(p);
  ASSERT_EQ(chain.joints.size(), 1u);
  EXPECT_DOUBLE_EQ(chain.inertias[1].mass, 2.0);
  EXPECT_NEAR(chain.inertias[1].com.z(), 0.2, 1e-15);  // (0.1 + 0.3) / 2
  // Steiner: each 1 kg body sits 0.1 m from the common centre: Ixx = 2·0.01 + 2·1·0.1².
  EXPECT_NEAR(chain.inertias[1].rotational(0, 0), 0.04, 1e-15);
}

/// A link named `name` with the given <inertia> attributes (mass 1 kg at the frame's origin).
std::string link_with_inertia(const std::string& name, const std::string& inertia) {
  return "<link name=\"" + name + "\"><inertial><mass value=\"1\"/><inertia " + inertia +
         "/></inertial></link>";
}

/// What loading `urdf` prints to stderr (the chain itself is not looked at).
std::string stderr_of_loading(const fs::path& urdf) {
  testing::internal::CaptureStderr();
  load_urdf_chain(urdf);
  return testing::internal::GetCapturedStderr();
}

TEST(Loading, AMovingLinkWithoutInertialIsRefusedNamingFileLineAndLink) {
  // Was: loaded as a massless link. Line 2 holds <link name="b"/>.
  const fs::path p =
      write("no_inertial.urdf", "<robot name=\"r\">\n<link name=\"b\"/>\n" + link("a") +
                                    joint("j1", "revolute", "a", "b") + "</robot>");
  EXPECT_EQ(message_of([&] { load_urdf_chain(p); }),
            p.string() +
                ":2: link 'b' has no <inertial>: it moves with joint 'j1' and no link fixed to it "
                "has one, so it would move without mass; give it an <inertial> (with <mass "
                "value=\"0\"/> if it has none)");
  // The same behind a fixed joint between moving links: b and its fixed child c are one body.
  const fs::path q =
      write("no_inertial_chain.urdf",
            "<robot name=\"r\">" + link("a") + "<link name=\"b\"/><link name=\"c\"/>" + link("d") +
                joint("j1", "revolute", "a", "b") + joint("flange", "fixed", "b", "c") +
                joint("j2", "revolute", "c", "d") + "</robot>");
  EXPECT_NE(message_of([&] {
              load_urdf_chain(q);
            }).find(": link 'b' has no <inertial>: it moves with joint 'j1' and"),
            std::string::npos);
}

TEST(Loading, MasslessBaseFramesAndAnExplicitZeroMassLoad) {
  // A massless root, a massless tool frame fixed to a body with mass, a massless link that takes
  // its mass from the flange fixed to it between two moving links, an explicit zero mass.
  const std::string zero =
      R"(<link name="e"><inertial><mass value="0"/><inertia ixx="0" iyy="0" izz="0" ixy="0")"
      R"( ixz="0" iyz="0"/></inertial></link>)";
  const fs::path p = write(
      "massless_frames.urdf",
      "<robot name=\"r\"><link name=\"world\"/>" + link("a") + "<link name=\"b\"/>" +
          link("flange") + link("c") + "<link name=\"tool\"/>" + zero +
          joint("base", "fixed", "world", "a") + joint("j1", "revolute", "a", "b") +
          joint("flange", "fixed", "b", "flange") + joint("j2", "revolute", "flange", "c") +
          joint("tool", "fixed", "c", "tool") + joint("j3", "revolute", "c", "e") + "</robot>");
  const ChainDescription chain = load_urdf_chain(p);
  ASSERT_EQ(chain.joints.size(), 3u);
  EXPECT_DOUBLE_EQ(chain.inertias[0].mass, 1.0);  // world + a
  EXPECT_DOUBLE_EQ(chain.inertias[1].mass, 1.0);  // b + flange
  EXPECT_DOUBLE_EQ(chain.inertias[2].mass, 1.0);  // c + tool
  EXPECT_DOUBLE_EQ(chain.inertias[3].mass, 0.0);  // e, declared massless
}

TEST(Loading, InertiaBreakingTheTriangleInequalityIsReportedNamingTheInequality) {
  // Was: accepted silently. Not physical (no body has ixx + iyy < izz), but M(q) stays positive
  // definite: a warning, as the Kinova Gen3's published tensors break it too.
  const fs::path diagonal = write(
      "triangle_diagonal.urdf",
      "<robot name=\"r\">\n" +
          link_with_inertia("b", R"(ixx="0.01" iyy="0.01" izz="0.03" ixy="0" ixz="0" iyz="0")") +
          "\n" + link("a") + joint("j1", "revolute", "a", "b") + "</robot>");
  EXPECT_EQ(stderr_of_loading(diagonal),
            "tpf: warning: " + diagonal.string() +
                ":2: link 'b': inertia breaks the triangle inequality (ixx + iyy = 0.02 < izz = "
                "0.03 kg·m²): no rigid body has this inertia; check the <inertia> values and their "
                "frame\n");
  // Principal moments 0.01, 0.01, 0.03 turned 45° about x: every diagonal inequality holds.
  const fs::path turned = write(
      "triangle_turned.urdf",
      "<robot name=\"r\">" + link("a") +
          link_with_inertia("b", R"(ixx="0.01" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0.01")") +
          joint("j1", "revolute", "a", "b") + "</robot>");
  EXPECT_NE(stderr_of_loading(turned).find(
                "link 'b': inertia breaks the triangle inequality (principal moments I1 + I2 = "
                "0.02 < I3 = 0.03 kg·m²)"),
            std::string::npos);
  // A thin rod (0 + I = I) and CAD rounding within 1e-9 pass; 1e-8 beyond does not.
  const auto rod = [](const std::string& name, const std::string& izz) {
    return write(name, "<robot name=\"r\">" + link("a") +
                           link_with_inertia("b", "ixx=\"0.005\" iyy=\"0.005\" izz=\"" + izz +
                                                      "\" ixy=\"0\" ixz=\"0\" iyz=\"0\"") +
                           joint("j1", "revolute", "a", "b") + "</robot>");
  };
  EXPECT_EQ(stderr_of_loading(rod("rod_exact.urdf", "0.01")), "");
  EXPECT_EQ(stderr_of_loading(rod("rod_rounded.urdf", "0.0100000000098")), "");
  EXPECT_NE(stderr_of_loading(rod("rod_beyond.urdf", "0.0100000002"))
                .find("ixx + iyy = 0.01 < izz = 0.0100000002 kg·m²"),
            std::string::npos);
  // The shipped robots: the arm and the bench are physical; the Gen3 (the maker's tensors) loads
  // with its warnings.
  EXPECT_EQ(stderr_of_loading(data_path("arm4.urdf")), "");
  EXPECT_EQ(stderr_of_loading(data_path("bench1.urdf")), "");
  const std::string gen3 = stderr_of_loading(data_path("real/kinova-gen3/gen3.urdf"));
  EXPECT_NE(gen3.find("'shoulder_link'"), std::string::npos) << gen3;
  // Its base_link breaks it too, but the base (the root and what is fixed to it) never moves.
  EXPECT_EQ(gen3.find("'base_link'"), std::string::npos) << gen3;
  const std::string broken = R"(ixx="0.01" iyy="0.01" izz="0.03" ixy="0" ixz="0" iyz="0")";
  EXPECT_EQ(stderr_of_loading(
                write("triangle_base.urdf", "<robot name=\"r\"><link name=\"world\"/>" +
                                                link_with_inertia("base", broken) + link("b") +
                                                joint("fix", "fixed", "world", "base") +
                                                joint("j1", "revolute", "base", "b") + "</robot>")),
            "");
}

TEST(Loading, InertiaThatIsNotPositiveSemiDefiniteIsRefused) {
  const fs::path p = write(
      "indefinite.urdf",
      "<robot name=\"r\">\n" +
          link_with_inertia("b", R"(ixx="0.01" iyy="0.01" izz="-0.001" ixy="0" ixz="0" iyz="0")") +
          "\n" + link("a") + joint("j1", "revolute", "a", "b") + "</robot>");
  EXPECT_EQ(message_of([&] { load_urdf_chain(p); }),
            p.string() + ":2: link 'b': inertia is not positive semi-definite");
}

TEST(Loading, RobotFileWithUnknownKeyIsRefusedNamingIt) {
  const fs::path urdf = write("one.urdf", "<robot name=\"r\">" + link("a") + link("b") +
                                              joint("j1", "revolute", "a", "b") + "</robot>");
  const fs::path robot = write("one.robot.json", R"({"format": "tpf-robot", "version": 1,
    "urdf": "one.urdf", "joints": [{"name": "j1", "gear_ratio": 100, "rotor_inertia": 1e-6,
    "torque_constant": 2, "current_limit": 1000, "gear_ration": 3}]})");
  (void)urdf;
  const std::string msg = message_of([&] { load_robot<double, 1>(robot); });
  EXPECT_NE(msg.find("one.robot.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find("joints[0].gear_ration"), std::string::npos) << msg;
}

TEST(Loading, JsonSyntaxErrorNamesTheLine) {
  const fs::path robot =
      write("bad.robot.json", "{\n\"format\": \"tpf-robot\",\n\"version\": 1,,\n}");
  const std::string msg = message_of([&] { load_robot_description(robot); });
  EXPECT_NE(msg.find("bad.robot.json:3"), std::string::npos) << msg;
}

TEST(Loading, PadOnUnknownLinkIsRefusedNamingThePad) {
  const fs::path pads = write("pads.json", R"({"format": "tpf-pads", "version": 1, "pads": [
    {"name": "elbow", "link": "link9", "center": [0, 0, 0], "normal": [0, 0, 1], "area": 0.001}]})");
  const std::string msg = message_of([&] { load_pads(pads, arm()); });
  EXPECT_NE(msg.find("pads[0].link"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'elbow'"), std::string::npos) << msg;
}

}  // namespace
}  // namespace tpf::test
