//! The sample poses of a reachability map, exactly as issue 49 defines them so that other tools
//! can compare maps sample by sample.
//!
//! - **Directions**: a Fibonacci sphere of N points, for i = 0..N-1:
//!   z_i = 1 - (2 i + 1) / N, rho_i = sqrt(1 - z_i^2), phi_i = i pi (3 - sqrt 5),
//!   d_i = (rho_i cos phi_i, rho_i sin phi_i, z_i) (unit vectors, world frame).
//! - **Rolls**: r_j = 2 pi j / R (rad), j = 0..R-1.
//! - **Tool orientation** of (d_k, r_j): the tool's z axis is d_k; its x axis is the unit vector
//!   of e - (e . d_k) d_k turned by r_j about d_k, where e is the world x axis, or the world y
//!   axis when |d_k . x| > 0.9; y = z x x.
//! - **Tool point**: the voxel centre origin + voxel (i, j, k) (m, world frame).

use nalgebra::{Matrix3, Rotation3, Vector3};
use std::f64::consts::{PI, TAU};

/// The N approach directions of the Fibonacci sphere (unit vectors, world frame), in sample
/// order (see the module documentation).
///
/// # Examples
///
/// ```
/// use armlab::reachability::fibonacci_directions;
///
/// let d = fibonacci_directions(200);
/// assert_eq!(d.len(), 200);
/// // Unit vectors, the first near the north pole, the last near the south pole.
/// assert!(d.iter().all(|v| ((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt() - 1.0).abs() < 1e-12));
/// assert!((d[0][2] - (1.0 - 1.0 / 200.0)).abs() < 1e-15);
/// assert!(d[199][2] < -0.99);
/// ```
pub fn fibonacci_directions(n: usize) -> Vec<[f64; 3]> {
    (0..n)
        .map(|i| {
            let z = 1.0 - (2 * i + 1) as f64 / n as f64;
            let rho = (1.0 - z * z).max(0.0).sqrt();
            // Left to right as the issue writes it, so that others get the same bits.
            let phi = i as f64 * PI * (3.0 - 5f64.sqrt());
            [rho * phi.cos(), rho * phi.sin(), z]
        })
        .collect()
}

/// The R roll angles 2 pi j / R (rad), j = 0..R-1.
pub fn roll_angles(r: usize) -> Vec<f64> {
    (0..r).map(|j| TAU * j as f64 / r as f64).collect()
}

/// The tool orientation of approach direction `d` (unit, world frame) and roll `roll` (rad):
/// z = d; x = the unit vector of e - (e . d) d (e = world x, or world y when |d . x| > 0.9)
/// turned by `roll` about d (right-handed); y = z x x. Columns are the tool axes in the world.
///
/// # Examples
///
/// ```
/// use armlab::reachability::sample_rotation;
///
/// // Pointing straight down with no roll: z = -z_world, x = x_world, y = z x x = -y_world.
/// let r = sample_rotation([0.0, 0.0, -1.0], 0.0);
/// let m = r.matrix();
/// assert!((m[(0, 0)] - 1.0).abs() < 1e-15 && (m[(1, 1)] + 1.0).abs() < 1e-15);
/// assert!((m[(2, 2)] + 1.0).abs() < 1e-15);
/// ```
pub fn sample_rotation(d: [f64; 3], roll: f64) -> Rotation3<f64> {
    let z = Vector3::from(d);
    let e = if z.x.abs() > 0.9 {
        Vector3::y()
    } else {
        Vector3::x()
    };
    let x0 = (e - z * e.dot(&z)).normalize();
    let y0 = z.cross(&x0);
    // Rodrigues about z, which is perpendicular to x0: x = x0 cos r + (z x x0) sin r.
    let (s, c) = roll.sin_cos();
    let x = x0 * c + y0 * s;
    let y = z.cross(&x);
    Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[x, y, z]))
}

/// A regular grid of voxels: voxel (i, j, k) is centred at `origin + voxel_m * (i, j, k)`
/// (m, world frame), `dims` = (nx, ny, nz).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct VoxelGrid {
    /// Centre of voxel (0, 0, 0) (m, world frame).
    pub origin: [f64; 3],
    /// Edge length of a voxel (m).
    pub voxel_m: f64,
    /// Voxels along x, y, z.
    pub dims: [usize; 3],
}

impl VoxelGrid {
    /// Number of voxels.
    pub fn len(&self) -> usize {
        self.dims.iter().product()
    }

    /// Whether the grid has no voxel.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Centre of voxel (i, j, k) (m, world frame).
    pub fn centre(&self, [i, j, k]: [usize; 3]) -> [f64; 3] {
        [
            self.origin[0] + self.voxel_m * i as f64,
            self.origin[1] + self.voxel_m * j as f64,
            self.origin[2] + self.voxel_m * k as f64,
        ]
    }

    /// Voxel (i, j, k) of flat index `v` in C order (k fastest), as NumPy stores (nx, ny, nz).
    pub fn ijk(&self, v: usize) -> [usize; 3] {
        let [_, ny, nz] = self.dims;
        [v / (ny * nz), v / nz % ny, v % nz]
    }

    /// Flat C-order index of voxel (i, j, k).
    pub fn flat(&self, [i, j, k]: [usize; 3]) -> usize {
        (i * self.dims[1] + j) * self.dims[2] + k
    }

    /// The voxel whose cell holds world point `p` (m), if inside the grid.
    pub fn voxel_at(&self, p: [f64; 3]) -> Option<[usize; 3]> {
        let mut out = [0; 3];
        for a in 0..3 {
            let t = ((p[a] - self.origin[a]) / self.voxel_m + 0.5).floor();
            if !(t >= 0.0 && t < self.dims[a] as f64) {
                return None;
            }
            out[a] = t as usize;
        }
        Some(out)
    }

    /// The smallest grid of `voxel_m` voxels whose cells cover the box `lo`..`hi` (m), centred
    /// on the box.
    pub fn covering(lo: [f64; 3], hi: [f64; 3], voxel_m: f64) -> Self {
        let mut origin = [0.0; 3];
        let mut dims = [0; 3];
        for a in 0..3 {
            let span = (hi[a] - lo[a]).max(0.0);
            let n = (span / voxel_m).ceil().max(0.0) as usize + 1;
            let mid = 0.5 * (lo[a] + hi[a]);
            origin[a] = mid - 0.5 * voxel_m * (n - 1) as f64;
            dims[a] = n;
        }
        Self {
            origin,
            voxel_m,
            dims,
        }
    }
}
