#include "orbit_camera.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace fissure::studio {

OrbitCamera::OrbitCamera(const Eigen::Vector3d& up) { set_up(up); }

void OrbitCamera::set_up(const Eigen::Vector3d& up) {
  m_up = up.normalized();
  // Any axis orthogonal to up serves as yaw 0; the least aligned coordinate axis keeps it exact.
  Eigen::Index least = 0;
  m_up.cwiseAbs().minCoeff(&least);
  m_reference = (Eigen::Vector3d::Unit(least) - m_up * m_up(least)).normalized();
}

Eigen::Vector3d OrbitCamera::forward() const {
  const Eigen::Vector3d side = m_up.cross(m_reference);
  const Eigen::Vector3d horizontal = std::cos(m_yaw) * m_reference + std::sin(m_yaw) * side;
  // The eye sits above the target for positive pitch, so it looks down.
  return -(std::cos(m_pitch) * horizontal + std::sin(m_pitch) * m_up).normalized();
}

Eigen::Vector3d OrbitCamera::eye() const { return m_target - m_distance * forward(); }

void OrbitCamera::orbit(double yaw, double pitch) {
  m_yaw = std::remainder(m_yaw + yaw, 2.0 * M_PI);
  const double limit = 0.5 * M_PI - 1e-3;
  m_pitch = std::clamp(m_pitch + pitch, -limit, limit);
}

void OrbitCamera::pan(double dx, double dy, double height) {
  if (height <= 0.0) return;
  const Eigen::Vector3d f = forward();
  const Eigen::Vector3d right = f.cross(m_up).normalized();
  const Eigen::Vector3d up = right.cross(f);
  // World units per pixel at the target's depth.
  const double scale = 2.0 * m_distance * std::tan(0.5 * kFieldOfView) / height;
  m_target += scale * (-dx * right + dy * up);
}

void OrbitCamera::zoom(double steps) {
  m_distance = std::clamp(m_distance * std::pow(1.2, -steps), 1e-4, 1e6);
}

void OrbitCamera::frame(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double aspect) {
  if (!(lo.array() <= hi.array()).all()) return;
  m_target = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * (hi - lo).norm(), 1e-3);
  const double half = 0.5 * kFieldOfView;
  const double horizontal = std::atan(std::tan(half) * std::max(aspect, 1e-3));
  m_distance = 1.1 * radius / std::sin(std::min(half, horizontal));
}

Eigen::Matrix4f OrbitCamera::view() const {
  const Eigen::Vector3d f = forward();
  const Eigen::Vector3d s = f.cross(m_up).normalized();
  const Eigen::Vector3d u = s.cross(f);
  const Eigen::Vector3d e = eye();
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(e);
  m(1, 3) = -u.dot(e);
  m(2, 3) = f.dot(e);
  return m.cast<float>();
}

Eigen::Matrix4f OrbitCamera::projection(double aspect) const {
  // Near and far follow the distance, so a 1 cm tile and a 100 m street both keep depth precision.
  const double near = m_distance * 1e-3, far = m_distance * 1e3;
  const double f = 1.0 / std::tan(0.5 * kFieldOfView);
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = f / std::max(aspect, 1e-6);
  p(1, 1) = f;
  p(2, 2) = (far + near) / (near - far);
  p(2, 3) = 2.0 * far * near / (near - far);
  p(3, 2) = -1.0;
  return p.cast<float>();
}

void OrbitCamera::ray(double x, double y, double width, double height, Eigen::Vector3d& origin,
                      Eigen::Vector3d& direction) const {
  const Eigen::Vector3d f = forward();
  const Eigen::Vector3d right = f.cross(m_up).normalized();
  const Eigen::Vector3d up = right.cross(f);
  const double t = std::tan(0.5 * kFieldOfView);
  const double aspect = height > 0.0 ? width / height : 1.0;
  const double nx = (2.0 * (x + 0.5) / std::max(width, 1.0) - 1.0) * t * aspect;
  const double ny = (1.0 - 2.0 * (y + 0.5) / std::max(height, 1.0)) * t;
  origin = eye();
  direction = (f + nx * right + ny * up).normalized();
}

}  // namespace fissure::studio
