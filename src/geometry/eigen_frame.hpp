#pragma once
// Internal: the eigen decomposition of a symmetric 3x3 matrix and orthonormal frames, in
// double. Used by the box fitters (bounds/) and by the oriented boxes of a mesh's tree
// (shapes/oriented_tree). Not installed.
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace proxima::detail {

/// Eigen decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations (Golub and
/// Van Loan, 8.5): returns the eigenvectors as columns, sorted by decreasing eigenvalue,
/// orthonormal and right-handed; `values` receives the eigenvalues.
glm::dmat3 symmetric_eigen(const glm::dmat3& m, glm::dvec3& values);

/// Orthonormal right-handed frame (double) whose first column is `axis` (normalised;
/// zero gives the identity).
glm::dmat3 frame_from_axis(const glm::dvec3& axis);

/// Orthonormalises `frame` (Gram-Schmidt on columns 0, 1; column 2 = cross) in double.
glm::dmat3 orthonormalize(const glm::dmat3& frame);

}  // namespace proxima::detail
