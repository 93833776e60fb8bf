#pragma once
/// Element stresses of linear tetrahedra (constant per tet) and their principal values.
/// Voigt order everywhere: (xx, yy, zz, yz, xz, xy), pascals, tensile positive.
///
/// Every function that turns displacements into stress takes the ElasticBody, which owns the
/// mesh, its gradients and the material together: gradients of one mesh cannot be paired with
/// another mesh or material (they once could, and gave garbage without an error).

#include "fissure/fem/elastic_body.hpp"

#include <Eigen/Core>

namespace fissure {

/// One row per tet, 6 Voigt columns; column-major, so each component is a contiguous array.
using StressField = Eigen::Matrix<double, Eigen::Dynamic, 6>;

/// Cauchy stress σ = D ε(u) of every tet of `body` for nodal displacements `u` (3·#nodes, m).
/// Throws InvalidInput when `u` has the wrong length or a non-finite entry (naming the node).
/// O(#tets). Thread-safe.
StressField compute_stress(const ElasticBody& body, const Eigen::VectorXd& u);

/// Principal stresses in descending order and the matching unit directions (columns), from
/// Eigen's self-adjoint solver (accurate to round-off; ≈ 200 ns per tet). The reference the fast
/// kernels are tested against.
struct PrincipalStresses {
  Eigen::Vector3d values;
  Eigen::Matrix3d directions;
};
PrincipalStresses principal_stresses(const Eigen::Matrix<double, 6, 1>& voigt);

/// The largest principal stress of a tensor and its unit direction, by the closed forms of the
/// fused kernels below (the same arithmetic, one tensor at a time).
///
/// Value: trigonometric solution of the characteristic cubic with a vectorisable polynomial
/// arccos and two Newton steps, on the tensor scaled by its largest component (so neither 1e300 Pa
/// nor 1e-300 Pa over- or underflows). Agrees with principal_stresses().values[0] to 1e-13·‖σ‖
/// (tested), except when the two largest eigenvalues nearly coincide: the cubic's root is then
/// ill-conditioned and the error is bounded by min(gap, √ε·‖σ‖) — inherent to any closed form.
///
/// Direction: the best-conditioned cross product of two rows of σ − λI (a column of its
/// adjugate), normalised, its largest component made positive (a direction is an axis: ±v are
/// the same; the sign rule makes the output deterministic). Guarantees, with g = λ₁ − λ₂ the gap
/// to the second eigenvalue (tested against Eigen):
///  - always a unit vector (to 1e-15) with residual ‖σv − λv‖ ≤ 1e-7·‖σ‖ whatever the gap (v is
///    an eigenvector of λ to within the accuracy of λ itself; ≤ 1e-13·‖σ‖ for a simple λ);
///  - for g ≥ 1e-6·‖σ‖, an angle to the true eigenvector ≤ 2e-13·‖σ‖/g: round-off times the
///    eigenvector's own condition number ‖σ‖/g, which no method avoids;
///  - for a (near-)repeated largest eigenvalue (g ≲ √ε·‖σ‖) the direction is not defined: v is
///    then a unit vector of the (near-)eigenspace of λ₁ and λ₂ (its component along the third
///    eigenvector is ≤ residual/(λ₁ − λ₃)), chosen deterministically; for an isotropic tensor it
///    is (1, 0, 0).
struct MaxPrincipal {
  double value = 0.0;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
};
MaxPrincipal max_principal_with_direction(const Eigen::Matrix<double, 6, 1>& voigt);
double max_principal_stress(const Eigen::Matrix<double, 6, 1>& voigt);

/// The stress state the fracture stage reads, per tet: stress, its largest principal value and
/// that value's unit direction (see max_principal_with_direction for the guarantees).
struct PrincipalStressField {
  StressField stress;               ///< #tets × 6, Pa
  Eigen::VectorXd max_principal;    ///< λ_max per tet, Pa
  Eigen::MatrixX3d max_direction;   ///< unit direction of λ_max, row t; column-major
};

/// The fused kernel of the stress map: stress, λ_max and its direction of every tet of `body`
/// in one vectorised pass over structure-of-arrays data (a fraction of a millisecond per 20K
/// tets on one core, ~30× faster than Eigen's solver per element: bench_fem in
/// docs/BENCHMARKS.md). `out` is resized (its memory is reused across calls of the same size).
/// Throws InvalidInput as compute_stress, NumericalFailure when a stress overflows double
/// precision (naming the tet). Thread-safe.
void compute_principal_stress(const ElasticBody& body, const Eigen::VectorXd& u, PrincipalStressField& out);

/// The same without directions (stress and λ_max only), ≈ 20 % cheaper.
void compute_stress_and_max_principal(const ElasticBody& body, const Eigen::VectorXd& u, StressField& stress,
                                      Eigen::VectorXd& max_principal);

/// λ_max and, when `directions` is given, its direction for every row of an existing stress field
/// (a recovered one, say), by the same vectorised closed forms. NumericalFailure for a
/// non-finite row (naming the tet). Thread-safe.
void max_principal_of(const StressField& stress, Eigen::VectorXd& max_principal, Eigen::MatrixX3d* directions = nullptr);

/// Voigt row → symmetric 3×3 tensor, and back.
Eigen::Matrix3d voigt_to_tensor(const Eigen::Matrix<double, 6, 1>& voigt);
Eigen::Matrix<double, 6, 1> tensor_to_voigt(const Eigen::Matrix3d& tensor);

/// Row-major 3×3 tensors (9 columns: xx xy xz yx yy yz zx zy zz) from Voigt rows, the layout of
/// gmsh tensor views.
Eigen::MatrixXd voigt_rows_to_tensor_rows(const StressField& voigt);

}  // namespace fissure
