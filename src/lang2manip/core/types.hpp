#pragma once
/// @file Math types shared by every module (Eigen, double precision).

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lang2manip {

using Vector3 = Eigen::Vector3d;
using Vector4 = Eigen::Vector4d;
using VectorX = Eigen::VectorXd;
using Matrix3 = Eigen::Matrix3d;
using MatrixX = Eigen::MatrixXd;
using Quaternion = Eigen::Quaterniond;
/// A rigid transform. Named by frames: X_WB is the pose of frame B in frame W.
using Pose = Eigen::Isometry3d;
using AlignedBox3 = Eigen::AlignedBox3d;

}  // namespace lang2manip
