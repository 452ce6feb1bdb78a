//! Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations.
//!
//! Used by the OBB fit (principal axes of the covariance) and by the
//! "largest variance" split-axis choice. Jacobi is short, branch-light and
//! converges quadratically; 32 sweeps are far more than a 3x3 ever needs.

use glam::{DMat3, DVec3};

/// Eigenvalues and unit eigenvectors (as matrix columns) of a symmetric matrix,
/// sorted by decreasing eigenvalue.
///
/// ```
/// use bvhkit::symmetric_eigen;
/// use glam::{DMat3, DVec3};
/// let m = DMat3::from_diagonal(DVec3::new(1.0, 3.0, 2.0));
/// let (values, vectors) = symmetric_eigen(m);
/// assert_eq!(values, DVec3::new(3.0, 2.0, 1.0));
/// assert_eq!(vectors.x_axis.abs(), DVec3::Y);
/// ```
#[allow(clippy::needless_range_loop)] // index arithmetic mirrors the maths
pub fn symmetric_eigen(m: DMat3) -> (DVec3, DMat3) {
    let mut a = m.to_cols_array_2d(); // a[col][row]; symmetric, so a[i][j] == a[j][i]
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..32 {
        let off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        if off <= 1e-30 * (a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2]) || off == 0.0
        {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + libm::sqrt(theta * theta + 1.0));
            let c = 1.0 / libm::sqrt(t * t + 1.0);
            let s = t * c;
            // A' = J^T A J with J the rotation in the (p, q) plane.
            for k in 0..3 {
                let akp = a[k][p];
                let akq = a[k][q];
                a[k][p] = c * akp - s * akq;
                a[k][q] = s * akp + c * akq;
            }
            for k in 0..3 {
                let apk = a[p][k];
                let aqk = a[q][k];
                a[p][k] = c * apk - s * aqk;
                a[q][k] = s * apk + c * aqk;
            }
            for row in v.iter_mut() {
                let vp = row[p];
                let vq = row[q];
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    // v[row][col]: column j is the eigenvector of a[j][j].
    let mut idx = [0usize, 1, 2];
    idx.sort_unstable_by(|&i, &j| a[j][j].total_cmp(&a[i][i]));
    let col = |j: usize| DVec3::new(v[0][j], v[1][j], v[2][j]).normalize_or_zero();
    (
        DVec3::new(a[idx[0]][idx[0]], a[idx[1]][idx[1]], a[idx[2]][idx[2]]),
        DMat3::from_cols(col(idx[0]), col(idx[1]), col(idx[2])),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diagonalises_a_full_matrix() {
        let m = DMat3::from_cols(
            DVec3::new(4.0, 1.0, 0.5),
            DVec3::new(1.0, 3.0, 0.2),
            DVec3::new(0.5, 0.2, 1.0),
        );
        let (vals, vecs) = symmetric_eigen(m);
        for j in 0..3 {
            let v = vecs.col(j);
            let mv = m * v;
            assert!((mv - v * vals[j]).length() < 1e-9, "column {j}");
        }
        assert!(vals.x >= vals.y && vals.y >= vals.z);
        assert!((vecs.transpose() * vecs).abs_diff_eq(DMat3::IDENTITY, 1e-9));
    }
}
