#pragma once
/// The bumps of a crack surface (paper §5.3): 3-D simplex noise [Per02] summed over four octaves,
/// S_k(x) = n̂·(x − c) + Σ_i A_i·simplex(f_i x + o_{k,i}) − m_k, where each crack k has its own
/// octave offsets o_{k,i} (drawn from its noise seed) and m_k makes the surface pass through the
/// opening element (see CrackSurfaceFunction). The noise stands in for micro-branching.
#include "fissure/fracture/fracture_params.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>

namespace fissure {

/// Gustavson's 3-D simplex noise with a fixed permutation (the same numbers on every platform):
/// smooth (C¹), zero at lattice points, |value| ≤ 1, period 256 in each axis.
double simplex_noise(const Eigen::Vector3d& p);

/// The implicit surface of one crack. Cheap to copy; evaluation is a few hundred nanoseconds with
/// four octaves, zero octaves cost nothing.
class CrackSurfaceFunction {
public:
  CrackSurfaceFunction() = default;
  /// A noisy plane through `origin` with unit `normal`; `noise_seed` draws the octave offsets.
  CrackSurfaceFunction(const Eigen::Vector3d& origin, const Eigen::Vector3d& normal,
                       const std::array<NoiseOctave, 4>& octaves, std::uint64_t noise_seed);
  /// S(x), m: signed distance to the plane plus the noise.
  double operator()(const Eigen::Vector3d& x) const;
  /// The bumps alone: S(x) minus its plane part (up to the constant of subtract), so a crack whose
  /// normal turns as it runs keeps the same noise (simulation.cpp, crack paths).
  double noise(const Eigen::Vector3d& x) const { return (*this)(x) - m_normal.dot(x - m_origin); }
  /// Shifts S by a constant (S ← S − offset), to make its P1 interpolant vanish where wanted.
  void subtract(double offset) { m_offset += offset; }
  const Eigen::Vector3d& normal() const { return m_normal; }
  const Eigen::Vector3d& origin() const { return m_origin; }

private:
  Eigen::Vector3d m_origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d m_normal = Eigen::Vector3d::UnitX();
  std::array<NoiseOctave, 4> m_octaves{};
  std::array<Eigen::Vector3d, 4> m_shift{};
  int m_octave_count = 0;
  double m_offset = 0.0;
};

}  // namespace fissure
