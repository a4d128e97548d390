#include "lang2manip/model/scene.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lang2manip/core/rotation.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "model_test_support.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;
using test::errorMessage;

SceneObject boxObject(const std::string& name, const Vector3& size, const Vector3& position) {
  SceneObject object;
  object.name = name;
  object.kind = "box";
  object.collisions.push_back(Shape{Box{size}, Pose::Identity(), std::nullopt, ""});
  object.pose = makePose(position, Quaternion::Identity());
  return object;
}

class SceneTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scene.addRobot(SceneRobot{"arm", readUrdfString(test::twoJointUrdf(), "arm.urdf", "."),
                              Pose::Identity(), VectorX::Zero(2), {}});
    scene.addObject(boxObject("crate", Vector3(0.2, 0.4, 0.6), Vector3(1, 0, 0)));
  }
  Scene scene;
};

TEST_F(SceneTest, ComputesDimensionsAndWorldBounds) {
  const SceneObject& crate = scene.object("crate");
  EXPECT_TRUE(crate.dimensions().isApprox(Vector3(0.2, 0.4, 0.6)));
  SceneObject turned = crate;
  turned.pose = makePose(Vector3::Zero(), Quaternion(Eigen::AngleAxisd(std::numbers::pi / 2, Vector3::UnitZ())));
  EXPECT_TRUE(turned.worldBounds().sizes().isApprox(Vector3(0.4, 0.2, 0.6), 1e-12));
}

TEST_F(SceneTest, RejectsDuplicatesUnknownNamesAndBadConfigurations) {
  EXPECT_THAT(errorMessage([&] { scene.addObject(boxObject("arm", Vector3::Ones(), Vector3::Zero())); }),
              HasSubstr("already has an entity named \"arm\""));
  EXPECT_THAT(errorMessage([&] { static_cast<void>(scene.object("cup")); }),
              HasSubstr("no object \"cup\"; its objects are: crate"));
  EXPECT_THAT(errorMessage([&] { scene.setConfiguration("arm", VectorX::Zero(5)); }),
              HasSubstr("has 5 values"));
  SceneObject nanPose = boxObject("nan", Vector3::Ones(), Vector3(std::nan(""), 0, 0));
  EXPECT_THAT(errorMessage([&] { scene.addObject(nanPose); }), HasSubstr("non-finite pose"));
}

TEST_F(SceneTest, AttachesAndDetachesObjects) {
  scene.attach(Attachment{"crate", "arm", "tip", Pose::Identity()});
  ASSERT_NE(scene.findAttachment("crate"), nullptr);
  EXPECT_THAT(errorMessage([&] { scene.attach(Attachment{"crate", "arm", "tip", Pose::Identity()}); }),
              HasSubstr("already attached"));
  EXPECT_THAT(errorMessage([&] { scene.attach(Attachment{"crate", "arm", "claw", Pose::Identity()}); }),
              HasSubstr("no link \"claw\""));
  const Pose dropped = makePose(Vector3(0, 2, 0), Quaternion::Identity());
  scene.detach("crate", dropped);
  EXPECT_EQ(scene.findAttachment("crate"), nullptr);
  EXPECT_TRUE(scene.object("crate").pose.isApprox(dropped));
  EXPECT_THAT(errorMessage([&] { scene.detach("crate", dropped); }), HasSubstr("is not attached"));
}

TEST_F(SceneTest, RemovingAnObjectRemovesItsAttachment) {
  scene.attach(Attachment{"crate", "arm", "tip", Pose::Identity()});
  scene.removeObject("crate");
  EXPECT_TRUE(scene.objects().empty());
  EXPECT_TRUE(scene.attachments().empty());
  EXPECT_THAT(errorMessage([&] { scene.removeObject("crate"); }), HasSubstr("no object \"crate\""));
}

TEST(ObjectRoleTest, NamesRoundTripAndUnknownNamesAreListed) {
  EXPECT_EQ(objectRoleFromName(objectRoleName(ObjectRole::kContainer)), ObjectRole::kContainer);
  EXPECT_THAT(errorMessage([] { objectRoleFromName("shelf"); }),
              HasSubstr("valid roles: none, support, container"));
}

}  // namespace
}  // namespace lang2manip
