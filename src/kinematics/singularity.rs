//! Which singularity an arm is at or near, named from its geometry (Sect. 3.3 of Siciliano et
//! al.): the wrist, elbow and shoulder singularities of the anthropomorphic arm with spherical
//! wrist, the aligned links of a planar arm, and otherwise a plain loss of rank of the Jacobian.
//!
//! # How it decides
//!
//! 1. **Conditioning.** The geometric Jacobian is expressed in the base frame, its linear rows
//!    are divided by the robot's characteristic length L ([`Robot::longest_chain_length`], m) so
//!    that every entry is dimensionless, and only the *task rows* are kept: the components the
//!    arm controls ([`SingularityAnalyzer::task_rows`]: x, y for the two-link planar arm; x, y and
//!    the rotation about z for the three-link one; x, y, z, rotation about z for the SCARA; the
//!    position for the 3-DOF spatial arms; the rotation for the wrist alone; all six otherwise).
//!    Its singular values sigma_1 >= sigma_2 >= ... give the *conditioning ratio*
//!    `sigma_r / sigma_1`, where r is the *task rank*: the largest rank those rows reach at a few
//!    sample configurations ([`TASK_RANK_SAMPLES`]). The arm is **near** a singularity when the
//!    ratio is below [`NEAR_RATIO`] and **at** one when it is below [`AT_RATIO`].
//! 2. **Geometry.** For the arms with a closed form ([`ClosedForm::detect`]) the joint axes are read
//!    off the Jacobian's columns (direction `z_k` = angular part, a point `p_e + z_k x v_k` on the
//!    axis), and one dimensionless *measure* per named kind is evaluated; a kind is reported when
//!    its measure is below [`GEOMETRY_NEAR`] (and is "at" below [`GEOMETRY_AT`]):
//!    - **wrist** (six-DOF arms with a spherical wrist, and the wrist alone): `|z_4 x z_6|`, the
//!      sine of the angle between the axes of joints 4 and 6 (`|sin theta5|` for the textbook
//!      wrist);
//!    - **elbow** (anthropomorphic arms, Puma 560 included): the sine of the angle at axis 3
//!      between the link from axis 2 to axis 3 and the line from axis 3 to the wrist centre (tool
//!      point for the 3-DOF arm), measured perpendicular to the parallel axes 2 and 3; it vanishes
//!      when the arm is stretched or folded (`s3 = 0` for the anthropomorphic arm of Table 2.4);
//!    - **shoulder** (anthropomorphic and spherical arms): the distance, divided by L, of the
//!      wrist centre (tool point) from the plane through axis 1 spanned by the directions of axes
//!      1 and 2. For a zero shoulder offset that plane test is "the wrist centre on the axis of
//!      joint 1"; with the Puma's lateral offset it is the offset cylinder's boundary. There the
//!      velocity that joint 1 gives the wrist centre lies in the plane that joints 2 and 3 already
//!      span;
//!    - **planar elbow** (two- and three-link planar arms, SCARA): the sine of the angle at axis
//!      2 between link 1 and the line from axis 2 to the positioned point (tool point, axis 3 of
//!      the three-link arm, axis 4 of the SCARA): links aligned, stretched or folded.
//!
//!    When the Jacobian says "near" but no measure is below [`GEOMETRY_NEAR`], the kind with the
//!    smallest measure is named if that measure is below [`GEOMETRY_ATTRIBUTE`]; otherwise the
//!    report says [`SingularityKind::RankDeficient`].
//!
//! Redundant and branched arms (DLR, LWR, Panda, humanoid) have no closed form here and are
//! reported by rank only: a wrist alignment of a seven-DOF arm is not, by itself, singular.

use crate::kinematics::ik::ClosedForm;
use crate::kinematics::ik::closed_form::{ArmKind, Family, ReversedOf};
use crate::kinematics::jacobian::analyze;
use crate::kinematics::{KinematicsError, Robot};
use nalgebra::{DMatrix, Matrix6xX, Vector3};

/// Conditioning ratio (sigma_r / sigma_1 of the length-scaled Jacobian) below which the arm is
/// reported *near* a singularity.
pub const NEAR_RATIO: f64 = 1e-2;
/// Conditioning ratio below which the arm is reported *at* a singularity (numerically singular).
pub const AT_RATIO: f64 = 1e-6;
/// A geometric measure (a sine, or a distance divided by L) below this names its kind as near.
pub const GEOMETRY_NEAR: f64 = 1e-2;
/// A geometric measure below this is "at" the singularity.
pub const GEOMETRY_AT: f64 = 1e-6;
/// When only the Jacobian says "near", the kind with the smallest measure is named if the measure
/// is below this value.
pub const GEOMETRY_ATTRIBUTE: f64 = 0.1;
/// Number of sample configurations used to find the task rank.
pub const TASK_RANK_SAMPLES: usize = 6;

/// The kind of a singularity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SingularityKind {
    /// Axes of joints 4 and 6 of a spherical wrist aligned (`sin theta5 = 0`).
    Wrist,
    /// Arm stretched or folded: axes 2 and 3 and the wrist centre in one plane.
    Elbow,
    /// Wrist centre on the axis of joint 1 (on the offset plane for a shoulder offset).
    Shoulder,
    /// Links of a planar arm aligned.
    PlanarElbow,
    /// No named kind: the Jacobian has rank `rank` of the task rank `of` (`rank == of` when it is
    /// only ill-conditioned).
    RankDeficient {
        /// Numerical rank of the length-scaled Jacobian.
        rank: usize,
        /// Task rank of the structure.
        of: usize,
    },
}

impl SingularityKind {
    /// Short label: "wrist", "elbow", "shoulder", "planar elbow", "rank-deficient (rank 5 of 6)"
    /// or "ill-conditioned (rank 6 of 6)".
    pub fn label(&self) -> String {
        match self {
            SingularityKind::Wrist => "wrist".into(),
            SingularityKind::Elbow => "elbow".into(),
            SingularityKind::Shoulder => "shoulder".into(),
            SingularityKind::PlanarElbow => "planar elbow".into(),
            SingularityKind::RankDeficient { rank, of } if rank < of => {
                format!("rank-deficient (rank {rank} of {of})")
            }
            SingularityKind::RankDeficient { rank, of } => {
                format!("ill-conditioned (rank {rank} of {of})")
            }
        }
    }
}

/// Whether the arm is at or only near a singularity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Proximity {
    /// Numerically singular (ratio below [`AT_RATIO`] or a measure below [`GEOMETRY_AT`]).
    At,
    /// Close (ratio below [`NEAR_RATIO`] or a measure below [`GEOMETRY_NEAR`]).
    Near,
}

/// One named condition that holds (approximately) at the configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct SingularCondition {
    /// The kind.
    pub kind: SingularityKind,
    /// Its dimensionless measure (a sine, a distance / L, or the conditioning ratio for
    /// [`SingularityKind::RankDeficient`]); 0 at the singularity.
    pub measure: f64,
    /// One sentence, e.g. "axes of joints 4 and 6 aligned (|sin theta5| = 3.0e-4)".
    pub detail: String,
}

/// A singularity warning.
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct SingularityReport {
    /// At or near.
    pub proximity: Proximity,
    /// Conditioning ratio sigma_r / sigma_1 of the length-scaled Jacobian.
    pub ratio: f64,
    /// The conditions that hold, smallest measure first; never empty.
    pub conditions: Vec<SingularCondition>,
}

impl SingularityReport {
    /// The kinds, smallest measure first.
    pub fn kinds(&self) -> Vec<SingularityKind> {
        self.conditions.iter().map(|c| c.kind).collect()
    }

    /// Whether `kind` is among the conditions.
    pub fn has(&self, kind: SingularityKind) -> bool {
        self.conditions.iter().any(|c| c.kind == kind)
    }

    /// A warning line, e.g. "near a wrist singularity: axes of joints 4 and 6 aligned (...)".
    pub fn message(&self) -> String {
        let at = match self.proximity {
            Proximity::At => "at",
            Proximity::Near => "near",
        };
        let kinds: Vec<String> = self.conditions.iter().map(|c| c.kind.label()).collect();
        let details: Vec<&str> = self.conditions.iter().map(|c| c.detail.as_str()).collect();
        let kinds = kinds.join(" + ");
        let article = if kinds.starts_with(['a', 'e', 'i', 'o', 'u']) {
            "an"
        } else {
            "a"
        };
        let full_rank = self
            .conditions
            .iter()
            .all(|c| matches!(c.kind, SingularityKind::RankDeficient { rank, of } if rank >= of));
        if full_rank {
            return format!(
                "{at} a singular configuration: {} (sigma_min/sigma_max = {:.1e})",
                details.join("; "),
                self.ratio
            );
        }
        format!(
            "{at} {article} {kinds} singularity: {} (sigma_min/sigma_max = {:.1e})",
            details.join("; "),
            self.ratio
        )
    }
}

/// Per-robot data of the classification, computed once per robot (rebuild it after a DH edit).
#[derive(Debug, Clone)]
pub struct SingularityAnalyzer {
    family: Option<Family>,
    no_closed_form: Option<String>,
    task_rank: Vec<usize>,
    scale: f64,
}

/// A joint axis line: unit direction and a point, world frame (m).
#[derive(Debug, Clone, Copy)]
struct Axis {
    z: Vector3<f64>,
    c: Vector3<f64>,
}

impl SingularityAnalyzer {
    /// Detects the family and the task rank of every end-effector.
    pub fn new(robot: &Robot) -> Self {
        let (family, no_closed_form) = if robot.end_effectors().len() == 1 {
            match ClosedForm::detect(robot) {
                Ok(cf) => (Some(*cf.family()), None),
                Err(e) => (None, Some(e.to_string())),
            }
        } else {
            (
                None,
                Some(format!(
                    "{} end-effectors: the closed forms solve a single chain",
                    robot.end_effectors().len()
                )),
            )
        };
        let scale = robot.longest_chain_length();
        let mut me = Self {
            family,
            no_closed_form,
            task_rank: Vec::new(),
            scale,
        };
        me.task_rank = (0..robot.end_effectors().len())
            .map(|ee| {
                (0..TASK_RANK_SAMPLES)
                    .filter_map(|s| me.svd(robot, &sample_q(robot, s), ee).ok())
                    .map(|(_, rank)| rank)
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        me
    }

    /// The closed-form family the geometric kinds are based on, if any.
    pub fn family(&self) -> Option<Family> {
        self.family
    }

    /// Why the robot has no closed form (`None` when it has one), in words.
    pub fn why_no_closed_form(&self) -> Option<&str> {
        self.no_closed_form.as_deref()
    }

    /// Task rank of end-effector `ee` (0 for an unknown index).
    pub fn task_rank(&self, ee: usize) -> usize {
        self.task_rank.get(ee).copied().unwrap_or(0)
    }

    /// The characteristic length L (m) dividing the linear rows.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// Singular values (descending) and numerical rank of the length-scaled Jacobian.
    fn svd(
        &self,
        robot: &Robot,
        q: &[f64],
        ee: usize,
    ) -> Result<(Vec<f64>, usize), KinematicsError> {
        let j = robot.jacobian(q, ee)?;
        let a = analyze(&self.scaled(robot, &j));
        Ok((a.singular_values.iter().copied().collect(), a.rank))
    }

    /// The rows (of the base-frame Jacobian `[v; omega]`) the arm controls: see the module doc.
    pub fn task_rows(&self) -> &'static [usize] {
        match self.family {
            Some(Family::Planar2) => &[0, 1],
            Some(Family::Planar3) => &[0, 1, 5],
            Some(Family::Scara) => &[0, 1, 2, 5],
            Some(
                Family::Anthropomorphic
                | Family::SphericalArm
                | Family::Cylindrical
                | Family::Cartesian,
            ) => &[0, 1, 2],
            Some(Family::SphericalWrist) => &[3, 4, 5],
            Some(
                Family::Decoupled6 { .. }
                | Family::ThreeParallel
                | Family::ThreeParallelGeneral
                | Family::Reversed6 { .. }
                | Family::General6,
            )
            | None => &[0, 1, 2, 3, 4, 5],
        }
    }

    /// The task rows (see [`SingularityAnalyzer::task_rows`]) of the geometric Jacobian of `ee`
    /// expressed in the base frame, in m (linear rows) and dimensionless (angular rows): the
    /// matrix whose singular values the readouts show.
    pub fn task_jacobian(
        &self,
        robot: &Robot,
        q: &[f64],
        ee: usize,
    ) -> Result<DMatrix<f64>, KinematicsError> {
        Ok(self.task_matrix(robot, &robot.jacobian(q, ee)?, 1.0))
    }

    /// The task rows of the base-frame Jacobian, linear rows divided by L.
    fn scaled(&self, robot: &Robot, j: &Matrix6xX<f64>) -> DMatrix<f64> {
        self.task_matrix(robot, j, self.scale)
    }

    /// The task rows of the base-frame Jacobian, linear rows divided by `length`.
    fn task_matrix(&self, robot: &Robot, j: &Matrix6xX<f64>, length: f64) -> DMatrix<f64> {
        let rt = robot.base.rotation.inverse();
        let rows = self.task_rows();
        let mut m = DMatrix::zeros(rows.len(), j.ncols());
        for c in 0..j.ncols() {
            let col = j.column(c);
            let v = rt * Vector3::new(col[0], col[1], col[2]) / length;
            let w = rt * Vector3::new(col[3], col[4], col[5]);
            let full = [v.x, v.y, v.z, w.x, w.y, w.z];
            for (r, &k) in rows.iter().enumerate() {
                m[(r, c)] = full[k];
            }
        }
        m
    }

    /// The conditioning ratio sigma_r / sigma_1 of the length-scaled Jacobian (r = task rank);
    /// 0 when the Jacobian vanishes. Dimensionless, in [0, 1].
    pub fn conditioning(
        &self,
        robot: &Robot,
        q: &[f64],
        ee: usize,
    ) -> Result<f64, KinematicsError> {
        let (sv, _) = self.svd(robot, q, ee)?;
        Ok(ratio_of(&sv, self.task_rank(ee)))
    }

    /// The singularity at or near `q` for end-effector `ee`, if any (see the module doc).
    pub fn classify(
        &self,
        robot: &Robot,
        q: &[f64],
        ee: usize,
    ) -> Result<Option<SingularityReport>, KinematicsError> {
        let j = robot.jacobian(q, ee)?;
        let a = analyze(&self.scaled(robot, &j));
        let sv: Vec<f64> = a.singular_values.iter().copied().collect();
        let of = self.task_rank(ee);
        let ratio = ratio_of(&sv, of);
        let measures = self.measures_of(robot, q, ee, &j)?;
        let jac_near = ratio < NEAR_RATIO;
        let mut conditions: Vec<SingularCondition> = measures
            .iter()
            .filter(|m| m.measure < GEOMETRY_NEAR)
            .cloned()
            .collect();
        if conditions.is_empty() && jac_near {
            match measures.first() {
                Some(m) if m.measure < GEOMETRY_ATTRIBUTE => conditions.push(m.clone()),
                _ => conditions.push(SingularCondition {
                    kind: SingularityKind::RankDeficient {
                        rank: a.rank.min(of),
                        of,
                    },
                    measure: ratio,
                    detail: if a.rank < of {
                        format!(
                            "the Jacobian has rank {} of {of}; none of the named kinds (wrist, \
                             elbow, shoulder) applies to this arm",
                            a.rank.min(of)
                        )
                    } else {
                        // Full rank, but close to losing it: say what a student sees, not
                        // "rank 6 of 6", which reads as no singularity at all.
                        "one direction of the hand barely moves as the joints turn; none of the \
                         named kinds (wrist, elbow, shoulder) applies to this arm"
                            .to_string()
                    },
                }),
            }
        }
        if conditions.is_empty() {
            return Ok(None);
        }
        let at = ratio < AT_RATIO || conditions.iter().any(|c| c.measure < GEOMETRY_AT);
        Ok(Some(SingularityReport {
            proximity: if at { Proximity::At } else { Proximity::Near },
            ratio,
            conditions,
        }))
    }

    /// Every named kind that applies to this arm with its measure at `q` (whether small or
    /// not), smallest measure first. Empty for arms without a closed-form family.
    pub fn measures(
        &self,
        robot: &Robot,
        q: &[f64],
        ee: usize,
    ) -> Result<Vec<SingularCondition>, KinematicsError> {
        let j = robot.jacobian(q, ee)?;
        self.measures_of(robot, q, ee, &j)
    }

    fn measures_of(
        &self,
        robot: &Robot,
        q: &[f64],
        ee: usize,
        j: &Matrix6xX<f64>,
    ) -> Result<Vec<SingularCondition>, KinematicsError> {
        let pe = robot.fk_ee(q, ee)?.translation.vector;
        let mut m = self.geometric(j, &pe);
        m.sort_by(|a, b| a.measure.total_cmp(&b.measure));
        Ok(m)
    }

    /// Every geometric measure that applies to the family.
    fn geometric(&self, j: &Matrix6xX<f64>, pe: &Vector3<f64>) -> Vec<SingularCondition> {
        let Some(family) = self.family else {
            return Vec::new();
        };
        let axes: Vec<Option<Axis>> = (0..j.ncols()).map(|k| axis_of(j, k, pe)).collect();
        let ax = |k: usize| axes.get(k).copied().flatten();
        let mut out = Vec::new();
        let (wrist, arm_point, arm) = match family {
            Family::Decoupled6 { arm } => {
                let w = match (ax(3), ax(4)) {
                    (Some(a4), Some(a5)) => closest_point(&a4, &a5),
                    _ => None,
                };
                (Some((3, 5)), w, Some(arm))
            }
            // The wrist at the base of a reversed chain: axes 1-3.
            Family::SphericalWrist
            | Family::Reversed6 {
                of: ReversedOf::Decoupled(_),
            } => (Some((0, 2)), None, None),
            Family::Anthropomorphic => (None, Some(*pe), Some(ArmKind::Anthropomorphic)),
            Family::SphericalArm => (None, Some(*pe), Some(ArmKind::Spherical)),
            Family::Cylindrical
            | Family::Cartesian
            | Family::ThreeParallel
            | Family::ThreeParallelGeneral
            | Family::Reversed6 {
                of: ReversedOf::ThreeParallel | ReversedOf::ThreeParallelGeneral,
            }
            | Family::General6 => (None, None, None),
            Family::Planar2 | Family::Planar3 | Family::Scara => {
                out.extend(planar_elbow(family, pe, ax));
                return out;
            }
        };
        if let Some((i, k)) = wrist {
            out.extend(wrist_condition(ax, i, k));
        }
        let (Some(p), Some(arm)) = (arm_point, arm) else {
            return out;
        };
        let what = if matches!(family, Family::Decoupled6 { .. }) {
            "wrist centre"
        } else {
            "tool point"
        };
        if arm == ArmKind::Anthropomorphic {
            out.extend(elbow_condition(ax, &p, what));
        }
        // A Cartesian arm's prismatic axes are not in one plane (else it is not detected): no
        // arm singularity.
        if matches!(arm, ArmKind::Anthropomorphic | ArmKind::Spherical) {
            out.extend(self.shoulder_condition(ax, &p, what));
        }
        out
    }

    /// The shoulder measure: the distance of `p` (the `what`) from the plane through axis 1
    /// parallel to axis 2, over the arm's length scale; `None` when axes 1 and 2 are missing or
    /// nearly parallel.
    fn shoulder_condition(
        &self,
        ax: impl Fn(usize) -> Option<Axis>,
        p: &Vector3<f64>,
        what: &str,
    ) -> Option<SingularCondition> {
        let (Some(a1), Some(a2)) = (ax(0), ax(1)) else {
            return None;
        };
        let n = a1.z.cross(&a2.z);
        if n.norm() > 0.5 {
            let d = (p - a1.c).dot(&n.normalize()).abs();
            let measure = d / self.scale;
            return Some(SingularCondition {
                kind: SingularityKind::Shoulder,
                measure,
                detail: format!(
                    "{what} {:.1} mm from the plane through axis 1 parallel to axis 2 (on the \
                     axis of joint 1 when there is no shoulder offset)",
                    d * 1000.0
                ),
            });
        }
        None
    }
}

/// The elbow of a planar arm or SCARA: links 1 and 2 stretched or folded (axes 1 and 2 and the
/// tool point, the axis of joint 3 or that of joint 4 in one plane).
fn planar_elbow(
    family: Family,
    pe: &Vector3<f64>,
    ax: impl Fn(usize) -> Option<Axis>,
) -> Option<SingularCondition> {
    let p = match family {
        Family::Planar2 => Some(*pe),
        Family::Planar3 => ax(2).map(|a| a.c),
        _ => ax(3).map(|a| a.c),
    };
    let (Some(a1), Some(a2), Some(p)) = (ax(0), ax(1), p) else {
        return None;
    };
    let (s, stretched) = bend(&a1, &a2, &p)?;
    Some(SingularCondition {
        kind: SingularityKind::PlanarElbow,
        measure: s,
        detail: format!(
            "links 1 and 2 {} (|sin theta2| = {s:.1e})",
            if stretched { "stretched" } else { "folded" }
        ),
    })
}

/// The wrist measure: |sin| of the angle between the axes of joints `i` and `k` (0-based).
fn wrist_condition(
    ax: impl Fn(usize) -> Option<Axis>,
    i: usize,
    k: usize,
) -> Option<SingularCondition> {
    let (Some(a), Some(b)) = (ax(i), ax(k)) else {
        return None;
    };
    let s = a.z.cross(&b.z).norm();
    Some(SingularCondition {
        kind: SingularityKind::Wrist,
        measure: s,
        detail: format!(
            "axes of joints {} and {} aligned (|sin theta{}| = {s:.1e})",
            i + 1,
            k + 1,
            i + 2
        ),
    })
}

/// The elbow measure of an anthropomorphic arm: axes 2 and 3 and `p` (the `what`) in one plane,
/// the arm stretched or folded.
fn elbow_condition(
    ax: impl Fn(usize) -> Option<Axis>,
    p: &Vector3<f64>,
    what: &str,
) -> Option<SingularCondition> {
    let (Some(a2), Some(a3)) = (ax(1), ax(2)) else {
        return None;
    };
    let (s, stretched) = bend(&a2, &a3, p)?;
    Some(SingularCondition {
        kind: SingularityKind::Elbow,
        measure: s,
        detail: format!(
            "arm {}: axes 2, 3 and the {what} in one plane (sine = {s:.1e})",
            if stretched { "stretched" } else { "folded" }
        ),
    })
}

/// Classifies with a one-off [`SingularityAnalyzer`] (build the analyzer once for repeated use).
pub fn classify(
    robot: &Robot,
    q: &[f64],
    ee: usize,
) -> Result<Option<SingularityReport>, KinematicsError> {
    SingularityAnalyzer::new(robot).classify(robot, q, ee)
}

fn ratio_of(sv: &[f64], rank: usize) -> f64 {
    let largest = sv.first().copied().unwrap_or(0.0);
    if rank == 0 || largest <= 0.0 {
        return 0.0;
    }
    sv.get(rank - 1).copied().unwrap_or(0.0) / largest
}

/// A deterministic configuration inside the limits (golden-ratio sequence).
fn sample_q(robot: &Robot, s: usize) -> Vec<f64> {
    robot
        .sampling_ranges()
        .iter()
        .enumerate()
        .map(|(k, [lo, hi])| {
            let f = ((k as f64 + 1.0) * 0.618_033_988_75 + s as f64 * 0.414_213_562_37).fract();
            lo + (hi - lo) * (0.1 + 0.8 * f)
        })
        .collect()
}

/// The axis of a revolute joint from its Jacobian column: direction = angular part, point =
/// `p_e + z x v` (v = z x (p_e - p) is the linear part). `None` for prismatic or idle columns.
fn axis_of(j: &Matrix6xX<f64>, k: usize, pe: &Vector3<f64>) -> Option<Axis> {
    let col = j.column(k);
    let z = Vector3::new(col[3], col[4], col[5]);
    let n = z.norm();
    if n < 1e-9 {
        return None;
    }
    let z = z / n;
    let v = Vector3::new(col[0], col[1], col[2]) / n;
    Some(Axis {
        z,
        c: pe + z.cross(&v),
    })
}

/// Midpoint of the common perpendicular of two non-parallel axes.
fn closest_point(a: &Axis, b: &Axis) -> Option<Vector3<f64>> {
    let w = a.c - b.c;
    let (aa, bb, ab) = (1.0, 1.0, a.z.dot(&b.z));
    let (d, e) = (a.z.dot(&w), b.z.dot(&w));
    let den = aa * bb - ab * ab;
    if den < 1e-12 {
        return None;
    }
    let s = (ab * e - bb * d) / den;
    let t = (aa * e - ab * d) / den;
    Some(((a.c + a.z * s) + (b.c + b.z * t)) * 0.5)
}

/// For parallel axes `a`, `b` and a point `p`: the |sine| of the angle at `b` between the link
/// a -> b and the line b -> p, measured perpendicular to the axes, and whether the two are
/// stretched (same direction) rather than folded. `None` when the axes are not parallel or a
/// segment vanishes.
fn bend(a: &Axis, b: &Axis, p: &Vector3<f64>) -> Option<(f64, bool)> {
    if a.z.cross(&b.z).norm() > 1e-6 {
        return None;
    }
    let z = a.z;
    let perp = |v: Vector3<f64>| v - z * z.dot(&v);
    let u = perp(b.c - a.c);
    let w = perp(p - b.c);
    let (nu, nw) = (u.norm(), w.norm());
    if nu < 1e-9 || nw < 1e-9 {
        return None;
    }
    Some((u.cross(&w).dot(&z).abs() / (nu * nw), u.dot(&w) > 0.0))
}
