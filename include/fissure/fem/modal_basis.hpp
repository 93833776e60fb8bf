#pragma once
/// The modal basis of paper §5.1: the lowest eigenpairs of K φ = λ M φ, mass-normalised, computed
/// once per body and reused for every load (Eq. 1 "solved directly" in modal coordinates).
/// A block shift-invert Krylov–Schur iteration runs over a CHOLMOD factorisation of K − σM, with
/// blocks of right-hand sides solved together.

#include "fissure/base/content_hash.hpp"
#include "fissure/base/progress.hpp"
#include "fissure/fem/elastic_body.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace fissure {

/// Arithmetic of the modal static solve. The solve only streams Φ, so it is memory-bound: Single
/// reads a float copy of Φ (half the bytes, ≈ 2× faster) and adds a relative error of ≈ 1e-6 in
/// displacement, four orders below the truncation error of any practical m (BENCHMARKS.md).
enum class ModalPrecision { Double, Single };

struct ModalOptions {
  int mode_count = 50;                ///< flexible modes wanted (rigid modes come on top)
  MassKind mass = MassKind::Lumped;
  /// Relative residual of each Ritz pair of the shift-inverted operator T = (K − σM)⁻¹M:
  /// ‖T φ − μ φ‖_M ≤ tolerance · μ (the criterion Spectra's Lanczos used).
  double tolerance = 1e-10;
  int max_iterations = 1000;          ///< restarts of the block iteration
  /// Krylov basis size; 0 picks nev + min(2·nev, 160) (at least nev + 3 blocks), capped by the
  /// free dimension.
  int krylov_size = 0;
  /// Refuse (InvalidInput, before any factorisation) when modal_memory_estimate() exceeds this;
  /// 0 = the machine's physical memory, UINT64_MAX = no limit. Not part of the cache key.
  std::uint64_t memory_limit_bytes = 0;

  std::vector<std::string> problems() const;
  void validate() const;
};

class ModalBasis {
public:
  /// Format version of save()/load() files and of the cache key (2: files end in a checksum).
  static constexpr int kFormatVersion = 2;

  ModalBasis() = default;

  /// Lowest `options.mode_count` flexible modes of `body` with the dofs `fixed_dofs` held at zero.
  /// Supported body: shift 0 (K_ff is positive definite). Free body (no fixed dofs): the 6 rigid
  /// motions per component are the exact ones, M-orthonormalised, and deflated from the block
  /// iteration, which runs with a shift −0.01·λ_R (λ_R a Rayleigh–Ritz upper bound of the first
  /// flexible eigenvalue from quadratic trial fields; fem-pitfalls.md §2.7 shows −1e-3…−1e-1·λ₇
  /// is safe). That the
  /// rigid motions carry no energy (rᵀKr ≤ 1e-6·λ₇) is checked, so a further zero mode is
  /// reported rather than hidden. Throws InvalidInput for bad options, a fixed dof outside the
  /// mesh, a mechanism, or a request whose memory estimate exceeds options.memory_limit_bytes
  /// (checked before any factorisation); NumericalFailure when the iteration does not converge or
  /// the spectrum is not what a free body must have; Cancelled when `cancel` fires — checked at
  /// every block of triangular solves and every restart, so within milliseconds. `progress` hears
  /// stage "modal analysis" at most every 0.2 s during the iteration (the fraction is an
  /// estimate: the number of restarts is not known in advance). Cost: a factorisation plus
  /// O(m) multi-right-hand-side solves and O(#dofs · m²) Gram–Schmidt; tenths of a second for
  /// 50 modes at 24K tets, seconds for hundreds (figures in docs/BENCHMARKS.md).
  static ModalBasis compute(std::shared_ptr<const ElasticBody> body, const std::vector<int>& fixed_dofs,
                            const ModalOptions& options, ProgressSink* progress = nullptr,
                            const CancelToken* cancel = nullptr);

  /// Flexible eigenvalues λ (rad²/s²), ascending.
  const Eigen::VectorXd& eigenvalues() const { return m_eigenvalues; }
  /// Flexible modes, 3·#nodes × m, columns M-orthonormal (φᵢᵀ M φⱼ = δᵢⱼ), zero on fixed dofs.
  const Eigen::MatrixXd& modes() const { return m_modes; }
  /// Free body: the exact rigid motions, M-orthonormal, 3·#nodes × 6·#components. Else empty.
  const Eigen::MatrixXd& rigid_modes() const { return m_rigid_modes; }
  /// Free body: the rigid modes' eigenvalues rᵀKr (≈ 0 to round-off; reported so users see the
  /// six near-zero modes per component).
  const Eigen::VectorXd& rigid_eigenvalues() const { return m_rigid_eigenvalues; }
  /// Natural frequencies √λ / 2π of the flexible modes, Hz.
  Eigen::VectorXd frequencies_hz() const;
  int mode_count() const { return static_cast<int>(m_eigenvalues.size()); }
  bool free_body() const { return m_rigid_modes.cols() > 0; }
  MassKind mass() const { return m_mass; }

  /// Modal static solve u = Σᵢ φᵢ (φᵢᵀ f) / λᵢ over the flexible modes (f: 3·#nodes, N). For a free
  /// body this is the inertia-relief solution truncated to m modes. O(#dofs · m). Φᵀf is always
  /// accumulated in double; `precision` picks the arithmetic of the expansion Φq. Throws
  /// InvalidInput for a wrong size or a non-finite f. Thread-safe, in both precisions (the float
  /// copy of Φ is made once under std::call_once).
  Eigen::VectorXd static_displacement(const Eigen::VectorXd& f,
                                      ModalPrecision precision = ModalPrecision::Double) const;

  /// The cache key: a hash of mesh, material, fixed dofs, options and the format version.
  static Hash128 cache_key(const ElasticBody& body, const std::vector<int>& fixed_dofs,
                           const ModalOptions& options);

  /// Binary file with the key; written atomically. IoError on failure.
  void save(const std::filesystem::path& path, const Hash128& key) const;
  /// Reads a file written by save(). Throws IoError when it is missing, truncated, of another
  /// format version, or its key differs from `expected_key`.
  static ModalBasis load(const std::filesystem::path& path, const Hash128& expected_key);

private:
  Eigen::VectorXd m_eigenvalues;
  Eigen::MatrixXd m_modes;
  /// Float copy of m_modes for ModalPrecision::Single, made on its first use (a basis only ever
  /// solved in double, as by the CLI, never pays its memory). Shared by copies of the basis,
  /// whose modes are the same.
  struct SingleCopy {
    std::once_flag made;
    Eigen::MatrixXf modes;
  };
  std::shared_ptr<SingleCopy> m_single = std::make_shared<SingleCopy>();
  Eigen::MatrixXd m_rigid_modes;
  Eigen::VectorXd m_rigid_eigenvalues;
  MassKind m_mass = MassKind::Lumped;
};

/// Bytes a modal analysis needs at its peak, estimated from the free dofs, the modes, the Krylov
/// size and nnz(K_ff): Φ (twice), the Krylov basis with a restart copy, the dense ncv² matrices of
/// Rayleigh–Ritz and the factor.
double modal_memory_estimate(Eigen::Index dofs, Eigen::Index modes, Eigen::Index krylov_size,
                             Eigen::Index stiffness_nonzeros);

/// The basis for (body, fixed dofs, options): loaded from `cache_dir` when a file with the same
/// content key exists and reads back cleanly (checksum included), else computed and saved there.
/// A cache that cannot be written is not an error, but when `cache_warning` is given it receives
/// one line saying so ("modal basis not cached (cannot create /x: Permission denied); it will be
/// computed again next time"), and is cleared otherwise, for the caller to show once. `loaded`
/// tells whether the basis came from the cache.
ModalBasis cached_modal_basis(std::shared_ptr<const ElasticBody> body, const std::vector<int>& fixed_dofs,
                              const ModalOptions& options, const std::filesystem::path& cache_dir,
                              bool* loaded = nullptr, ProgressSink* progress = nullptr,
                              const CancelToken* cancel = nullptr, std::string* cache_warning = nullptr);

}  // namespace fissure
