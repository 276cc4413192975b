//! Three-joint positioning arms solved for one point fixed in frame 3 (the tool point of a 3-DOF
//! arm, or the wrist centre of a 6-DOF arm): the anthropomorphic arm (Sect. 2.12.4, generalised to
//! the shoulder offsets of the Puma 560), the spherical arm (Sect. 2.12.3, Stanford arm) and the
//! cylindrical arm (Problem 2.19).
//!
//! Derivation, standard DH `A_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i)`, point w in frame 3.
//! In frame 2, `A_3 w = Rz(theta3) u` with `u = (a3, 0, d3) + Rx(alpha3) w`. With alpha1 =
//! s1 pi/2, `p = Rz(theta1) (a1 + x1, -s1 z1, d1 + s1 y1)` where (x1, y1, z1) is the point in
//! frame 1, so:
//!
//! - z1 = h is constant for the anthropomorphic and spherical arms (a lateral shoulder offset, 0
//!   for the textbook arms): `(p_x, p_y) = Rz(theta1) (a1 + x1, -s1 h)` gives
//!   `a1 + x1 = +-sqrt(p_x^2 + p_y^2 - h^2)` and theta1, which are (2.109)-(2.110) for h = a1 = 0
//!   (Paul's right/left arm of the Puma 560 otherwise), and `y1 = s1 (p_z - d1)`;
//! - anthropomorphic arm (alpha2 = 0 or pi, f2 = cos alpha2): `(x1, y1) = a2 e^{i theta2} +
//!   (u_x, f2 u_y) e^{i (theta2 + f2 theta3)}`, the two-link problem of Sect. 2.12.1 that yields
//!   (2.98)-(2.108); the Puma's `a3` and `d4` form the second link, `d3` is h;
//! - spherical arm (alpha2 = s2 pi/2): `(x1, y1) = Rz(theta2) (e, -s2 rho)` with rho the
//!   extension along z2, which is (2.94) for e = 0; rho = +-sqrt(x1^2 + y1^2 - e^2) (the textbook
//!   keeps d3 >= 0);
//! - cylindrical arm (alpha1 = 0 or pi, alpha2 = +-pi/2): the height gives d2 directly, and the
//!   horizontal point is `Rz(theta1) (g + rho n)` with constant g and unit n, a quadratic in rho;
//! - Cartesian arm (three prismatic joints): every rotation is constant and
//!   `A_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i)` moves the point by d_i along z_(i-1), so
//!   `p = c + d1 z0 + d2 z1 + d3 z2` (c the point at d = 0): a 3 x 3 linear system, one solution
//!   when the axes are not in one plane.

use super::arm_general::GeneralArm;
use super::chain::Row;
use super::planar::{TwoLinkSol, elbow_of, two_link};
use super::posture::{Extension, FreeReason, Posture, Shoulder};
use super::{ArmKind, COS_TOL};
use nalgebra::{Matrix3, Vector3};

/// One arm solution: the joint values (theta or d, offsets included) and the posture.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct ArmSol {
    /// Joint values of joints 1-3.
    pub v: [f64; 3],
    /// Posture.
    pub posture: Posture,
}

#[derive(Debug, Clone, Copy)]
enum Geom {
    /// (x1, y1) = L1 e^{i(theta2 + beta1)} + L2 e^{i(theta2 + f2 theta3 + beta2)}.
    Anthropomorphic(Anthropomorphic),
    /// (x1, y1) = Rz(theta2) (e, -s2 rho), d3 = rho - vz.
    Spherical(Spherical),
    /// Horizontal point = Rz(theta1) (g + rho n), d2 = f1 (pz - d1) - zoff, d3 = rho - vz.
    Cylindrical(Cylindrical),
    /// p = c + [z0 z1 z2] (d1, d2, d3).
    Cartesian(Cartesian),
    /// Any other three revolute joints: Pieper's quartic.
    General(GeneralArm),
}

/// The Cartesian arm's numbers: the point at d = 0 (frame 0, m) and the inverse of the matrix
/// whose columns are the prismatic axes z0, z1, z2.
#[derive(Debug, Clone, Copy)]
struct Cartesian {
    c: Vector3<f64>,
    inv: Matrix3<f64>,
}

/// The anthropomorphic arm's numbers: (x1, y1) = L1 e^{i(theta2 + beta1)} +
/// L2 e^{i(theta2 + f2 theta3 + beta2)}.
#[derive(Debug, Clone, Copy)]
struct Anthropomorphic {
    l1: f64,
    beta1: f64,
    l2: f64,
    beta2: f64,
    f2: f64,
}

/// The spherical arm's numbers: (x1, y1) = Rz(theta2) (e, -s2 rho), d3 = rho - vz.
#[derive(Debug, Clone, Copy)]
struct Spherical {
    e: f64,
    s2: f64,
    vz: f64,
}

/// The cylindrical arm's numbers: horizontal point = Rz(theta1) (g + rho n),
/// d2 = f1 (pz - d1) - zoff, d3 = rho - vz.
#[derive(Debug, Clone, Copy)]
struct Cylindrical {
    g: [f64; 2],
    n: [f64; 2],
    f1: f64,
    zoff: f64,
    vz: f64,
}

/// A recognised positioning arm with the numbers its formulas need.
#[derive(Debug, Clone)]
pub(super) struct SpatialArm {
    /// Which arm.
    pub kind: ArmKind,
    rows: [Row; 3],
    a1: f64,
    d1: f64,
    /// sin(alpha1) = +-1 (anthropomorphic and spherical arms).
    s1: f64,
    /// Lateral offset of the point along z1 (m): d2 + ... (the Puma's d3, the Stanford's d2).
    h: f64,
    geom: Geom,
    len_tol: f64,
}

/// One theta1 branch of (2.109)-(2.110) with a lateral offset.
#[derive(Debug, Clone, Copy, Default)]
struct Branch {
    th1: f64,
    x1: f64,
    b: f64,
    shoulder: Option<Shoulder>,
}

impl SpatialArm {
    /// Recognises R-R-R (alpha1 = +-pi/2, alpha2 = 0 or pi), R-R-P (alpha1, alpha2 = +-pi/2) and
    /// R-P-P (alpha1 = 0 or pi, alpha2 = +-pi/2) arms positioning the point `w` (frame-3
    /// coordinates).
    pub(super) fn detect(rows: &[Row], w: &Vector3<f64>, len_tol: f64) -> Option<Self> {
        Self::detect_named(rows, w, len_tol)
    }

    /// [`Self::detect`], and any other three revolute joints as [`ArmKind::General3R`] (the
    /// positioning arm of a six-revolute arm with a spherical wrist: Pieper's general case).
    pub(super) fn detect_any(rows: &[Row], w: &Vector3<f64>, len_tol: f64) -> Option<Self> {
        if let Some(arm) = Self::detect_named(rows, w, len_tol) {
            return Some(arm);
        }
        let three: &[Row; 3] = rows.try_into().ok()?;
        let g = GeneralArm::detect(three, w, len_tol)?;
        Some(SpatialArm {
            kind: ArmKind::General3R,
            rows: *three,
            a1: three[0].a,
            d1: three[0].d,
            s1: 0.0,
            h: 0.0,
            geom: Geom::General(g),
            len_tol,
        })
    }

    fn detect_named(rows: &[Row], w: &Vector3<f64>, len_tol: f64) -> Option<Self> {
        let [r1, r2, r3] = [*rows.first()?, *rows.get(1)?, *rows.get(2)?];
        if rows.len() != 3 {
            return None;
        }
        // The point in frame 2 before joint 3 moves: A_3 w = Rz(theta3) [(a3, 0, d3) + Rx(alpha3) w].
        let v = r3.rx(w);
        let (kind, s1, h, geom) = match (r1.revolute, r2.revolute, r3.revolute) {
            (true, true, true) => {
                let s1 = r1.twist.perpendicular_sign()?;
                let f2 = r2.twist.parallel_sign()?;
                let u = Vector3::new(r3.a + v.x, v.y, r3.d + v.z);
                let l1 = r2.a.abs();
                let (vx, vy) = (u.x, f2 * u.y);
                let l2 = vx.hypot(vy);
                if l1 <= len_tol || l2 <= len_tol {
                    return None;
                }
                let beta1 = if r2.a > 0.0 {
                    0.0
                } else {
                    std::f64::consts::PI
                };
                let geom = Geom::Anthropomorphic(Anthropomorphic {
                    l1,
                    beta1,
                    l2,
                    beta2: vy.atan2(vx),
                    f2,
                });
                (ArmKind::Anthropomorphic, s1, r2.d + f2 * u.z, geom)
            }
            (true, true, false) => {
                let s1 = r1.twist.perpendicular_sign()?;
                let s2 = r2.twist.perpendicular_sign()?;
                let (st, ct) = r3.theta.sin_cos();
                let (kx, ky) = (ct * (r3.a + v.x) - st * v.y, st * (r3.a + v.x) + ct * v.y);
                let geom = Geom::Spherical(Spherical {
                    e: r2.a + kx,
                    s2,
                    vz: v.z,
                });
                (ArmKind::Spherical, s1, r2.d + s2 * ky, geom)
            }
            (true, false, false) => {
                let f1 = r1.twist.parallel_sign()?;
                let s2 = r2.twist.perpendicular_sign()?;
                let (st, ct) = r3.theta.sin_cos();
                let (kx, ky) = (ct * (r3.a + v.x) - st * v.y, st * (r3.a + v.x) + ct * v.y);
                let e = r2.a + kx;
                let (s2t, c2t) = r2.theta.sin_cos();
                let geom = Geom::Cylindrical(Cylindrical {
                    g: [r1.a + e * c2t, f1 * e * s2t],
                    n: [s2 * s2t, -f1 * s2 * c2t],
                    f1,
                    zoff: s2 * ky,
                    vz: v.z,
                });
                (ArmKind::Cylindrical, 1.0, 0.0, geom)
            }
            (false, false, false) => {
                let geom = Geom::Cartesian(Cartesian::detect(&[r1, r2, r3], w)?);
                (ArmKind::Cartesian, 1.0, 0.0, geom)
            }
            _ => return None,
        };
        Some(SpatialArm {
            kind,
            rows: [r1, r2, r3],
            a1: r1.a,
            d1: r1.d,
            s1,
            h,
            geom,
            len_tol,
        })
    }

    /// `R_3^0` for the joint values `v`.
    #[inline]
    pub(super) fn rotation(&self, v: &[f64; 3]) -> Matrix3<f64> {
        let [r1, r2, r3] = &self.rows;
        if let Geom::Anthropomorphic(Anthropomorphic { f2, .. }) = self.geom {
            // Parallel axes 2 and 3: Rz(theta2) Rx(alpha2) Rz(theta3) Rx(alpha3)
            // = Rz(theta2 + f2 theta3) Rx(alpha2 + alpha3), since Rx(pi) Rz(t) = Rz(-t) Rx(pi).
            let mut r23 = *r3;
            r23.ca = r2.ca * r3.ca - r2.sa * r3.sa;
            r23.sa = r2.sa * r3.ca + r2.ca * r3.sa;
            return r1.rotation(v[0]) * r23.rotation(v[1] + f2 * v[2]);
        }
        r1.rotation(r1.theta_of(v[0]))
            * r2.rotation(r2.theta_of(v[1]))
            * r3.rotation(r3.theta_of(v[2]))
    }

    /// The theta1 branches for the horizontal point (px, py): (2.109), (2.110) when there is no
    /// lateral offset; with an offset h, (px, py) = Rz(theta1) (a1 + x1, -s1 h), so
    /// a1 + x1 = +-sqrt(px^2 + py^2 - h^2).
    fn shoulder(&self, px: f64, py: f64, out: &mut [Branch; 2]) -> Result<usize, f64> {
        let r = (px * px + py * py).sqrt();
        let h = self.h;
        let tol = self.len_tol;
        if h.abs() <= tol {
            if r <= tol {
                out[0] = Branch {
                    th1: py.atan2(px),
                    x1: r - self.a1,
                    b: 1.0,
                    shoulder: Some(Shoulder::OnAxis),
                };
                return Ok(1);
            }
            // (2.109), (2.110)
            out[0] = Branch {
                th1: py.atan2(px),
                x1: r - self.a1,
                b: 1.0,
                shoulder: Some(Shoulder::Right),
            };
            out[1] = Branch {
                th1: (-py).atan2(-px),
                x1: -r - self.a1,
                b: -1.0,
                shoulder: Some(Shoulder::Left),
            };
            return Ok(2);
        }
        if h.abs() > r * (1.0 + COS_TOL) {
            return Err(h.abs() - r);
        }
        let branch = |big_r: f64, b: f64, shoulder| {
            let (vx, vy) = (big_r, -self.s1 * h);
            Branch {
                th1: (vx * py - vy * px).atan2(vx * px + vy * py),
                x1: big_r - self.a1,
                b,
                shoulder: Some(shoulder),
            }
        };
        if h.abs() >= r * (1.0 - COS_TOL) {
            out[0] = branch(0.0, 1.0, Shoulder::Boundary);
            return Ok(1);
        }
        let big_r = ((r - h.abs()) * (r + h.abs())).sqrt();
        out[0] = branch(big_r, 1.0, Shoulder::Right);
        out[1] = branch(-big_r, -1.0, Shoulder::Left);
        Ok(2)
    }

    /// Every solution for the point `p` (frame 0), shoulder right first. `Err(distance)` when
    /// no branch reaches it: the gap measured in the plane of the arm (frame 1), which is
    /// |p_W| - (a2 + a3) for the textbook arm, or the gap to the cylinder of the lateral offset.
    pub(super) fn solve(&self, p: &Vector3<f64>, out: &mut [ArmSol; 4]) -> Result<usize, f64> {
        match &self.geom {
            Geom::Anthropomorphic(g) => self.solve_anthropomorphic(g, p, out),
            Geom::Spherical(g) => self.solve_spherical(g, p, out),
            Geom::Cylindrical(g) => self.solve_cylindrical(g, p, out),
            Geom::General(g) => g.solve(p, out),
            Geom::Cartesian(g) => {
                // Always reachable: the joint limits decide (the caller checks them).
                out[0] = ArmSol {
                    v: (g.inv * (p - g.c)).into(),
                    posture: Posture::default(),
                };
                Ok(1)
            }
        }
    }

    /// [`Self::solve`] for the anthropomorphic arm: per theta1 branch, the two-link problem of
    /// Sect. 2.12.1 in the plane of the arm.
    #[inline]
    fn solve_anthropomorphic(
        &self,
        g: &Anthropomorphic,
        p: &Vector3<f64>,
        out: &mut [ArmSol; 4],
    ) -> Result<usize, f64> {
        let Anthropomorphic {
            l1,
            beta1,
            l2,
            beta2,
            f2,
        } = *g;
        let mut br = [Branch::default(); 2];
        let nb = self.shoulder(p.x, p.y, &mut br)?;
        let y1 = self.s1 * (p.z - self.d1);
        let mut n = 0;
        let mut gap = f64::INFINITY;
        let mut tl = [TwoLinkSol::default(); 2];
        for b in &br[..nb] {
            match two_link(b.x1, y1, l1, l2, self.len_tol, &mut tl) {
                Err(d) => gap = gap.min(d),
                Ok(k) => {
                    for s in &tl[..k] {
                        // theta2 from (2.103)-(2.108), theta3 from (2.98)-(2.101).
                        let th2 = s.a - beta1;
                        let th3 = f2 * (s.d - beta2 + beta1);
                        let mut posture = Posture {
                            shoulder: b.shoulder,
                            elbow: Some(elbow_of(s, self.s1 * b.b)),
                            ..Posture::default()
                        };
                        if b.shoulder == Some(Shoulder::OnAxis) {
                            posture.free[0] = Some(FreeReason::ShoulderAxis);
                        }
                        if s.free_first {
                            posture.free[1] = Some(FreeReason::ElbowAtShoulder);
                        }
                        out[n] = ArmSol {
                            v: [b.th1, th2, th3],
                            posture,
                        };
                        n += 1;
                    }
                }
            }
        }
        if n == 0 { Err(gap) } else { Ok(n) }
    }

    /// [`Self::solve`] for the spherical arm: per theta1 branch, the signed extensions rho and
    /// theta2 of (2.94).
    #[inline]
    fn solve_spherical(
        &self,
        g: &Spherical,
        p: &Vector3<f64>,
        out: &mut [ArmSol; 4],
    ) -> Result<usize, f64> {
        let Spherical { e, s2, vz } = *g;
        let mut br = [Branch::default(); 2];
        let nb = self.shoulder(p.x, p.y, &mut br)?;
        let y1 = self.s1 * (p.z - self.d1);
        let mut n = 0;
        let mut gap = f64::INFINITY;
        for b in &br[..nb] {
            let mut rho = [(0.0, Extension::Forward); 2];
            match extension(b.x1.hypot(y1), e, self.len_tol, &mut rho) {
                Err(d) => gap = gap.min(d),
                Ok(k) => {
                    for &(rho, ext) in &rho[..k] {
                        // (2.94): (x1, y1) = Rz(theta2) (e, -s2 rho); theta2 as in
                        // Sect. 2.12.3, Atan2(p_Wx c1 + p_Wy s1, p_Wz) for e = 0.
                        let (vx, vy) = (e, -s2 * rho);
                        let th2 = (vx * y1 - vy * b.x1).atan2(vx * b.x1 + vy * y1);
                        let mut posture = Posture {
                            shoulder: b.shoulder,
                            extension: Some(ext),
                            ..Posture::default()
                        };
                        if b.shoulder == Some(Shoulder::OnAxis) {
                            posture.free[0] = Some(FreeReason::ShoulderAxis);
                        }
                        if ext == Extension::Zero && e.abs() <= self.len_tol {
                            posture.free[1] = Some(FreeReason::ExtensionZero);
                        }
                        out[n] = ArmSol {
                            v: [b.th1, th2, rho - vz],
                            posture,
                        };
                        n += 1;
                    }
                }
            }
        }
        if n == 0 { Err(gap) } else { Ok(n) }
    }

    /// [`Self::solve`] for the cylindrical arm: d2 from the height, rho from the quadratic
    /// |g + rho n| = r, then theta1.
    #[inline]
    fn solve_cylindrical(
        &self,
        g: &Cylindrical,
        p: &Vector3<f64>,
        out: &mut [ArmSol; 4],
    ) -> Result<usize, f64> {
        let Cylindrical {
            g,
            n: dir,
            f1,
            zoff,
            vz,
        } = *g;
        let r = p.x.hypot(p.y);
        let gn = g[0] * dir[0] + g[1] * dir[1];
        let gp = g[0] * dir[1] - g[1] * dir[0];
        // |g + rho n| = r: rho = -g.n +- sqrt(r^2 - (g x n)^2)
        let mut rho = [(0.0, Extension::Forward); 2];
        let k = extension(r, gp, self.len_tol, &mut rho)?;
        let d2 = f1 * (p.z - self.d1) - zoff;
        for (i, &(rho, ext)) in rho[..k].iter().enumerate() {
            let rho = rho - gn;
            let (vx, vy) = (g[0] + rho * dir[0], g[1] + rho * dir[1]);
            let th1 = (vx * p.y - vy * p.x).atan2(vx * p.x + vy * p.y);
            let mut posture = Posture {
                extension: Some(ext),
                ..Posture::default()
            };
            if ext == Extension::Zero && gp.abs() <= self.len_tol {
                posture.free[0] = Some(FreeReason::ShoulderAxis);
            }
            out[i] = ArmSol {
                v: [th1, d2, rho - vz],
                posture,
            };
        }
        Ok(k)
    }
}

impl Cartesian {
    /// The numbers of three prismatic rows moving the point `w` (frame 3); `None` when the
    /// three axes are in one plane (or nearly: the volume they span below 1e-6).
    fn detect(rows: &[Row; 3], w: &Vector3<f64>) -> Option<Self> {
        let mut r = Matrix3::identity();
        let mut c = Vector3::zeros();
        let mut axes = Matrix3::zeros();
        for (i, row) in rows.iter().enumerate() {
            axes.set_column(i, &r.column(2));
            // A_i at d_i = 0 (its offset included in d_i): Rz(theta) Tx(a) Rx(alpha).
            let (s, co) = row.theta.sin_cos();
            c += r * Vector3::new(row.a * co, row.a * s, 0.0);
            r *= row.rotation(row.theta);
        }
        c += r * w;
        if axes.determinant().abs() < 1e-6 {
            return None;
        }
        Some(Cartesian {
            c,
            inv: axes.try_inverse()?,
        })
    }
}

/// The signed extensions rho with rho^2 + e^2 = r^2 (the point at distance r, a fixed leg e
/// perpendicular to the prismatic axis): +sqrt first (the textbook's d3 >= 0), then the mirror.
fn extension(r: f64, e: f64, tol: f64, out: &mut [(f64, Extension); 2]) -> Result<usize, f64> {
    let e = e.abs();
    if e <= tol {
        if r <= tol {
            out[0] = (0.0, Extension::Zero);
            return Ok(1);
        }
        out[0] = (r, Extension::Forward);
        out[1] = (-r, Extension::Reversed);
        return Ok(2);
    }
    if e > r * (1.0 + COS_TOL) {
        return Err(e - r);
    }
    if e >= r * (1.0 - COS_TOL) {
        out[0] = (0.0, Extension::Zero);
        return Ok(1);
    }
    let rho = ((r - e) * (r + e)).sqrt();
    out[0] = (rho, Extension::Forward);
    out[1] = (-rho, Extension::Reversed);
    Ok(2)
}
