#pragma once
// The viewport's camera with Blender's habits: it orbits a target point (middle drag), pans the
// target in the view plane (Shift + middle drag), zooms towards it (wheel), and frames a box
// (Home: everything; numpad '.': the selection) so the box fills the view.
// Plain Eigen, so its arithmetic is tested without a window.
#include <Eigen/Core>

namespace fissure::studio {

class OrbitCamera {
 public:
  /// `up`: the scene's up axis (unit, a coordinate axis: +Y for glTF, +Z for PLY).
  explicit OrbitCamera(const Eigen::Vector3d& up = Eigen::Vector3d::UnitY());

  void set_up(const Eigen::Vector3d& up);
  /// Turns about the target: `yaw` about up, `pitch` about the view's right axis (radians).
  /// Pitch stops short of the poles so the view never flips.
  void orbit(double yaw, double pitch);
  /// Moves the target by a drag of (dx, dy) pixels in a viewport `height` pixels tall, so the
  /// point under the cursor stays under it.
  void pan(double dx, double dy, double height);
  /// Each step brings the eye 1/1.2 closer (negative steps move away).
  void zoom(double steps);
  /// Looks at the box [lo, hi] from the current direction, at the distance where its bounding
  /// sphere fills the smaller field of view.
  void frame(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double aspect);

  Eigen::Vector3d eye() const;
  const Eigen::Vector3d& target() const { return m_target; }
  double distance() const { return m_distance; }
  /// The unit direction from the eye to the target.
  Eigen::Vector3d forward() const;
  Eigen::Matrix4f view() const;
  Eigen::Matrix4f projection(double aspect) const;
  /// The world ray through a pixel: origin (the eye) and unit direction. (x, y) in pixels from
  /// the top left of a width × height viewport.
  void ray(double x, double y, double width, double height, Eigen::Vector3d& origin, Eigen::Vector3d& direction) const;

  static constexpr double kFieldOfView = 0.7;  ///< vertical, radians (40°, Blender's 50 mm)

 private:
  Eigen::Vector3d m_up, m_reference;  // up, and a horizontal axis for yaw = 0
  Eigen::Vector3d m_target = Eigen::Vector3d::Zero();
  double m_distance = 5.0;
  double m_yaw = 0.6, m_pitch = 0.45;
};

}  // namespace fissure::studio
