//! Direct kinematics in symbols, in the textbook's notation (Sects. 2.8-2.9): each
//! `A_i^{i-1}(q_i)`, the product `T_n^0 = A_1^0 ... A_n^{n-1}` (2.50), and for an arm with a
//! spherical wrist the wrist point `p_W`, written with `c1`, `s1`, `c23` = cos(theta2 +
//! theta3), the lengths `a2`, `d4` as symbols and the constant twists folded to their values.
//!
//! How the forms come out like the book's: the product is expanded one matrix at a time and,
//! after each, the addition formulas collect `c2 c3 - s2 s3` into `c23` wherever consecutive
//! parallel axes make the angles add (and `c^2 + s^2` into 1); printing then takes common
//! factors out ([`expr`]), which gives `c1(a2c2 + a3c23)` for (2.95).
//!
//! The grammar of the strings ([`expr::Style::Json`]): names `c1`, `s23` (cos, sin of the sum of
//! the listed variables' angles; with ten or more variables the indices are separated by `_`,
//! `c1_2`), `a2`, `d4` (constant lengths, m), `d3` (a prismatic variable that is its row's DH
//! length) or `q3` (any other prismatic variable); numbers; `+ - * / ^` and parentheses.
//! Variable k is the robot's joint variable `q_k` (the angle itself where the joint's offset
//! is zero, as on every textbook arm); lengths carry the subscript of their DH row.
//!
//! The matrices of the representations of orientation ([`rotation`]: ZYZ, ZXZ, RPY, angle and
//! axis, unit quaternion) use the same engine and grammar with the book's letters: `c_phi`,
//! `s_theta`, `c_psi` (cos, sin of the angles phi, theta, psi), `r_x`, `r_y`, `r_z` (the unit
//! axis) and `eta`, `epsilon_x`, `epsilon_y`, `epsilon_z` (the unit quaternion).

pub mod document;
pub mod expr;
pub mod poly;
pub mod rotation;

use super::pose::pose_to_rows;
use super::robot::{Drive, JointGeometry, JointId, JointKind};
use super::{Convention, DhRow, KinematicsError, Pose, Robot};
use nalgebra::{Matrix4, Unit, Vector3};
use poly::{Factor, Poly, Values, cos_sin_of_sum, snap};
use std::collections::BTreeMap;
use std::f64::consts::FRAC_PI_2;
use thiserror::Error;

/// A 4x4 homogeneous matrix of polynomials (rows, then columns).
pub type SymMatrix = [[Poly; 4]; 4];

/// What cannot be written in symbols.
#[derive(Debug, Error, PartialEq)]
pub enum SymbolicError {
    /// A coupled joint whose coefficient is not +-1 (theta = 2 q1 has no name in the grammar).
    #[error(
        "joint {joint:?} follows another joint with coefficient {coefficient}: only +-1 can be written with c_k, s_k"
    )]
    Coupling {
        /// The coupled joint.
        joint: String,
        /// The coefficient that is not +-1.
        coefficient: f64,
    },
    /// The end-effector index does not exist.
    #[error("the robot has {count} end-effectors, there is no end-effector {ee}")]
    EndEffector {
        /// Index asked for.
        ee: usize,
        /// How many there are.
        count: usize,
    },
}

/// Options of [`derive()`].
#[derive(Debug, Clone, Copy, Default)]
pub struct Options {
    /// Substitute the constant lengths by their values (m) instead of naming them `a2`, `d4`.
    pub numbers: bool,
}

/// Where a variable's value comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum Source {
    /// Component `k` (0-based) of the joint vector q.
    Actuated(usize),
    /// A passive joint of a closed chain, whose value follows from the loop (Problem 2.11): it
    /// stays a variable of its own in the symbols.
    Passive(JointId),
}

/// One variable of the symbolic expressions.
#[derive(Debug, Clone, PartialEq)]
pub struct Variable {
    /// Its index k in `c_k`, `s_k`, `d_k`, `q_k` (1-based).
    pub index: u16,
    /// The joint's name.
    pub joint: String,
    /// Revolute (an angle, rad) or prismatic (a displacement, m).
    pub kind: JointKind,
    /// What it is in terms of the joint vector.
    pub source: Source,
}

/// One factor `A_to^from` of the product: the transform of one joint of the chain.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkMatrix {
    /// The frame it maps into (0 = base frame of the chain).
    pub from: usize,
    /// The frame it maps from (`from + 1`).
    pub to: usize,
    /// The joint's name.
    pub joint: String,
    /// `A_to^from(q)`.
    pub matrix: SymMatrix,
}

/// The symbolic direct kinematics of one chain of a robot (base to one end-effector).
#[derive(Debug, Clone, PartialEq)]
pub struct SymbolicKinematics {
    /// The robot's name.
    pub model: String,
    /// "standard", "modified" (DH), "urdf" or "mixed".
    pub convention: &'static str,
    /// The constant lengths and their values (m), by name (`"a2"`); with
    /// [`Options::numbers`] they are substituted and this lists what was substituted.
    pub symbols: BTreeMap<String, f64>,
    /// The variables, in index order.
    pub variables: Vec<Variable>,
    /// Each joint's matrix, base to end-effector.
    pub links: Vec<LinkMatrix>,
    /// The partial products `T_i^0`, i = 1..n (the last is `T_n^0`, (2.50)).
    pub partials: Vec<SymMatrix>,
    /// `world_from_chain_base`: the robot's base transform (not part of `T_n^0`).
    pub base: Pose,
    /// `flange_from_tool`: the end-effector's tool transform (not part of `T_n^0`).
    pub tool: Pose,
    /// For an arm with a spherical wrist: the frame whose origin is the wrist point and that
    /// origin `p_W` in the base frame of the chain (depends on the first three joints only).
    pub wrist: Option<(usize, [Poly; 3])>,
    /// Whether angle names separate indices with `_` (ten or more variables).
    pub separate_indices: bool,
    /// The index of the first variable and row: 1, or 4 for the spherical wrist numbered 4-6.
    pub first: u16,
    /// Whether the DH table was derived from URDF origins and axes (see [`derive()`]).
    pub derived_dh: bool,
    /// Where near misses of the derived table were rounded (CAD noise below 1e-9): the largest
    /// end-effector difference it makes (m, rotations times the arm's size).
    pub rounded: Option<f64>,
}

fn identity() -> SymMatrix {
    std::array::from_fn(|i| std::array::from_fn(|j| Poly::constant(if i == j { 1.0 } else { 0.0 })))
}

/// The numeric transform `p` as a matrix of constants (entries within 1e-12 of 0, +-1 exact).
pub fn constant_matrix(p: &Pose) -> SymMatrix {
    let rows = pose_to_rows(p);
    std::array::from_fn(|i| std::array::from_fn(|j| Poly::constant(snap(rows[i][j]))))
}

/// `a * b`, simplified entry by entry (4x4 transforms, or 3x3 rotations).
pub fn mat_mul<const N: usize>(a: &[[Poly; N]; N], b: &[[Poly; N]; N]) -> [[Poly; N]; N] {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let mut p = Poly::default();
            for k in 0..N {
                if !a[i][k].is_zero() && !b[k][j].is_zero() {
                    p = p.add(&a[i][k].mul(&b[k][j]));
                }
            }
            p.simplify();
            p
        })
    })
}

/// Rotation about z by the angle whose cosine and sine are `c`, `s`.
fn rot_z(c: &Poly, s: &Poly) -> SymMatrix {
    let mut m = identity();
    m[0][0] = c.clone();
    m[0][1] = s.scale(-1.0);
    m[1][0] = s.clone();
    m[1][1] = c.clone();
    m
}

/// Rotation about the unit `axis` by the angle (c, s): Rodrigues, R = c I + s [k]x + (1 - c) k k^T.
fn rot_axis(axis: &Vector3<f64>, c: &Poly, s: &Poly) -> SymMatrix {
    let mut m = identity();
    let one_minus_c = Poly::constant(1.0).add(&c.scale(-1.0));
    let cross = [
        [0.0, -axis.z, axis.y],
        [axis.z, 0.0, -axis.x],
        [-axis.y, axis.x, 0.0],
    ];
    for i in 0..3 {
        for j in 0..3 {
            let diag = if i == j { c.clone() } else { Poly::default() };
            let mut p = diag
                .add(&s.scale(snap(cross[i][j])))
                .add(&one_minus_c.scale(snap(axis[i] * axis[j])));
            p.simplify();
            m[i][j] = p;
        }
    }
    m
}

/// Translation by the vector of polynomials `v`.
fn translation(v: [Poly; 3]) -> SymMatrix {
    let mut m = identity();
    for (i, p) in v.into_iter().enumerate() {
        m[i][3] = p;
    }
    m
}

/// The symbol for a constant length, or its value with `numbers` (zero stays zero).
struct Lengths<'a> {
    numbers: bool,
    used: &'a mut BTreeMap<String, f64>,
}

impl Lengths<'_> {
    fn length(&mut self, name: char, index: usize, value: f64) -> Poly {
        if value == 0.0 {
            return Poly::default();
        }
        self.used.insert(format!("{name}{index}"), value);
        if self.numbers {
            return Poly::constant(value);
        }
        Poly::factor(Factor::Length {
            name,
            index: index as u16,
        })
    }
}

/// The motion of one joint: cos/sin of its angle (revolute) or its displacement (prismatic).
enum Motion {
    Angle(Poly, Poly),
    Slide(Poly),
    Fixed,
}

/// A DH row's matrix with the joint's motion, lengths named after row `i` (1-based), (2.52).
fn dh_matrix(
    convention: Convention,
    row: &DhRow,
    motion: &Motion,
    i: usize,
    lengths: &mut Lengths,
) -> SymMatrix {
    let (ca, sa) = (snap(row.alpha.cos()), snap(row.alpha.sin()));
    let rot_x = {
        let mut m = identity();
        m[1][1] = Poly::constant(ca);
        m[1][2] = Poly::constant(-sa);
        m[2][1] = Poly::constant(sa);
        m[2][2] = Poly::constant(ca);
        m
    };
    let constant_theta = || {
        let (c, s) = cos_sin_of_sum(&[], row.theta);
        rot_z(&c, &s)
    };
    let (rz, d) = match motion {
        Motion::Angle(c, s) => (rot_z(c, s), lengths.length('d', i, row.d)),
        Motion::Slide(v) => (constant_theta(), v.clone()),
        Motion::Fixed => (constant_theta(), lengths.length('d', i, row.d)),
    };
    let tz = translation([Poly::default(), Poly::default(), d]);
    match convention {
        // A_i = Rz(theta) Tz(d) Tx(a) Rx(alpha), (2.52)
        Convention::Standard => {
            let a = lengths.length('a', i, row.a);
            let tx = translation([a, Poly::default(), Poly::default()]);
            mat_mul(&mat_mul(&mat_mul(&rz, &tz), &tx), &rot_x)
        }
        // A_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i)
        Convention::Modified => {
            let a = lengths.length('a', i - 1, row.a);
            let tx = translation([a, Poly::default(), Poly::default()]);
            mat_mul(&mat_mul(&mat_mul(&rot_x, &tx), &rz), &tz)
        }
    }
}

/// The number of the first joint when a chain's joints are named `q4`, `q5`, `q6` (the
/// spherical wrist of Sect. 2.9.5 is joints 4-6 of an arm): 4; otherwise 1. Variables and
/// rows are numbered from it, so that the wrist's matrices read `c4c5c6` as in (2.67).
fn first_index(robot: &Robot, chain: &[JointId]) -> u16 {
    let numbers: Option<Vec<u16>> = chain
        .iter()
        .map(|&j| robot.joints()[j].name.strip_prefix('q')?.parse().ok())
        .collect();
    match numbers.as_deref() {
        Some([first, ..])
            if chain.len() == robot.dof()
                && numbers
                    .iter()
                    .flatten()
                    .enumerate()
                    .all(|(i, &k)| k == first + i as u16)
                && chain
                    .iter()
                    .enumerate()
                    .all(|(i, &j)| robot.joints()[j].drive == Drive::Actuated(i)) =>
        {
            (*first).max(1)
        }
        _ => 1,
    }
}

/// Variables: one per actuated joint (index = its q component + `first`), then the passive
/// joints of the chain (closed chains) after them.
fn variables(robot: &Robot, chain: &[JointId], first: u16) -> Vec<Variable> {
    let mut vars: Vec<Variable> = (0..robot.dof())
        .map(|k| {
            let j = robot.dof_joint(k);
            Variable {
                index: k as u16 + first,
                joint: j.name.clone(),
                kind: j.kind,
                source: Source::Actuated(k),
            }
        })
        .collect();
    for &jid in chain {
        let j = &robot.joints()[jid];
        if matches!(j.drive, Drive::Closure(_)) {
            vars.push(Variable {
                index: vars.len() as u16 + first,
                joint: j.name.clone(),
                kind: j.kind,
                source: Source::Passive(jid),
            });
        }
    }
    vars
}

/// The prismatic variable's symbol: `d_k` where the joint is row k of a DH chain with no
/// offset (so the variable is the DH length itself), `q_k` otherwise.
fn slide_factor(robot: &Robot, jid: JointId, k: u16, position: usize) -> Factor {
    let j = &robot.joints()[jid];
    let is_dh = matches!(j.geometry, JointGeometry::Dh { .. });
    let name = if is_dh && j.offset == 0.0 && position == k as usize {
        'd'
    } else {
        'q'
    };
    Factor::Var { name, index: k }
}

/// The joint's variable as `(index, sign)` terms of a sum, plus its offset.
fn variable_terms(
    robot: &Robot,
    jid: JointId,
    vars: &[Variable],
) -> Result<Option<Vec<(u16, f64)>>, SymbolicError> {
    let j = &robot.joints()[jid];
    let index_of = |source: Source| {
        vars.iter()
            .find(|v| v.source == source)
            .map(|v| v.index)
            .unwrap_or(0)
    };
    Ok(Some(match &j.drive {
        Drive::Actuated(k) => vec![(index_of(Source::Actuated(*k)), 1.0)],
        Drive::Coupled(terms) => {
            let mut out = Vec::new();
            for &(src, coef) in terms {
                if coef.abs() != 1.0 {
                    return Err(SymbolicError::Coupling {
                        joint: j.name.clone(),
                        coefficient: coef,
                    });
                }
                if let Drive::Actuated(k) = robot.joints()[src].drive {
                    out.push((index_of(Source::Actuated(k)), coef));
                }
            }
            out
        }
        Drive::Closure(_) => vec![(index_of(Source::Passive(jid)), 1.0)],
        Drive::None => return Ok(None),
    }))
}

/// The motion of joint `jid` (row `position` of the chain).
fn motion(
    robot: &Robot,
    jid: JointId,
    position: usize,
    vars: &[Variable],
) -> Result<Motion, SymbolicError> {
    let j = &robot.joints()[jid];
    let Some(terms) = variable_terms(robot, jid, vars)? else {
        return Ok(Motion::Fixed);
    };
    Ok(match j.kind {
        JointKind::Revolute => {
            let (c, s) = cos_sin_of_sum(&terms, j.offset);
            Motion::Angle(c, s)
        }
        JointKind::Prismatic => {
            let mut v = Poly::constant(j.offset);
            for (k, sign) in terms {
                let own = terms_single(robot, jid, k, vars);
                let f = if own {
                    slide_factor(robot, jid, k, position)
                } else {
                    Factor::Var {
                        name: 'q',
                        index: k,
                    }
                };
                v = v.add(&Poly::factor(f).scale(sign));
            }
            Motion::Slide(v)
        }
        JointKind::Fixed => Motion::Fixed,
    })
}

/// Whether variable `k` is joint `jid`'s own (not another joint's through a coupling).
fn terms_single(robot: &Robot, jid: JointId, k: u16, vars: &[Variable]) -> bool {
    let own = match robot.joints()[jid].drive {
        Drive::Actuated(d) => Source::Actuated(d),
        _ => Source::Passive(jid),
    };
    vars.iter().any(|v| v.index == k && v.source == own)
}

/// The symbolic direct kinematics of the chain from the base to end-effector `ee`.
///
/// A chain given by URDF origins and axes is first written as a standard DH table where it
/// has one ([`crate::kinematics::dh_derive::derive_dh`], same joint variables q), so that a
/// UR5 reads `a2c2 + a3c23` with `a2 = -0.425` rather than a page of numbers; otherwise the
/// origins are used as they are (constant numeric matrices).
///
/// # Examples
///
/// The three-link planar arm in the textbook's notation, (2.63): the position column of
/// `T_3^0` is `(a1c1 + a2c12 + a3c123, a1s1 + a2s12 + a3s123, 0)`, and the symbolic matrix
/// evaluated at q equals the forward kinematics.
///
/// ```
/// use armlab::kinematics::models::built_in;
/// use armlab::kinematics::symbolic::expr::Style;
/// use armlab::kinematics::symbolic::{Options, derive, document};
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let arm = built_in("planar3").expect("a built-in model");
/// let sk = derive(&arm, 0, &Options::default())?;
/// println!("{}", document::text(&sk, false)); // what `armlab symbolic planar3` prints
/// assert_eq!(sk.symbols["a1"], 0.5);
/// let p = document::position(&sk.t(), Style::Text, sk.separate_indices);
/// assert_eq!(p, ["a1c1 + a2c12 + a3c123", "a1s1 + a2s12 + a3s123", "0"]);
///
/// let q = [0.3, -0.2, 0.7];
/// let t = sk.eval_t(&sk.variable_values(&arm, &q)?);
/// assert!((t - arm.fk(&q)?.to_homogeneous()).amax() < 1e-15);
/// # Ok(())
/// # }
/// ```
pub fn derive(
    robot: &Robot,
    ee: usize,
    options: &Options,
) -> Result<SymbolicKinematics, SymbolicError> {
    let parent =
        robot
            .end_effectors()
            .get(ee)
            .map(|e| e.parent)
            .ok_or(SymbolicError::EndEffector {
                ee,
                count: robot.end_effectors().len(),
            })?;
    let from_origins = robot
        .chain_to(parent)
        .iter()
        .any(|&j| matches!(robot.joints()[j].geometry, JointGeometry::Origin { .. }));
    if from_origins {
        if let Some((dh, rounded)) = ideal_table(robot, ee) {
            let mut sk = derive_chain(&dh, 0, options)?;
            sk.derived_dh = true;
            sk.rounded = Some(rounded);
            return Ok(sk);
        }
        if let Ok(table) = super::dh_derive::derive_dh(robot, ee, Convention::Standard)
            && let Ok(dh) = table.robot(&robot.name)
        {
            let mut sk = derive_chain(&dh, 0, options)?;
            sk.derived_dh = true;
            return Ok(sk);
        }
    }
    derive_chain(robot, ee, options)
}

/// Rounding below this (rad; m relative to the arm's size) is CAD noise, not geometry: a
/// URDF's `rpy="1.570796325"` leaves a 5e-12 rad offset that would print on every entry.
const NEAR_MISS: f64 = 1e-9;

/// The chain's ideal DH table ([`crate::kinematics::dh_derive::derive_ideal_dh`], with joint
/// offsets within [`NEAR_MISS`] of a multiple of 90 degrees rounded too) as a robot, and the
/// largest FK difference it makes (m, rotations times the arm's size, at sample joint
/// vectors); `None` if there is none or it moves the end-effector more than that.
fn ideal_table(robot: &Robot, ee: usize) -> Option<(Robot, f64)> {
    let scale = robot.characteristic_length().max(1e-3);
    let (mut table, _) =
        super::dh_derive::derive_ideal_dh(robot, ee, NEAR_MISS, NEAR_MISS * scale).ok()?;
    for j in &mut table.joints {
        let right = (j.offset / FRAC_PI_2).round() * FRAC_PI_2;
        if (j.offset - right).abs() <= NEAR_MISS {
            j.offset = right;
        }
    }
    let dh = table.robot(&robot.name).ok()?;
    let mut worst: f64 = 0.0;
    for seed in 0..6 {
        let u = samples(seed + 101, robot.dof());
        let q: Vec<f64> = robot
            .sampling_ranges()
            .iter()
            .zip(u)
            .map(|(r, t)| 0.5 * (r[0] + r[1]) + 0.5 * (r[1] - r[0]) * t)
            .collect();
        let (a, b) = (robot.fk_ee(&q, ee).ok()?, dh.fk_ee(&q, 0).ok()?);
        let dp = (a.translation.vector - b.translation.vector).norm();
        // entries of the rotation matrices (angle_to's acos is only good to 1e-8 near zero)
        let dr = (a.rotation.matrix() - b.rotation.matrix()).abs().max() * scale;
        worst = worst.max(dp).max(dr);
    }
    (worst <= NEAR_MISS * scale).then_some((dh, worst))
}

/// [`derive()`] on the robot's own joint geometry.
fn derive_chain(
    robot: &Robot,
    ee: usize,
    options: &Options,
) -> Result<SymbolicKinematics, SymbolicError> {
    let effector = robot
        .end_effectors()
        .get(ee)
        .ok_or(SymbolicError::EndEffector {
            ee,
            count: robot.end_effectors().len(),
        })?;
    let chain = robot.chain_to(effector.parent).to_vec();
    let first = first_index(robot, &chain);
    let vars = variables(robot, &chain, first);
    let mut symbols = BTreeMap::new();
    let mut lengths = Lengths {
        numbers: options.numbers,
        used: &mut symbols,
    };
    let mut links = Vec::with_capacity(chain.len());
    let mut conventions = Vec::new();
    for (pos, &jid) in chain.iter().enumerate() {
        let j = &robot.joints()[jid];
        let row = pos + first as usize;
        let motion = motion(robot, jid, row, &vars)?;
        let own = match &j.geometry {
            JointGeometry::Dh {
                row: dh_row,
                convention,
            } => {
                conventions.push(convention.as_str());
                dh_matrix(*convention, dh_row, &motion, row, &mut lengths)
            }
            JointGeometry::Origin {
                parent_from_joint,
                axis,
            } => {
                conventions.push("urdf");
                origin_matrix(parent_from_joint, axis, &motion)
            }
        };
        let matrix = if j.pre == Pose::identity() {
            own
        } else {
            mat_mul(&constant_matrix(&j.pre), &own)
        };
        links.push(LinkMatrix {
            from: row - 1,
            to: row,
            joint: j.name.clone(),
            matrix,
        });
    }
    let partials = partial_products(&links);
    conventions.dedup();
    let convention = match conventions.as_slice() {
        [one] => one,
        [] => "standard",
        _ => "mixed",
    };
    let mut out = SymbolicKinematics {
        model: robot.name.clone(),
        convention,
        symbols,
        separate_indices: vars.len() + first as usize > 10,
        first,
        derived_dh: false,
        rounded: None,
        variables: vars,
        links,
        partials,
        base: robot.base,
        tool: effector.tool,
        wrist: None,
    };
    out.wrist = wrist_point(&out);
    Ok(out)
}

/// `T_1^0, T_2^0, ..., T_n^0`: the product one matrix at a time, simplified after each.
fn partial_products(links: &[LinkMatrix]) -> Vec<SymMatrix> {
    let mut partials: Vec<SymMatrix> = Vec::with_capacity(links.len());
    for link in links {
        let next = match partials.last() {
            Some(prev) => mat_mul(prev, &link.matrix),
            None => link.matrix.clone(),
        };
        partials.push(next);
    }
    partials
}

/// A URDF joint: `parent_from_joint` then the motion about/along `axis`.
fn origin_matrix(
    parent_from_joint: &Pose,
    axis: &Unit<Vector3<f64>>,
    motion: &Motion,
) -> SymMatrix {
    let origin = constant_matrix(parent_from_joint);
    let m = match motion {
        Motion::Angle(c, s) => rot_axis(axis, c, s),
        Motion::Slide(v) => translation(std::array::from_fn(|i| v.scale(snap(axis[i])))),
        Motion::Fixed => identity(),
    };
    mat_mul(&origin, &m)
}

/// Small deterministic generator for the wrist test's sample values.
fn samples(seed: u64, n: usize) -> Vec<f64> {
    let mut x = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (0..n)
        .map(|_| {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((x >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        })
        .collect()
}

/// The wrist point of an arm whose last three joints are revolute with axes through one point
/// (a spherical wrist, Sect. 2.12.2): the first frame origin that depends on none of the last
/// three variables and stays put in the flange frame when they move. `None` otherwise.
fn wrist_point(sk: &SymbolicKinematics) -> Option<(usize, [Poly; 3])> {
    let n = sk.partials.len();
    if n < 4 {
        return None;
    }
    let last: Vec<u16> = (n - 3..n)
        .map(|p| {
            let t = &sk.links[p].matrix;
            let vs: Vec<u16> = t.iter().flatten().flat_map(|e| e.variables()).collect();
            let mut vs = vs;
            vs.sort_unstable();
            vs.dedup();
            match vs.as_slice() {
                [k] if sk
                    .variable(*k)
                    .is_some_and(|v| v.kind == JointKind::Revolute) =>
                {
                    Some(*k)
                }
                _ => None,
            }
        })
        .collect::<Option<Vec<u16>>>()?;
    for k in 1..=n - 2 {
        let t = &sk.partials[k - 1];
        let p = [t[0][3].clone(), t[1][3].clone(), t[2][3].clone()];
        if p.iter()
            .any(|e| e.variables().iter().any(|v| last.contains(v)))
        {
            continue;
        }
        if (0..3).all(|trial| fixed_in_flange(sk, &p, &last, trial)) {
            return Some((k, p));
        }
    }
    None
}

/// Whether the point `p` (base frame of the chain) keeps its flange-frame coordinates when
/// the variables `last` move, at one sample of the others.
fn fixed_in_flange(sk: &SymbolicKinematics, p: &[Poly; 3], last: &[u16], trial: u64) -> bool {
    let m = sk.variables.len();
    let mut v = samples(trial + 1, m);
    let flange_coords = |v: &[f64]| {
        let values = Values {
            variables: v,
            first: sk.first,
            lengths: &sk.symbols,
        };
        let t = eval_matrix(sk.partials.last().expect("n >= 4"), &values);
        let world = Vector3::new(p[0].eval(&values), p[1].eval(&values), p[2].eval(&values));
        let r = t.fixed_view::<3, 3>(0, 0);
        r.transpose() * (world - t.fixed_view::<3, 1>(0, 3))
    };
    let before = flange_coords(&v);
    let other = samples(trial + 17, 3);
    for (i, &k) in last.iter().enumerate() {
        v[(k - sk.first) as usize] = 2.0 * other[i];
    }
    let after = flange_coords(&v);
    let scale = 1.0 + before.norm();
    (before - after).norm() < 1e-9 * scale
}

/// The numeric value of a symbolic matrix.
pub fn eval_matrix(m: &SymMatrix, values: &Values) -> Matrix4<f64> {
    Matrix4::from_fn(|i, j| m[i][j].eval(values))
}

impl SymbolicKinematics {
    /// The values of the variables (index k at `[k - 1]`) at the joint vector `q`: the joint
    /// variables themselves, the passive joints' from their loops.
    pub fn variable_values(&self, robot: &Robot, q: &[f64]) -> Result<Vec<f64>, KinematicsError> {
        robot.check_q(q)?;
        Ok(self
            .variables
            .iter()
            .map(|v| match v.source {
                Source::Actuated(k) => q[k],
                Source::Passive(j) => robot.joint_variable(j, q),
            })
            .collect())
    }

    /// `T_n^0` evaluated at the variables' values (see [`Self::variable_values`]).
    pub fn eval_t(&self, variables: &[f64]) -> Matrix4<f64> {
        let values = Values {
            variables,
            first: self.first,
            lengths: &self.symbols,
        };
        match self.partials.last() {
            Some(t) => eval_matrix(t, &values),
            None => Matrix4::identity(),
        }
    }

    /// The variable with index `k`.
    pub fn variable(&self, k: u16) -> Option<&Variable> {
        self.variables.iter().find(|v| v.index == k)
    }

    /// `T_n^0`, the product of every joint's matrix (2.50).
    pub fn t(&self) -> SymMatrix {
        self.partials.last().cloned().unwrap_or_else(identity)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::models::built_in;

    #[test]
    fn the_anthropomorphic_arm_has_c23_and_its_wrist_point() {
        let r = built_in("anthropomorphic_spherical_wrist").unwrap();
        let sk = derive(&r, 0, &Options::default()).unwrap();
        let t = sk.t();
        assert!(t[2][3].variables().contains(&5), "{:?}", t[2][3]);
        let (k, _) = sk.wrist.as_ref().expect("a spherical wrist");
        assert_eq!(*k, 4);
    }
}
