#include "lang2manip/kinematics/kdl_chain.hpp"

#include "lang2manip/core/error.hpp"

namespace lang2manip {
namespace {

KDL::Joint toKdlJoint(const RobotModel& model, const ChainJoint& joint) {
  const std::string& name = model.joints()[static_cast<std::size_t>(joint.joint)].name;
  const KDL::Vector axis(joint.axis.x(), joint.axis.y(), joint.axis.z());
  const auto type = joint.type == JointType::kPrismatic ? KDL::Joint::TransAxis
                                                        : KDL::Joint::RotAxis;
  return KDL::Joint(name, KDL::Vector::Zero(), axis, type);
}

}  // namespace

KDL::Frame toKdlFrame(const Pose& pose) {
  const Matrix3& r = pose.linear();
  const Vector3& p = pose.translation();
  return KDL::Frame(KDL::Rotation(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0),
                                  r(2, 1), r(2, 2)),
                    KDL::Vector(p.x(), p.y(), p.z()));
}

Pose fromKdlFrame(const KDL::Frame& frame) {
  Pose pose = Pose::Identity();
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) pose.linear()(row, col) = frame.M(row, col);
    pose.translation()[row] = frame.p(row);
  }
  return pose;
}

KDL::Chain makeKdlChain(const RobotModel& model, const KinematicChain& chain) {
  if (chain.hasCoupledJoints()) {
    throw InputError("the chain " + chain.baseLink() + " -> " + chain.tipLink() +
                     " has mimic or coupled joints, which KDL's chain solvers cannot represent");
  }
  KDL::Chain result;
  // The fixed transforms since the last movable joint, and that joint (none yet).
  Pose pending = Pose::Identity();
  const ChainJoint* moving = nullptr;
  auto flush = [&](const std::string& name) {
    if (moving == nullptr) {
      result.addSegment(KDL::Segment(name, KDL::Joint(KDL::Joint::Fixed), toKdlFrame(pending)));
    } else {
      result.addSegment(KDL::Segment(name, toKdlJoint(model, *moving), toKdlFrame(pending)));
    }
    pending.setIdentity();
  };
  for (const ChainJoint& joint : chain.joints()) {
    const std::string& link =
        model.links()[static_cast<std::size_t>(model.parentLinkOf(joint.joint))].name;
    pending = pending * joint.origin;
    if (joint.variable >= 0) {
      flush(link);
      moving = &joint;
    }
  }
  flush(chain.tipLink());
  return result;
}

KDL::Chain makeKdlChain(const RobotModel& model, const std::string& baseLink,
                        const std::string& tipLink) {
  return makeKdlChain(model, KinematicChain(model, baseLink, tipLink));
}

}  // namespace lang2manip
