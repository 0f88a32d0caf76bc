#pragma once
// Lekien & Marsden (2005), "Tricubic interpolation in three dimensions": the 64 coefficients
// a[i + 4j + 16k] of p(x,y,z) = sum a x^i y^j z^k on the unit cell from 64 corner data
// b[d * 8 + corner]: for each derivative d (bits: x = 1, y = 2, z = 4; so f, fx, fy, fxy, fz,
// fxz, fyz, fxyz) at each corner (bits: x = 1, y = 2, z = 4).
#include <array>

namespace mfadvr {

// The paper's 64x64 matrix (row-major), built here as the inverse of the constraint matrix
// rather than typed in; its entries are integers.
const std::array<double, 64 * 64>& lekienMarsdenMatrix();

// The same product, computed one axis at a time: the constraints are a tensor product, so the
// matrix is the Kronecker product of the 4x4 cubic Hermite matrix with itself three times.
// 768 multiply-adds instead of 4096. (Tests check it against lekienMarsdenMatrix().)
void lekienMarsdenCoefficients(const double b[64], double a[64]);

}  // namespace mfadvr
