#pragma once
/// Element stresses of linear tetrahedra (constant per tet) and their principal values.
/// Voigt order everywhere: (xx, yy, zz, yz, xz, xy), pascals, tensile positive.

#include "fissure/fem/elastic_material.hpp"
#include "fissure/fem/tet_gradients.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

namespace fissure {

/// One row per tet, 6 Voigt columns; column-major, so each component is a contiguous array.
using StressField = Eigen::Matrix<double, Eigen::Dynamic, 6>;

/// Cauchy stress σ = D ε(u) of every tet for nodal displacements `u` (3·#nodes, m). Throws
/// InvalidInput when `u` has the wrong length or a non-finite entry. O(#tets).
StressField compute_stress(const TetMesh& mesh, const TetGradients& gradients,
                           const ElasticMaterial& material, const Eigen::VectorXd& u);

/// Principal stresses in descending order and the matching unit directions (columns), from
/// Eigen's self-adjoint solver (accurate to round-off; ≈ 200 ns per tet).
struct PrincipalStresses {
  Eigen::Vector3d values;
  Eigen::Matrix3d directions;
};
PrincipalStresses principal_stresses(const Eigen::Matrix<double, 6, 1>& voigt);

/// Maximum principal stress of a symmetric tensor by the closed form (trigonometric solution of
/// the characteristic cubic) with a vectorisable polynomial arccos and one Newton step. Agrees
/// with principal_stresses().values[0] to 1e-13 of the tensor's norm (tested), except when the two
/// largest eigenvalues nearly coincide: the cubic's root is then ill-conditioned and the error is
/// bounded by min(gap, √ε·‖σ‖) — inherent to any closed form, harmless for threshold tests.
double max_principal_stress(const Eigen::Matrix<double, 6, 1>& voigt);

/// The fused kernel of the stress map: stress of every tet and its maximum principal stress in
/// one pass over structure-of-arrays data (performance.md §4.1: ~13× faster than per-element
/// Eigen). `stress` and `max_principal` are resized. Same preconditions as compute_stress.
void compute_stress_and_max_principal(const TetMesh& mesh, const TetGradients& gradients,
                                      const ElasticMaterial& material, const Eigen::VectorXd& u,
                                      StressField& stress, Eigen::VectorXd& max_principal);

/// Voigt row → symmetric 3×3 tensor, and back.
Eigen::Matrix3d voigt_to_tensor(const Eigen::Matrix<double, 6, 1>& voigt);
Eigen::Matrix<double, 6, 1> tensor_to_voigt(const Eigen::Matrix3d& tensor);

}  // namespace fissure
