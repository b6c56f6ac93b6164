#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <tuple>
#include <algorithm>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "sixdof_core/collision.h"
#include "sixdof_core/setup_assistant.h"
#include "test_description.h"

using namespace sixdof_core;

namespace {

const std::string kDataDir = SIXDOF_TEST_DATA_DIR;
std::string armUrdf() { return sixdof_test::descriptionDir() + "/urdf/sixdof.urdf"; }
std::string armSrdf() { return sixdof_test::descriptionDir() + "/config/sixdof.srdf"; }
const std::string kUrUrdf = kDataDir + "/ur_like.urdf";
const std::string kUrSrdf = kDataDir + "/ur_like.srdf";
// The density the committed SRDF was generated with (the paper's "low sampling density").
constexpr std::size_t kCommittedDensity = 1000;

PackageResolver armResolver() { return PackageResolver::fromSearchRoots({sixdof_test::descriptionDir() + "/.."}); }
PackageResolver urResolver() { return PackageResolver::fromSearchRoots({kDataDir + "/../.."}); }

RobotModelConstPtr model(const std::string& urdf, const std::string& srdf, const PackageResolver& resolver) {
  return std::make_shared<const RobotModel>(urdf, srdf, resolver);
}

RobotModelConstPtr armModel() { return model(readTextFile(armUrdf()), readTextFile(armSrdf()), armResolver()); }

using NamePair = std::pair<std::string, std::string>;

NamePair unordered(const std::string& a, const std::string& b) { return a < b ? NamePair(a, b) : NamePair(b, a); }

std::set<NamePair> pairsWithReason(const DisabledCollisions& result, DisableReason reason) {
  std::set<NamePair> pairs;
  for (const auto& p : result.disabled) {
    if (p.reason == reason) pairs.insert(unordered(p.link1, p.link2));
  }
  return pairs;
}

// Link pairs in collision at a state, with nothing allowed (an independent check of the classification).
std::set<NamePair> collidingPairs(const CollisionScene& scene, const RobotState& state) {
  CollisionRequest request;
  request.scope = CollisionScope::kSelf;
  std::set<NamePair> pairs;
  for (const auto& c : scene.checkCollision(state.linkTransforms(), request).contacts) {
    pairs.insert(unordered(c.body1, c.body2));
  }
  return pairs;
}

// base_link -(slider, prismatic x in [-1, 1])-> l1 -(fixed)-> l2 -(fixed)-> l3. l2 is a small cube that
// fits the 4 cm gap between two base boxes around x = 0 (free at the default state, colliding in ~97.5%
// of samples: Always); l3 always overlaps the base plate (Default); l1 is far above everything (Never with l3).
const char* const kSliderUrdf = R"(<?xml version="1.0"?>
<robot name="slider">
  <link name="base_link">
    <collision><origin xyz="-0.56 0 0"/><geometry><box size="1.08 0.2 0.2"/></geometry></collision>
    <collision><origin xyz="0.56 0 0"/><geometry><box size="1.08 0.2 0.2"/></geometry></collision>
    <collision><origin xyz="0 0 -1"/><geometry><box size="4 4 0.2"/></geometry></collision>
  </link>
  <link name="l1"><collision><origin xyz="0 0 5"/><geometry><sphere radius="0.01"/></geometry></collision></link>
  <link name="l2"><collision><geometry><box size="0.01 0.01 0.01"/></geometry></collision></link>
  <link name="l3"><collision><origin xyz="0 0 -1"/><geometry><box size="0.1 0.1 0.3"/></geometry></collision></link>
  <joint name="slider" type="prismatic">
    <parent link="base_link"/><child link="l1"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" velocity="1" effort="1"/>
  </joint>
  <joint name="l2_joint" type="fixed"><parent link="l1"/><child link="l2"/></joint>
  <joint name="l3_joint" type="fixed"><parent link="l2"/><child link="l3"/></joint>
</robot>)";

// a -> b (no geometry) -> c, and b -> d: MoveIt collapses b, so a, c and d are pairwise adjacent.
const char* const kGeometrylessUrdf = R"(<?xml version="1.0"?>
<robot name="hollow">
  <link name="a"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="b"/>
  <link name="c"><collision><origin xyz="0 0 1"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="d"><collision><origin xyz="0 1 0"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="e"><collision><origin xyz="0 0 1"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="ab" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" velocity="1" effort="1"/></joint>
  <joint name="bc" type="fixed"><parent link="b"/><child link="c"/></joint>
  <joint name="bd" type="fixed"><parent link="b"/><child link="d"/></joint>
  <joint name="ce" type="revolute"><parent link="c"/><child link="e"/><origin xyz="0 0 1"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" velocity="1" effort="1"/></joint>
</robot>)";

// A palm turning on a base, with two fingers (the second mimics the first) that slide into each other over the
// upper half of their range: their pair collides in about half of the samples.
const char* const kPincerUrdf = R"(<?xml version="1.0"?>
<robot name="pincer">
  <link name="base_link"><collision><origin xyz="0 0 -1"/><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <link name="palm"><collision><geometry><box size="0.05 0.1 0.05"/></geometry></collision></link>
  <link name="left_finger"><collision><geometry><box size="0.01 0.02 0.05"/></geometry></collision></link>
  <link name="right_finger"><collision><geometry><box size="0.01 0.02 0.05"/></geometry></collision></link>
  <joint name="turn" type="revolute"><parent link="base_link"/><child link="palm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" velocity="1" effort="1"/></joint>
  <joint name="left" type="prismatic"><parent link="palm"/><child link="left_finger"/><origin xyz="0 0.03 0.1"/>
    <axis xyz="0 -1 0"/><limit lower="0" upper="0.04" velocity="1" effort="1"/></joint>
  <joint name="right" type="prismatic"><parent link="palm"/><child link="right_finger"/><origin xyz="0 -0.03 0.1"/>
    <axis xyz="0 1 0"/><limit lower="0" upper="0.04" velocity="1" effort="1"/><mimic joint="left"/></joint>
</robot>)";
const char* const kPincerSrdf = R"(<robot name="pincer">
  <group name="arm"><joint name="turn"/></group>
  <group name="gripper"><joint name="left"/><joint name="right"/></group>
  <end_effector name="hand" parent_link="palm" group="gripper"/>
</robot>)";

SetupAssistantOptions options(std::size_t density, std::uint64_t seed) {
  SetupAssistantOptions o;
  o.collision.density = density;
  o.collision.seed = seed;
  return o;
}

}  // namespace

TEST(SetupAssistant, ArmAdjacentPairsAreExactlyTheTreeNeighboursWithGeometry) {
  const auto arm = armModel();
  std::set<NamePair> expected;
  for (const auto& joint : arm->joints()) {
    const bool parent_has_geometry = !arm->link(joint.parent_link).collision.shapes.empty();
    if (parent_has_geometry && !arm->link(joint.child_link).collision.shapes.empty()) {
      expected.insert(unordered(joint.parent_link, joint.child_link));
    }
  }
  EXPECT_EQ(expected.size(), 9u);
  EXPECT_FALSE(expected.count(unordered("link6", "tcp")));
  CollisionMatrixOptions o;
  o.density = kCommittedDensity;
  const auto result = computeDisabledCollisions(arm, o);
  EXPECT_EQ(pairsWithReason(result, DisableReason::kAdjacent), expected);
  EXPECT_EQ(result.link_pairs, 45u);
}

TEST(SetupAssistant, AdjacencyPassesThroughLinksWithoutGeometry) {
  const auto m = model(kGeometrylessUrdf, "<robot name=\"hollow\"/>", PackageResolver());
  const auto pairs = adjacentLinkPairs(*m);
  const std::vector<NamePair> expected{{"a", "c"}, {"a", "d"}, {"c", "d"}, {"c", "e"}};
  EXPECT_EQ(pairs, expected);
}

TEST(SetupAssistant, ArmNeverPairsNeverCollideInAnIndependentResampling) {
  const auto arm = armModel();
  CollisionMatrixOptions o;
  o.density = kCommittedDensity;
  o.seed = 0;
  const auto never = pairsWithReason(computeDisabledCollisions(arm, o), DisableReason::kNever);
  ASSERT_FALSE(never.empty());

  const CollisionScene scene(allLinkGeometry(*arm), {});
  StateSampler sampler(*arm, 20261121);
  RobotState state(arm);
  std::size_t never_collisions = 0;
  std::size_t other_collisions = 0;
  for (int i = 0; i < 20000; ++i) {
    state.setPositions(sampler.sample());
    ASSERT_TRUE(state.satisfiesBounds());
    ASSERT_DOUBLE_EQ(state.jointPosition("finger2_joint"), state.jointPosition("finger1_joint"));
    for (const auto& pair : collidingPairs(scene, state)) (never.count(pair) ? never_collisions : other_collisions)++;
  }
  EXPECT_EQ(never_collisions, 0u);
  // The sampling does reach colliding configurations of the pairs left enabled.
  EXPECT_GT(other_collisions, 0u);
}

TEST(SetupAssistant, DefaultAlwaysAndNeverOnAFixtureThatHasEach) {
  const auto m = model(kSliderUrdf, "<robot name=\"slider\"/>", PackageResolver());
  CollisionMatrixOptions o;
  o.density = 1000;
  const auto result = computeDisabledCollisions(m, o);
  EXPECT_EQ(pairsWithReason(result, DisableReason::kAdjacent),
            (std::set<NamePair>{unordered("base_link", "l1"), unordered("l1", "l2"), unordered("l2", "l3")}));
  EXPECT_EQ(pairsWithReason(result, DisableReason::kDefault), (std::set<NamePair>{unordered("base_link", "l3")}));
  EXPECT_EQ(pairsWithReason(result, DisableReason::kAlways), (std::set<NamePair>{unordered("base_link", "l2")}));
  EXPECT_EQ(pairsWithReason(result, DisableReason::kNever), (std::set<NamePair>{unordered("l1", "l3")}));
  EXPECT_EQ(result.disabled.size(), result.link_pairs);

  // Default pairs collide at the default state, Always pairs do not (else they would be Default).
  const CollisionScene scene(allLinkGeometry(*m), {});
  const auto at_default = collidingPairs(scene, RobotState(m));
  EXPECT_TRUE(at_default.count(unordered("base_link", "l3")));
  EXPECT_FALSE(at_default.count(unordered("base_link", "l2")));
  for (const auto& p : result.disabled) {
    if (p.reason == DisableReason::kAlways) {
      EXPECT_GT(p.colliding_samples, 950u);
    }
  }
}

TEST(SetupAssistant, GripperLinksThatCollideInSomeStatesAreDisabledAsGripper) {
  CollisionMatrixOptions o;
  o.density = 500;
  const auto result = computeDisabledCollisions(model(kPincerUrdf, kPincerSrdf, PackageResolver()), o);
  EXPECT_EQ(pairsWithReason(result, DisableReason::kGripper),
            (std::set<NamePair>{unordered("left_finger", "right_finger")}));
  const auto gripper = std::find_if(result.disabled.begin(), result.disabled.end(),
                                    [](const ComputedPair& p) { return p.reason == DisableReason::kGripper; });
  ASSERT_NE(gripper, result.disabled.end());
  EXPECT_GT(gripper->colliding_samples, 0u);  // counted until the pair could no longer be Always
  EXPECT_EQ(reasonName(DisableReason::kGripper), "Gripper");
  // Without an end effector in the SRDF no link is a gripper's: the pair stays checked.
  const auto plain = computeDisabledCollisions(model(kPincerUrdf, "<robot name=\"pincer\"/>", PackageResolver()), o);
  EXPECT_TRUE(pairsWithReason(plain, DisableReason::kGripper).empty());
  EXPECT_EQ(plain.disabled.size() + 1, result.disabled.size());
}

TEST(SetupAssistant, DefaultPairsOfTheArmCollideAtTheDefaultState) {
  const auto arm = armModel();
  CollisionMatrixOptions o;
  o.density = kCommittedDensity;
  const auto result = computeDisabledCollisions(arm, o);
  const CollisionScene scene(allLinkGeometry(*arm), {});
  const auto at_default = collidingPairs(scene, RobotState(arm));
  for (const auto& pair : pairsWithReason(result, DisableReason::kDefault)) EXPECT_TRUE(at_default.count(pair));
  // Every pair colliding at the default state is disabled as Adjacent or Default.
  for (const auto& pair : at_default) {
    EXPECT_TRUE(pairsWithReason(result, DisableReason::kAdjacent).count(pair) ||
                pairsWithReason(result, DisableReason::kDefault).count(pair))
        << pair.first << " " << pair.second;
  }
}

TEST(SetupAssistant, SameSeedGivesTheSameBytesAndTheOutputIsAFixedPoint) {
  const std::string urdf = readTextFile(armUrdf());
  const std::string srdf = readTextFile(armSrdf());
  const auto first = runSetupAssistant(urdf, srdf, options(kCommittedDensity, 7), armResolver());
  const auto second = runSetupAssistant(urdf, srdf, options(kCommittedDensity, 7), armResolver());
  EXPECT_EQ(first.srdf, second.srdf);
  EXPECT_EQ(runSetupAssistant(urdf, first.srdf, options(kCommittedDensity, 7), armResolver()).srdf, first.srdf);

  StateSampler a(*armModel(), 3), b(*armModel(), 3), c(*armModel(), 4);
  for (int i = 0; i < 10; ++i) {
    const Eigen::VectorXd qa = a.sample();
    EXPECT_EQ(qa, b.sample());
    EXPECT_NE(qa, c.sample());
  }
}

TEST(SetupAssistant, CommittedArmSrdfHoldsTheComputedPairsAtLowDensity) {
  const auto arm = armModel();
  CollisionMatrixOptions o;
  o.density = kCommittedDensity;
  o.seed = 0;
  std::set<std::tuple<std::string, std::string, std::string>> computed, committed;
  for (const auto& p : computeDisabledCollisions(arm, o).disabled) {
    const auto u = unordered(p.link1, p.link2);
    computed.emplace(u.first, u.second, reasonName(p.reason));
  }
  for (const auto& p : arm->disabledCollisionPairs()) {
    const auto u = unordered(p.link1, p.link2);
    committed.emplace(u.first, u.second, p.reason);
  }
  EXPECT_EQ(committed, computed);
}

TEST(SetupAssistant, KeepsHandWrittenPartsAndReplacesOnlyComputedReasons) {
  const std::string urdf = readTextFile(armUrdf());
  std::string srdf = readTextFile(armSrdf());
  const std::string extra =
      "  <passive_joint name=\"finger2_joint\"/>\n"
      "  <disable_collisions link1=\"link1\" link2=\"link2\" reason=\"User\"/>\n"
      "  <disable_collisions link1=\"base_link\" link2=\"link6\" reason=\"Never\"/>\n"
      "  <disable_collisions link2=\"finger1\" link1=\"link2\" reason=\"User\"/>\n"
      "</robot>";
  srdf.replace(srdf.rfind("</robot>"), std::string("</robot>").size(), extra);
  const auto result = runSetupAssistant(urdf, srdf, options(kCommittedDensity, 0), armResolver());
  EXPECT_EQ(result.manual_pairs_kept, 2u);

  const auto in = parseSrdfDocument(srdf);
  const auto out = parseSrdfDocument(result.srdf);
  auto same = [](const std::vector<XmlElement>& a, const std::vector<XmlElement>& b) {
    if (a.size() != b.size()) return false;
    SrdfDocument da, db;
    da.robot_name = db.robot_name = "x";
    da.groups = a;
    db.groups = b;
    return writeSrdf(da) == writeSrdf(db);
  };
  EXPECT_EQ(out.robot_name, "sixdof");
  EXPECT_EQ(out.leading_comments, in.leading_comments);
  EXPECT_TRUE(same(out.groups, in.groups));
  EXPECT_TRUE(same(out.group_states, in.group_states));
  EXPECT_TRUE(same(out.end_effectors, in.end_effectors));
  EXPECT_TRUE(same(out.virtual_joints, in.virtual_joints));
  ASSERT_EQ(out.passive_joints.size(), 1u);
  EXPECT_EQ(out.passive_joints[0].attribute("name"), "finger2_joint");

  std::map<NamePair, std::string> reasons;
  for (const auto& p : out.disabled_collisions) {
    EXPECT_TRUE(reasons.emplace(unordered(p.link1, p.link2), p.reason).second) << "duplicate " << p.link1;
  }
  // A hand-written entry wins over the computed one for the same pair; its attributes stay as written.
  EXPECT_EQ(reasons.at(unordered("link1", "link2")), "User");
  EXPECT_EQ(reasons.at(unordered("link2", "finger1")), "User");
  EXPECT_NE(result.srdf.find("link1=\"link2\" link2=\"finger1\" reason=\"User\""), std::string::npos);
  // A stale computed entry is dropped: base_link and link6 do collide in some states.
  EXPECT_FALSE(reasons.count(unordered("base_link", "link6")));
  EXPECT_EQ(reasons.at(unordered("link5", "link6")), "Adjacent");
  // Sorted: Adjacent, Default, Always, Never, then hand-written reasons.
  const std::vector<std::string> order{"Adjacent", "Default", "Always", "Never", "User"};
  int last = 0;
  for (const auto& p : out.disabled_collisions) {
    const int rank = static_cast<int>(std::find(order.begin(), order.end(), p.reason) - order.begin());
    EXPECT_GE(rank, last);
    last = rank;
  }
}

TEST(SetupAssistant, SecondFixtureUrdfWithItsSrdfAndWithASkeleton) {
  const std::string urdf = readTextFile(kUrUrdf);
  const auto with_srdf = runSetupAssistant(urdf, readTextFile(kUrSrdf), options(2000, 1), urResolver());
  EXPECT_FALSE(with_srdf.skeleton_written);
  const auto ur = model(urdf, with_srdf.srdf, urResolver());
  ASSERT_NE(ur->findGroup("manipulator"), nullptr);
  ASSERT_NE(ur->findGroupState("manipulator", "up"), nullptr);
  EXPECT_EQ(pairsWithReason(with_srdf.collisions, DisableReason::kAdjacent),
            (std::set<NamePair>{unordered("base_link", "shoulder_link"), unordered("shoulder_link", "upper_arm_link"),
                                unordered("upper_arm_link", "forearm_link"), unordered("forearm_link", "wrist_1_link"),
                                unordered("wrist_1_link", "wrist_2_link"), unordered("wrist_2_link", "wrist_3_link")}));
  const auto never = pairsWithReason(with_srdf.collisions, DisableReason::kNever);
  ASSERT_FALSE(never.empty());
  const CollisionScene scene(allLinkGeometry(*ur), {});
  StateSampler sampler(*ur, 99);
  RobotState state(ur);
  for (int i = 0; i < 5000; ++i) {
    state.setPositions(sampler.sample());
    for (const auto& pair : collidingPairs(scene, state)) ASSERT_FALSE(never.count(pair)) << pair.first << pair.second;
  }

  SetupAssistantOptions skeleton = options(1000, 0);
  skeleton.groups_skeleton = true;
  const auto from_urdf = runSetupAssistant(urdf, "", skeleton, urResolver());
  EXPECT_TRUE(from_urdf.skeleton_written);
  const auto m = model(urdf, from_urdf.srdf, urResolver());
  const JointGroup* arm = m->findGroup("arm");
  ASSERT_NE(arm, nullptr);
  EXPECT_EQ(arm->chain_base, "base_link");
  EXPECT_EQ(arm->chain_tip, "wrist_3_link");
  EXPECT_EQ(arm->active_joints.size(), 6u);
  EXPECT_EQ(m->findGroup("gripper"), nullptr);  // no movable joint outside the arm
  EXPECT_TRUE(m->endEffectors().empty());
}

TEST(SetupAssistant, SkeletonForOurArmMatchesTheDesign) {
  SetupAssistantOptions o = options(1000, 0);
  o.groups_skeleton = true;
  const std::string urdf = readTextFile(armUrdf());
  const auto result = runSetupAssistant(urdf, "", o, armResolver());
  const auto m = model(urdf, result.srdf, armResolver());
  ASSERT_NE(m->findGroup("arm"), nullptr);
  EXPECT_EQ(m->findGroup("arm")->chain_tip, "link6");
  ASSERT_NE(m->findGroup("gripper"), nullptr);
  EXPECT_EQ(m->findGroup("gripper")->joints, (std::vector<std::string>{"finger1_joint", "finger2_joint"}));
  ASSERT_EQ(m->endEffectors().size(), 1u);
  EXPECT_EQ(m->endEffectors()[0].parent_link, "link6");
  EXPECT_EQ(m->endEffectors()[0].group, "gripper");
  // An input with groups keeps them: no skeleton.
  EXPECT_FALSE(runSetupAssistant(urdf, readTextFile(armSrdf()), o, armResolver()).skeleton_written);
}

TEST(SetupAssistant, BadInputsAreNamed) {
  const std::string urdf = readTextFile(kUrUrdf);
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_THROW(runSetupAssistant("<robot", "", options(100, 0), urResolver()), RobotModelError);
  EXPECT_THROW(runSetupAssistant(urdf, "<robot name=\"ur_like\">", options(100, 0), urResolver()), SrdfError);
  EXPECT_NE(message([&] { runSetupAssistant(urdf, "<robot name=\"other\"/>", options(100, 0), urResolver()); })
                .find("does not match"),
            std::string::npos);
  const std::string unknown_link = "<robot name=\"ur_like\"><disable_collisions link1=\"x\" link2=\"tool0\"/></robot>";
  EXPECT_NE(message([&] { runSetupAssistant(urdf, unknown_link, options(100, 0), urResolver()); }).find("'x'"),
            std::string::npos);
  const std::string unknown_element = "<robot name=\"ur_like\"><link/></robot>";
  EXPECT_NE(message([&] { runSetupAssistant(urdf, unknown_element, options(100, 0), urResolver()); }).find("<link>"),
            std::string::npos);
  EXPECT_THROW(runSetupAssistant(urdf, "", options(0, 0), urResolver()), std::invalid_argument);
  EXPECT_THROW(runSetupAssistant(urdf, "", options(100, 0), PackageResolver()), RobotModelError);  // mesh not found

  EXPECT_NE(message([] { parseSetupAssistantArguments({"--urdf", "a", "--srdf-out", "b", "--density", "0"}); })
                .find("--density must be a whole number > 0"),
            std::string::npos);
  EXPECT_THROW(parseSetupAssistantArguments({"--urdf", "a", "--srdf-out", "b", "--density", "-5"}),
               std::invalid_argument);
  EXPECT_THROW(parseSetupAssistantArguments({"--urdf", "a", "--srdf-out", "b", "--density", "1e3"}),
               std::invalid_argument);
  EXPECT_THROW(parseSetupAssistantArguments({"--urdf", "a", "--srdf-out", "b", "--seed", "x"}), std::invalid_argument);
  EXPECT_THROW(parseSetupAssistantArguments({"--urdf", "a"}), std::invalid_argument);
  EXPECT_THROW(parseSetupAssistantArguments({"--srdf-out", "a"}), std::invalid_argument);
  EXPECT_THROW(parseSetupAssistantArguments({"--urdf"}), std::invalid_argument);
  EXPECT_THROW(parseSetupAssistantArguments({"--bogus"}), std::invalid_argument);
  const auto ok = parseSetupAssistantArguments(
      {"--urdf", "a", "--srdf-in", "c", "--srdf-out", "b", "--density", "1000", "--seed", "3", "--groups-skeleton"});
  EXPECT_EQ(ok.options.collision.density, 1000u);
  EXPECT_EQ(ok.options.collision.seed, 3u);
  EXPECT_TRUE(ok.options.groups_skeleton);
  EXPECT_EQ(ok.srdf_in_path, "c");

  SetupAssistantCommand missing = ok;
  missing.urdf_path = kDataDir + "/no_such.urdf";
  EXPECT_NE(message([&] { runSetupAssistantOnFiles(missing); }).find("no_such.urdf"), std::string::npos);
}

TEST(SetupAssistant, RunsOnFilesAndWritesTheSrdf) {
  SetupAssistantCommand command;
  command.urdf_path = kUrUrdf;
  command.srdf_in_path = kUrSrdf;
  command.srdf_out_path = testing::TempDir() + "/setup_assistant_ur_like.srdf";
  command.options.collision.density = 500;
  const auto result = runSetupAssistantOnFiles(command);
  EXPECT_EQ(readTextFile(command.srdf_out_path), result.srdf);
  std::remove(command.srdf_out_path.c_str());
  command.srdf_out_path = kDataDir + "/no_such_dir/out.srdf";
  EXPECT_THROW(runSetupAssistantOnFiles(command), RobotModelError);
}

TEST(SetupAssistant, ProgressIsReportedWhileSamplingAndAtTheEnd) {
  CollisionMatrixOptions collision;
  collision.density = 400;
  std::vector<std::pair<std::size_t, std::size_t>> calls;
  collision.progress = [&calls](std::size_t done, std::size_t total) { calls.emplace_back(done, total); };
  computeDisabledCollisions(armModel(), collision);
  ASSERT_GE(calls.size(), 2u);
  EXPECT_EQ(calls.back(), std::make_pair(std::size_t{400}, std::size_t{400}));
  for (size_t i = 1; i < calls.size(); ++i) EXPECT_GT(calls[i].first, calls[i - 1].first);
}

TEST(SetupAssistant, DescribesTheModelWithTheSolverThatFitsEachChain) {
  const auto arm = armModel();
  const std::string description = describeModel(*arm);
  EXPECT_NE(description.find("robot: \"sixdof\""), std::string::npos);
  EXPECT_NE(description.find("root_link: \"base_link\""), std::string::npos);
  EXPECT_NE(description.find("mimic: {joint: \"finger1_joint\", multiplier: 1, offset: 0}"), std::string::npos);
  EXPECT_NE(description.find("  solver: analytic\n"), std::string::npos);  // the arm: 6R, spherical wrist
  EXPECT_NE(description.find("  solver: none\n"), std::string::npos);      // the gripper: not a chain
  EXPECT_EQ(description.find("collisions:"), std::string::npos);
  // Joint origins and link shapes (collision, else visual), for the front end's suction-cup inference.
  EXPECT_NE(description.find("  rpy: [0, 1.5707963"), std::string::npos) << description;
  EXPECT_NE(description.find("{name: \"link6\", parent_joint: \"joint6\", geometry: true, shapes: [{type: mesh, xyz: "
                             "[0, 0, 0], rpy: [0, 0, 0]}]}"),
            std::string::npos)
      << description;

  // The same 6R arm with the wrist moved off the forearm's axis has no closed form: numeric, and why.
  std::string urdf = readTextFile(armUrdf());
  const std::string joint5 = "<joint name=\"joint5\" type=\"revolute\">";
  const size_t at = urdf.find("<origin", urdf.find(joint5));
  urdf.replace(at, urdf.find("/>", at) + 2 - at, "<origin xyz=\"0.18 0.03 0\" rpy=\"0 0 0\"/>");
  const RobotModel offset(urdf, readTextFile(armSrdf()), armResolver());
  const std::string numeric = describeModel(offset);
  EXPECT_NE(numeric.find("  solver: numeric\n  solver_reason: \"no closed form: "), std::string::npos) << numeric;

  DisabledCollisions collisions;
  collisions.link_pairs = 3;
  EXPECT_NE(describeModel(*arm, &collisions).find("collisions: {link_pairs: 3,"), std::string::npos);
}

TEST(SetupAssistant, DescribeOnlyNeedsNoSrdfOut) {
  const auto command = parseSetupAssistantArguments({"--urdf", "a", "--describe", "d.yaml"});
  EXPECT_EQ(command.describe_path, "d.yaml");
  EXPECT_TRUE(command.srdf_out_path.empty());
  SetupAssistantCommand run;
  run.urdf_path = kUrUrdf;
  run.describe_path = testing::TempDir() + "/setup_assistant_describe.yaml";
  runSetupAssistantOnFiles(run);
  EXPECT_NE(readTextFile(run.describe_path).find("robot: \"ur_like\""), std::string::npos);
  std::remove(run.describe_path.c_str());
}
