//! Measurement setups without a laser tracker: what each one measures, the unknowns it brings
//! (pivot points, planes, sphere centres, estimated with the robot), the residual and the
//! identification Jacobian of one measurement, and what the setup cannot see, in words.
//!
//! Every measurement is `y = f(zeta, s, q)` with `s` the setup's unknowns; the residual is
//! `y - f` and the Jacobian `[df/dzeta, df/ds]`, so that one Gauss-Newton step solves
//! `Phi dx = residual` as (2.88) does for poses. The tool point's part of `df/dzeta` is the
//! position rows of (2.86): a distance, a plane or a sphere projects them on one direction.

use super::CalibrationError;
use super::model::{Measurement, ParameterModel};
use nalgebra::{DMatrix, Rotation3, Vector3};

/// How the measurements were taken: which equations they give, which unknowns come with them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Setup {
    /// Full poses of the tool in the robot's world frame (a tracker with a 6-D target).
    #[default]
    Pose,
    /// Tool points in the robot's world frame.
    Position,
    /// Tool points or poses in a tracker's (or camera's) own frame, whose pose relative to the
    /// robot's base is unknown and estimated (six base parameters, started from a rigid
    /// registration of the tool points).
    Tracker,
    /// Pairs of joint vectors whose tool points are a known distance apart (a two-socket
    /// artefact, a ball bar).
    Distance,
    /// The tool point held on fixed, unknown points with different orientations.
    Pivot,
    /// A probe touching planes of unknown pose.
    Plane,
    /// A probe touching spheres of known radius and unknown centre.
    Sphere,
}

impl Setup {
    /// Every setup, in the order of the CLI's list.
    pub const ALL: [Setup; 7] = [
        Setup::Pose,
        Setup::Position,
        Setup::Tracker,
        Setup::Distance,
        Setup::Pivot,
        Setup::Plane,
        Setup::Sphere,
    ];

    /// The name used by `--setup` and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Setup::Pose => "pose",
            Setup::Position => "position",
            Setup::Tracker => "tracker",
            Setup::Distance => "distance",
            Setup::Pivot => "pivot",
            Setup::Plane => "plane",
            Setup::Sphere => "sphere",
        }
    }

    /// What this setup cannot see, in words (the rank analysis then names the parameters).
    pub fn blind_spots(self) -> &'static str {
        match self {
            Setup::Pose => {
                "full poses see every geometric parameter of the chain; an estimated base or tool \
                 pose trades with the first and last DH rows (the analysis below names which)"
            }
            Setup::Position => {
                "tool points alone cannot see a rotation about the tool point: with the tool point \
                 on the last joint axis, the last twist and joint offset are invisible"
            }
            Setup::Tracker => {
                "the tracker's pose is estimated, so whatever moves the whole arm rigidly (the \
                 first joint's offset and d1 of a standard table) trades with it; and tool points \
                 alone cannot see a rotation about the tool point"
            }
            Setup::Distance => {
                "distances do not change when the whole arm moves or turns: the base pose is \
                 invisible (in a standard table, theta1 and d1 with it); nor can tool points see \
                 a rotation about the tool point"
            }
            Setup::Pivot => {
                "the pivot points are estimated, and they move with the base: the base pose is \
                 invisible (in a standard table, theta1 and d1 with it); nor can pivoting see the \
                 arm's size (one length keeps its nominal value and sets the scale)"
            }
            Setup::Plane => {
                "a plane of unknown pose moves with the base: the base pose is invisible (theta1 \
                 and d1 of a standard table), and each touch sees the tool point only along the \
                 plane's normal, so touch every plane in many orientations or use several planes; \
                 nor can planes see the arm's size (one length keeps its nominal value and sets the \
                 scale)"
            }
            Setup::Sphere => {
                "a sphere of unknown centre moves with the base: the base pose is invisible \
                 (theta1 and d1 of a standard table); each touch sees the tool point only along \
                 the radius"
            }
        }
    }

    /// The measurement kind this setup's measurements have ("pose", "position", ...).
    pub fn measurement_kind(self) -> &'static str {
        match self {
            Setup::Pose => "pose",
            Setup::Position | Setup::Tracker => "position",
            Setup::Distance => "distance",
            Setup::Pivot => "pivot",
            Setup::Plane => "plane",
            Setup::Sphere => "sphere",
        }
    }
}

/// A plane's unknowns: its unit normal `n = R0 (a, b, 1) / |(a, b, 1)|` (R0 fixed at the start,
/// so that a and b start at zero far from any singularity) and its offset h (`n . p = h`, m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneUnknown {
    /// The rotation taking z to the starting normal.
    pub frame: Rotation3<f64>,
    /// First tilt coordinate of the normal.
    pub a: f64,
    /// Second tilt coordinate.
    pub b: f64,
    /// Offset along the normal (m).
    pub h: f64,
}

impl PlaneUnknown {
    /// The unit normal (world frame).
    pub fn normal(&self) -> Vector3<f64> {
        (self.frame * Vector3::new(self.a, self.b, 1.0)).normalize()
    }

    /// d n / d a and d n / d b.
    fn normal_derivatives(&self) -> [Vector3<f64>; 2] {
        let v = Vector3::new(self.a, self.b, 1.0);
        let s = v.norm();
        let d = |e: Vector3<f64>, c: f64| self.frame * (e / s - v * (c / (s * s * s)));
        [d(Vector3::x(), self.a), d(Vector3::y(), self.b)]
    }
}

/// The unknowns a setup estimates with the robot: pivot points, planes, sphere centres (world
/// frame, m). Their vector is `[points (x, y, z) ...; planes (a, b, h) ...; spheres (x, y, z)
/// ...]`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Unknowns {
    /// The pivot points.
    pub points: Vec<Vector3<f64>>,
    /// The planes.
    pub planes: Vec<PlaneUnknown>,
    /// The sphere centres.
    pub spheres: Vec<Vector3<f64>>,
}

impl Unknowns {
    /// Number of scalar unknowns.
    pub fn len(&self) -> usize {
        3 * (self.points.len() + self.planes.len() + self.spheres.len())
    }

    /// Whether there are none (pose, position and distance setups).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The names of the unknowns, in the order of the vector: "point1_x", "plane1_a", ...
    pub fn names(&self) -> Vec<String> {
        let mut out = Vec::with_capacity(self.len());
        for k in 1..=self.points.len() {
            out.extend(["x", "y", "z"].map(|c| format!("point{k}_{c}")));
        }
        for k in 1..=self.planes.len() {
            out.extend(["a", "b", "h"].map(|c| format!("plane{k}_{c}")));
        }
        for k in 1..=self.spheres.len() {
            out.extend(["x", "y", "z"].map(|c| format!("sphere{k}_{c}")));
        }
        out
    }

    /// Whether the unknown at this index is a length (m) rather than a normal's tilt.
    pub fn is_length(&self, index: usize) -> bool {
        let planes = 3 * self.points.len()..3 * (self.points.len() + self.planes.len());
        !planes.contains(&index) || (index - planes.start) % 3 == 2
    }

    /// The unknowns as one vector.
    pub fn values(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.len());
        for p in &self.points {
            out.extend(p.iter());
        }
        for pl in &self.planes {
            out.extend([pl.a, pl.b, pl.h]);
        }
        for c in &self.spheres {
            out.extend(c.iter());
        }
        out
    }

    /// Adds a step `dx` (in the order of [`Self::values`]).
    pub fn apply(&mut self, dx: &[f64]) {
        let mut k = 0;
        for p in &mut self.points {
            *p += Vector3::new(dx[k], dx[k + 1], dx[k + 2]);
            k += 3;
        }
        for pl in &mut self.planes {
            pl.a += dx[k];
            pl.b += dx[k + 1];
            pl.h += dx[k + 2];
            k += 3;
        }
        for c in &mut self.spheres {
            *c += Vector3::new(dx[k], dx[k + 1], dx[k + 2]);
            k += 3;
        }
    }

    fn plane_at(&self) -> usize {
        3 * self.points.len()
    }

    fn sphere_at(&self) -> usize {
        3 * (self.points.len() + self.planes.len())
    }

    /// Starting values from the tool points of the model with `zeta`: each pivot point the mean
    /// of its tool points, each plane the least-squares plane through its points, each sphere
    /// the algebraic least-squares sphere (then refined with the known radius).
    pub fn initial(
        model: &ParameterModel,
        zeta: &[f64],
        ms: &[Measurement],
    ) -> Result<Self, CalibrationError> {
        let mut groups: [Vec<Vec<Vector3<f64>>>; 3] = Default::default();
        for m in ms {
            let (kind, index) = match m {
                Measurement::Pivot { point, .. } => (0, *point),
                Measurement::Plane { plane, .. } => (1, *plane),
                Measurement::Sphere { sphere, .. } => (2, *sphere),
                _ => continue,
            };
            if groups[kind].len() <= index {
                groups[kind].resize(index + 1, Vec::new());
            }
            groups[kind][index].push(tool_point(model, zeta, m.q())?);
        }
        let [points, planes, spheres] = groups;
        Ok(Self {
            points: points.iter().map(|g| centroid(g)).collect(),
            planes: planes.iter().map(|g| fit_plane(g)).collect(),
            spheres: spheres.iter().map(|g| fit_sphere(g)).collect(),
        })
    }
}

fn centroid(ps: &[Vector3<f64>]) -> Vector3<f64> {
    ps.iter().sum::<Vector3<f64>>() / ps.len().max(1) as f64
}

/// The least-squares plane: through the centroid, normal along the smallest principal axis.
fn fit_plane(ps: &[Vector3<f64>]) -> PlaneUnknown {
    let c = centroid(ps);
    let mut cov = nalgebra::Matrix3::zeros();
    for p in ps {
        let d = p - c;
        cov += d * d.transpose();
    }
    let eig = cov.symmetric_eigen();
    let k = eig.eigenvalues.imin();
    let n: Vector3<f64> = eig.eigenvectors.column(k).into_owned().normalize();
    let n = if n.iter().all(|v| v.is_finite()) {
        n
    } else {
        Vector3::z()
    };
    let frame = Rotation3::rotation_between(&Vector3::z(), &n)
        .unwrap_or_else(|| Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI));
    PlaneUnknown {
        frame,
        a: 0.0,
        b: 0.0,
        h: n.dot(&c),
    }
}

/// The algebraic sphere `|p|^2 = 2 c . p + k` by least squares (the centroid when the points
/// cannot fix it).
fn fit_sphere(ps: &[Vector3<f64>]) -> Vector3<f64> {
    let c0 = centroid(ps);
    if ps.len() < 4 {
        return c0;
    }
    // Centred coordinates for conditioning.
    let a = DMatrix::from_fn(ps.len(), 4, |r, c| match c {
        3 => 1.0,
        _ => 2.0 * (ps[r][c] - c0[c]),
    });
    let b = nalgebra::DVector::from_fn(ps.len(), |r, _| (ps[r] - c0).norm_squared());
    match a.svd(true, true).solve(&b, 1e-12) {
        Ok(x) if x.iter().all(|v| v.is_finite()) => c0 + Vector3::new(x[0], x[1], x[2]),
        _ => c0,
    }
}

/// The tool point of the model with `zeta` at `q` (world frame, m).
pub(super) fn tool_point(
    model: &ParameterModel,
    zeta: &[f64],
    q: &[f64],
) -> Result<Vector3<f64>, CalibrationError> {
    Ok(model.frames(zeta, q)?.1.translation.vector)
}

/// `u^T phi` of a 3 x P block as a 1 x P matrix.
fn project(u: &Vector3<f64>, phi: &DMatrix<f64>) -> DMatrix<f64> {
    DMatrix::from_fn(1, phi.ncols(), |_, c| {
        u[0] * phi[(0, c)] + u[1] * phi[(1, c)] + u[2] * phi[(2, c)]
    })
}

/// One measurement linearised: its residual `y - f` and the identification Jacobian.
#[derive(Debug, Clone, PartialEq)]
pub struct Linearised {
    /// `y - f` in its first `rows` entries (m, and rad for a pose's orientation rows).
    pub residual: [f64; 6],
    /// `df/dzeta`: rows x every parameter of zeta (fixed ones included).
    pub robot: DMatrix<f64>,
    /// `df/ds`: rows x the setup's unknowns.
    pub unknowns: DMatrix<f64>,
}

/// The residual and identification Jacobian of one measurement with the model's parameters
/// `zeta` and the setup's unknowns `s` (see the module's notes).
pub fn linearise(
    model: &ParameterModel,
    zeta: &[f64],
    s: &Unknowns,
    m: &Measurement,
) -> Result<Linearised, CalibrationError> {
    let rows = m.rows();
    let mut residual = [0.0; 6];
    let mut du = DMatrix::zeros(rows, s.len());
    // The tool point and the position rows of (2.86) at q.
    let point = |q: &[f64]| -> Result<(Vector3<f64>, DMatrix<f64>), CalibrationError> {
        Ok((
            tool_point(model, zeta, q)?,
            model.calibration_matrix(zeta, q, true)?,
        ))
    };
    let robot = match m {
        Measurement::Pose { q, .. } | Measurement::Position { q, .. } => {
            model.residual(zeta, m, &mut residual)?;
            model.calibration_matrix(zeta, q, rows == 3)?
        }
        Measurement::Distance { qa, qb, distance } => {
            let (pa, phia) = point(qa)?;
            let (pb, phib) = point(qb)?;
            let d = pa - pb;
            let len = d.norm().max(1e-300);
            residual[0] = distance - len;
            project(&(d / len), &(phia - phib))
        }
        Measurement::Pivot { q, point: k } => {
            let (p, phi) = point(q)?;
            let r = s.points[*k] - p;
            residual[..3].copy_from_slice(r.as_slice());
            for i in 0..3 {
                du[(i, 3 * k + i)] = -1.0;
            }
            phi
        }
        Measurement::Plane { q, plane } => {
            let (p, phi) = point(q)?;
            let pl = &s.planes[*plane];
            let n = pl.normal();
            residual[0] = pl.h - n.dot(&p);
            let [dna, dnb] = pl.normal_derivatives();
            let at = s.plane_at() + 3 * plane;
            du[(0, at)] = dna.dot(&p);
            du[(0, at + 1)] = dnb.dot(&p);
            du[(0, at + 2)] = -1.0;
            project(&n, &phi)
        }
        Measurement::Sphere {
            q, sphere, radius, ..
        } => {
            let (p, phi) = point(q)?;
            let v = p - s.spheres[*sphere];
            let len = v.norm().max(1e-300);
            let u = v / len;
            residual[0] = radius - len;
            let at = s.sphere_at() + 3 * sphere;
            for i in 0..3 {
                du[(0, at + i)] = -u[i];
            }
            project(&u, &phi)
        }
    };
    Ok(Linearised {
        residual,
        robot,
        unknowns: du,
    })
}

/// The tracker's pose from position measurements taken in its own frame: the rigid motion
/// `tracker_from_world` that best maps the model's tool points (with `zeta`) onto the measured
/// points, by the SVD of their cross-covariance (Kabsch / Horn). The starting point of the
/// tracker setup's six base parameters.
pub fn register_tracker(
    model: &ParameterModel,
    zeta: &[f64],
    ms: &[Measurement],
) -> Result<crate::kinematics::pose::Pose, CalibrationError> {
    let mut pairs = Vec::with_capacity(ms.len());
    for m in ms {
        match m {
            Measurement::Position { q, p } => pairs.push((tool_point(model, zeta, q)?, *p)),
            Measurement::Pose {
                q, world_from_tool, ..
            } => pairs.push((
                tool_point(model, zeta, q)?,
                world_from_tool.translation.vector,
            )),
            _ => {}
        }
    }
    if pairs.len() < 3 {
        return Err(CalibrationError::InvalidOption(
            "the tracker setup needs at least 3 position or pose measurements".into(),
        ));
    }
    let ca = pairs.iter().map(|(a, _)| a).sum::<Vector3<f64>>() / pairs.len() as f64;
    let cb = pairs.iter().map(|(_, b)| b).sum::<Vector3<f64>>() / pairs.len() as f64;
    let mut h = nalgebra::Matrix3::zeros();
    for (a, b) in &pairs {
        h += (a - ca) * (b - cb).transpose();
    }
    let svd = h.svd(true, true);
    let (u, vt) = (svd.u.expect("u requested"), svd.v_t.expect("v_t requested"));
    let mut d = nalgebra::Matrix3::identity();
    d[(2, 2)] = (vt.transpose() * u.transpose()).determinant().signum();
    let r = Rotation3::from_matrix_unchecked(vt.transpose() * d * u.transpose());
    let t = cb - r * ca;
    Ok(crate::kinematics::pose::Pose::from_parts(
        nalgebra::Translation3::from(t),
        r,
    ))
}
