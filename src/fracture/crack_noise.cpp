#include "fissure/fracture/crack_noise.hpp"

#include "fissure/base/rng.hpp"

#include <cmath>

namespace fissure {
namespace {

// The permutation of 0..255, shuffled once by Fissure's own generator (so the same on every
// platform), doubled to avoid index wrapping.
struct Permutation {
  std::array<std::uint8_t, 512> p{};
  Permutation() {
    std::array<std::uint8_t, 256> base{};
    for (int i = 0; i < 256; ++i) base[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(i);
    Rng rng(0x5eed'c0de'f155'0e5dULL);
    for (int i = 255; i > 0; --i) {
      const auto j = static_cast<std::size_t>(rng.uniform_index(static_cast<std::uint64_t>(i) + 1));
      std::swap(base[static_cast<std::size_t>(i)], base[j]);
    }
    for (std::size_t i = 0; i < 512; ++i) p[i] = base[i & 255];
  }
};

const Permutation& permutation() {
  static const Permutation perm;
  return perm;
}

// The 12 gradient directions: midpoints of a cube's edges.
constexpr int kGrad[12][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1},
                              {1, 0, -1}, {-1, 0, -1}, {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};

double corner(int gi, double x, double y, double z) {
  double t = 0.6 - x * x - y * y - z * z;
  if (t < 0.0) return 0.0;
  t *= t;
  return t * t * (kGrad[gi][0] * x + kGrad[gi][1] * y + kGrad[gi][2] * z);
}

}  // namespace

double simplex_noise(const Eigen::Vector3d& pos) {
  const auto& perm = permutation().p;
  constexpr double F3 = 1.0 / 3.0, G3 = 1.0 / 6.0;
  const double s = (pos.x() + pos.y() + pos.z()) * F3;
  const double fi = std::floor(pos.x() + s), fj = std::floor(pos.y() + s), fk = std::floor(pos.z() + s);
  const double t = (fi + fj + fk) * G3;
  const double x0 = pos.x() - (fi - t), y0 = pos.y() - (fj - t), z0 = pos.z() - (fk - t);
  // Which of the six simplices of the skewed cube holds the point.
  int i1, j1, k1, i2, j2, k2;
  if (x0 >= y0) {
    if (y0 >= z0) { i1 = 1; j1 = 0; k1 = 0; i2 = 1; j2 = 1; k2 = 0; }
    else if (x0 >= z0) { i1 = 1; j1 = 0; k1 = 0; i2 = 1; j2 = 0; k2 = 1; }
    else { i1 = 0; j1 = 0; k1 = 1; i2 = 1; j2 = 0; k2 = 1; }
  } else {
    if (y0 < z0) { i1 = 0; j1 = 0; k1 = 1; i2 = 0; j2 = 1; k2 = 1; }
    else if (x0 < z0) { i1 = 0; j1 = 1; k1 = 0; i2 = 0; j2 = 1; k2 = 1; }
    else { i1 = 0; j1 = 1; k1 = 0; i2 = 1; j2 = 1; k2 = 0; }
  }
  const double x1 = x0 - i1 + G3, y1 = y0 - j1 + G3, z1 = z0 - k1 + G3;
  const double x2 = x0 - i2 + 2.0 * G3, y2 = y0 - j2 + 2.0 * G3, z2 = z0 - k2 + 2.0 * G3;
  const double x3 = x0 - 1.0 + 3.0 * G3, y3 = y0 - 1.0 + 3.0 * G3, z3 = z0 - 1.0 + 3.0 * G3;
  // Lattice coordinates modulo 256 (floor of a huge or negative coordinate wraps correctly).
  const int ii = static_cast<int>(fi - 256.0 * std::floor(fi / 256.0));
  const int jj = static_cast<int>(fj - 256.0 * std::floor(fj / 256.0));
  const int kk = static_cast<int>(fk - 256.0 * std::floor(fk / 256.0));
  auto grad_index = [&](int a, int b, int c) { return perm[static_cast<std::size_t>(ii + a + perm[static_cast<std::size_t>(jj + b + perm[static_cast<std::size_t>(kk + c)])])] % 12; };
  const double n = corner(grad_index(0, 0, 0), x0, y0, z0) + corner(grad_index(i1, j1, k1), x1, y1, z1) +
                   corner(grad_index(i2, j2, k2), x2, y2, z2) + corner(grad_index(1, 1, 1), x3, y3, z3);
  // 32 scales the sum to about [−1, 1] (Gustavson); clamp the last ulps.
  return std::fmax(-1.0, std::fmin(1.0, 32.0 * n));
}

CrackSurfaceFunction::CrackSurfaceFunction(const Eigen::Vector3d& origin, const Eigen::Vector3d& normal,
                                           const std::array<NoiseOctave, 4>& octaves, std::uint64_t noise_seed)
    : m_origin(origin), m_normal(normal.normalized()) {
  Rng rng(noise_seed);
  for (const NoiseOctave& o : octaves) {
    // Offsets are drawn for every octave, used or not, so turning one octave off does not move
    // the others.
    const Eigen::Vector3d shift(rng.uniform(0.0, 256.0), rng.uniform(0.0, 256.0), rng.uniform(0.0, 256.0));
    if (o.amplitude == 0.0 || o.frequency == 0.0) continue;
    m_octaves[static_cast<std::size_t>(m_octave_count)] = o;
    m_shift[static_cast<std::size_t>(m_octave_count)] = shift;
    ++m_octave_count;
  }
}

double CrackSurfaceFunction::operator()(const Eigen::Vector3d& x) const {
  double s = m_normal.dot(x - m_origin) - m_offset;
  for (int i = 0; i < m_octave_count; ++i) {
    const auto& o = m_octaves[static_cast<std::size_t>(i)];
    s += o.amplitude * simplex_noise(o.frequency * x + m_shift[static_cast<std::size_t>(i)]);
  }
  return s;
}

}  // namespace fissure
