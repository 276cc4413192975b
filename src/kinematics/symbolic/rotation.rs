//! Rotation matrices in symbols (Sects. 2.4-2.6): the Euler angles ZYZ (2.18) and ZXZ
//! (Problem 2.1), roll-pitch-yaw (2.21), angle and axis (2.25) and the unit quaternion (2.33),
//! in the textbook's notation `c_phi c_psi - s_phi c_theta s_psi`.
//!
//! Each is derived with the engine the arms use ([`super::poly`]): the Euler and RPY matrices
//! as products of symbolic elementary rotations (2.6)-(2.8), angle and axis as
//! `c_theta I + s_theta S(r) + (1 - c_theta) r r^T` (the form (2.25) is written out from), and
//! the quaternion as the same sum with (2.30)-(2.31) put in: `cos theta = 2 eta^2 - 1`,
//! `sin theta r = 2 eta epsilon`, `(1 - cos theta) r r^T = 2 epsilon epsilon^T`. The printer
//! then takes common factors out as for the arms: `r_x^2(1 - c_theta) + c_theta`,
//! `2(eta^2 + epsilon_x^2) - 1`.

use super::mat_mul;
use super::poly::{Factor, Poly, Symbol};
use nalgebra::Matrix3;
use std::fmt;

/// A 3x3 rotation matrix of polynomials (rows, then columns).
pub type SymRotation = [[Poly; 3]; 3];

/// A representation of orientation whose matrix is written in symbols.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Representation {
    /// Euler angles ZXZ: `R = Rz(phi) Rx'(theta) Rz''(psi)`, Problem 2.1.
    Zxz,
    /// Euler angles ZYZ: `R = Rz(phi) Ry'(theta) Rz''(psi)`, (2.18).
    Zyz,
    /// Roll-pitch-yaw: `R = Rz(phi) Ry(theta) Rx(psi)` about fixed axes (ZYX about current
    /// ones), (2.21).
    Rpy,
    /// The rotation by theta about the unit axis r, (2.25).
    AxisAngle,
    /// The unit quaternion (eta, epsilon), (2.33).
    Quaternion,
}

/// Every representation, in the order the chapter's problems take them.
pub const REPRESENTATIONS: [Representation; 5] = [
    Representation::Zxz,
    Representation::Zyz,
    Representation::Rpy,
    Representation::AxisAngle,
    Representation::Quaternion,
];

/// A coordinate axis of an elementary rotation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Axis {
    X,
    Y,
    Z,
}

/// One elementary rotation of a product: about `axis` by `angle`, with `primes` marking an
/// axis of the current frame (`Ry'`, `Rz''`) as the book writes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Elementary {
    axis: Axis,
    angle: Symbol,
    primes: usize,
}

impl fmt::Display for Elementary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let axis = match self.axis {
            Axis::X => "x",
            Axis::Y => "y",
            Axis::Z => "z",
        };
        let primes = "'".repeat(self.primes);
        write!(f, "R{axis}{primes}({})", self.angle)
    }
}

impl Representation {
    /// The name of the `--rotation` flag's value: `zxz`, `axis-angle`.
    ///
    /// ```
    /// use armlab::kinematics::symbolic::rotation::Representation;
    /// assert_eq!(Representation::AxisAngle.name(), "axis-angle");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Representation::Zxz => "zxz",
            Representation::Zyz => "zyz",
            Representation::Rpy => "rpy",
            Representation::AxisAngle => "axis-angle",
            Representation::Quaternion => "quaternion",
        }
    }

    /// What it is, in words: `ZYZ Euler angles`.
    ///
    /// ```
    /// use armlab::kinematics::symbolic::rotation::Representation;
    /// assert_eq!(Representation::Rpy.title(), "Roll-pitch-yaw angles");
    /// ```
    pub fn title(self) -> &'static str {
        match self {
            Representation::Zxz => "ZXZ Euler angles",
            Representation::Zyz => "ZYZ Euler angles",
            Representation::Rpy => "Roll-pitch-yaw angles",
            Representation::AxisAngle => "Angle and axis",
            Representation::Quaternion => "Unit quaternion",
        }
    }

    /// Where the textbook gives the matrix: `(2.18)`, `Problem 2.1`.
    ///
    /// ```
    /// use armlab::kinematics::symbolic::rotation::Representation;
    /// assert_eq!(Representation::Quaternion.equation(), "(2.33)");
    /// ```
    pub fn equation(self) -> &'static str {
        match self {
            Representation::Zxz => "Problem 2.1",
            Representation::Zyz => "(2.18)",
            Representation::Rpy => "(2.21)",
            Representation::AxisAngle => "(2.25)",
            Representation::Quaternion => "(2.33)",
        }
    }

    /// The variables of the matrix, in the book's order: (phi, theta, psi) rad for the angle
    /// sets, (theta rad, r_x, r_y, r_z) for angle and axis, (eta, epsilon_x, epsilon_y,
    /// epsilon_z) for the quaternion.
    ///
    /// ```
    /// use armlab::kinematics::symbolic::poly::Symbol;
    /// use armlab::kinematics::symbolic::rotation::Representation;
    /// assert_eq!(Representation::AxisAngle.variables()[0], Symbol::Theta);
    /// assert_eq!(Representation::Quaternion.variables().len(), 4);
    /// ```
    pub fn variables(self) -> &'static [Symbol] {
        match self {
            Representation::Zxz | Representation::Zyz | Representation::Rpy => {
                &[Symbol::Phi, Symbol::Theta, Symbol::Psi]
            }
            Representation::AxisAngle => &[Symbol::Theta, Symbol::Rx, Symbol::Ry, Symbol::Rz],
            Representation::Quaternion => &[
                Symbol::Eta,
                Symbol::EpsilonX,
                Symbol::EpsilonY,
                Symbol::EpsilonZ,
            ],
        }
    }

    /// The elementary rotations whose product the matrix is, first (leftmost) first; none
    /// for angle and axis and the quaternion.
    fn product(self) -> Vec<Elementary> {
        let turn = |axis, angle, primes| Elementary {
            axis,
            angle,
            primes,
        };
        match self {
            // (2.17)-(2.18) and Problem 2.1: about z, the current y (x), the current z
            Representation::Zyz => vec![
                turn(Axis::Z, Symbol::Phi, 0),
                turn(Axis::Y, Symbol::Theta, 1),
                turn(Axis::Z, Symbol::Psi, 2),
            ],
            Representation::Zxz => vec![
                turn(Axis::Z, Symbol::Phi, 0),
                turn(Axis::X, Symbol::Theta, 1),
                turn(Axis::Z, Symbol::Psi, 2),
            ],
            // (2.20)-(2.21): x, y, z of the fixed frame, pre-multiplied
            Representation::Rpy => vec![
                turn(Axis::Z, Symbol::Phi, 0),
                turn(Axis::Y, Symbol::Theta, 0),
                turn(Axis::X, Symbol::Psi, 0),
            ],
            Representation::AxisAngle | Representation::Quaternion => Vec::new(),
        }
    }

    /// How the matrix is formed, in text: `R = Rz(phi) Rx'(theta) Rz''(psi)`.
    ///
    /// ```
    /// use armlab::kinematics::symbolic::rotation::Representation;
    /// assert_eq!(Representation::Zyz.formula(), "R = Rz(phi) Ry'(theta) Rz''(psi)");
    /// assert_eq!(
    ///     Representation::AxisAngle.formula(),
    ///     "R(theta, r) = c_theta I + s_theta S(r) + (1 - c_theta) r r^T"
    /// );
    /// ```
    pub fn formula(self) -> String {
        match self {
            Representation::AxisAngle => {
                "R(theta, r) = c_theta I + s_theta S(r) + (1 - c_theta) r r^T".into()
            }
            Representation::Quaternion => {
                "R(eta, epsilon) = (2 eta^2 - 1) I + 2 eta S(epsilon) + 2 epsilon epsilon^T".into()
            }
            _ => {
                let factors: Vec<String> = self.product().iter().map(|e| e.to_string()).collect();
                format!("R = {}", factors.join(" "))
            }
        }
    }

    /// The unit-norm constraint its variables satisfy, as a polynomial equal to 1
    /// (`r_x^2 + r_y^2 + r_z^2`; (2.32) for the quaternion); `None` for the angle sets.
    ///
    /// ```
    /// use armlab::kinematics::symbolic::expr::{Style, write};
    /// use armlab::kinematics::symbolic::rotation::Representation;
    /// let norm = Representation::AxisAngle.constraint().expect("a unit axis");
    /// assert_eq!(write(&norm, Style::Text, false), "r_x^2 + r_y^2 + r_z^2");
    /// assert!(Representation::Rpy.constraint().is_none());
    /// ```
    pub fn constraint(self) -> Option<Poly> {
        let squares = |symbols: &[Symbol]| {
            symbols.iter().fold(Poly::default(), |acc, s| {
                let x = Poly::factor(Factor::Symbol(*s));
                acc.add(&x.mul(&x))
            })
        };
        match self {
            Representation::AxisAngle => Some(squares(&self.variables()[1..])),
            Representation::Quaternion => Some(squares(self.variables())),
            _ => None,
        }
    }
}

impl fmt::Display for Representation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A rotation matrix in symbols, with what it represents.
#[derive(Debug, Clone, PartialEq)]
pub struct SymbolicRotation {
    /// The representation it is the matrix of.
    pub representation: Representation,
    /// `R`, each entry simplified.
    pub matrix: SymRotation,
}

impl SymbolicRotation {
    /// The symbols the entries are written with (`c_phi`, `s_phi`, ..., `r_x`, `eta`), each
    /// once, in the textbook's writing order.
    ///
    /// ```
    /// use armlab::kinematics::symbolic::poly::{Factor, Symbol};
    /// use armlab::kinematics::symbolic::rotation::{Representation, derive_rotation};
    /// let r = derive_rotation(Representation::AxisAngle);
    /// assert_eq!(
    ///     r.symbols(),
    ///     [
    ///         Factor::Symbol(Symbol::Rx),
    ///         Factor::Symbol(Symbol::Ry),
    ///         Factor::Symbol(Symbol::Rz),
    ///         Factor::CosOf(Symbol::Theta),
    ///         Factor::SinOf(Symbol::Theta),
    ///     ]
    /// );
    /// ```
    pub fn symbols(&self) -> Vec<Factor> {
        let mut out: Vec<Factor> = self
            .matrix
            .iter()
            .flatten()
            .flat_map(|p| p.terms.keys().flatten().map(|(f, _)| f.clone()))
            .collect();
        out.sort_by_key(Factor::writing_key);
        out.dedup();
        out
    }

    /// The matrix at the variables' values given by `value` (angles in rad).
    ///
    /// ```
    /// use armlab::kinematics::symbolic::poly::Symbol;
    /// use armlab::kinematics::symbolic::rotation::{Representation, derive_rotation};
    /// // the quaternion of a half turn about z: eta = 0, epsilon = (0, 0, 1)
    /// let r = derive_rotation(Representation::Quaternion);
    /// let m = r.eval(|s| if s == Symbol::EpsilonZ { 1.0 } else { 0.0 });
    /// assert_eq!(m, nalgebra::Matrix3::new(-1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 1.0));
    /// ```
    pub fn eval(&self, value: impl Fn(Symbol) -> f64) -> Matrix3<f64> {
        Matrix3::from_fn(|i, j| self.matrix[i][j].eval_symbols(&value))
    }
}

/// The 3x3 identity.
fn identity() -> SymRotation {
    std::array::from_fn(|i| std::array::from_fn(|j| if i == j { one() } else { zero() }))
}

fn zero() -> Poly {
    Poly::default()
}

fn one() -> Poly {
    Poly::constant(1.0)
}

/// The elementary rotation about `axis` by the named angle: (2.6), (2.7), (2.8).
fn elementary(axis: Axis, angle: Symbol) -> SymRotation {
    let c = Poly::factor(Factor::CosOf(angle));
    let s = Poly::factor(Factor::SinOf(angle));
    let ms = s.scale(-1.0);
    match axis {
        // (2.6)
        Axis::Z => [
            [c.clone(), ms, zero()],
            [s, c, zero()],
            [zero(), zero(), one()],
        ],
        // (2.7)
        Axis::Y => [
            [c.clone(), zero(), s],
            [zero(), one(), zero()],
            [ms, zero(), c],
        ],
        // (2.8)
        Axis::X => [
            [one(), zero(), zero()],
            [zero(), c.clone(), ms],
            [zero(), s, c],
        ],
    }
}

/// `d I + S(w) + k v v^T`: the rotation about an axis with the diagonal part `d`, the skew
/// part `S(w)` (the skew-symmetric matrix with `S(w) x = w x x`) and the outer product part
/// `k v v^T`.
fn axis_form(d: &Poly, w: &[Poly; 3], k: &Poly, v: &[Poly; 3]) -> SymRotation {
    let skew = [
        [zero(), w[2].scale(-1.0), w[1].clone()],
        [w[2].clone(), zero(), w[0].scale(-1.0)],
        [w[1].scale(-1.0), w[0].clone(), zero()],
    ];
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let diag = if i == j { d.clone() } else { zero() };
            let mut p = diag.add(&skew[i][j]).add(&k.mul(&v[i]).mul(&v[j]));
            p.simplify();
            p
        })
    })
}

/// The symbols as a vector of polynomials.
fn vector(symbols: [Symbol; 3]) -> [Poly; 3] {
    symbols.map(|s| Poly::factor(Factor::Symbol(s)))
}

/// The matrix of `representation` in symbols, derived with the polynomial engine.
///
/// # Examples
///
/// Problem 2.1: the rotation matrix of the ZXZ Euler angles, evaluated against the product
/// of the elementary rotations multiplied out in numbers.
///
/// ```
/// use armlab::kinematics::symbolic::expr::{Style, write};
/// use armlab::kinematics::symbolic::poly::Symbol;
/// use armlab::kinematics::symbolic::rotation::{Representation, derive_rotation};
/// use nalgebra::{Rotation3, Vector3};
///
/// let r = derive_rotation(Representation::Zxz);
/// assert_eq!(
///     write(&r.matrix[0][0], Style::Text, false),
///     "c_phi c_psi - s_phi c_theta s_psi"
/// );
/// let (phi, theta, psi) = (0.3, -1.1, 2.0);
/// let numeric = Rotation3::from_axis_angle(&Vector3::z_axis(), phi)
///     * Rotation3::from_axis_angle(&Vector3::x_axis(), theta)
///     * Rotation3::from_axis_angle(&Vector3::z_axis(), psi);
/// let m = r.eval(|s| match s {
///     Symbol::Phi => phi,
///     Symbol::Theta => theta,
///     _ => psi,
/// });
/// assert!((m - numeric.matrix()).amax() < 1e-15);
/// ```
pub fn derive_rotation(representation: Representation) -> SymbolicRotation {
    let matrix = match representation {
        Representation::Zxz | Representation::Zyz | Representation::Rpy => {
            representation.product().iter().fold(identity(), |acc, e| {
                mat_mul(&acc, &elementary(e.axis, e.angle))
            })
        }
        // (2.25): R = c I + s S(r) + (1 - c) r r^T
        Representation::AxisAngle => {
            let c = Poly::factor(Factor::CosOf(Symbol::Theta));
            let s = Poly::factor(Factor::SinOf(Symbol::Theta));
            let r = vector([Symbol::Rx, Symbol::Ry, Symbol::Rz]);
            let sr = r.clone().map(|x| s.mul(&x));
            axis_form(&c, &sr, &one().add(&c.scale(-1.0)), &r)
        }
        // (2.33) from (2.25) with (2.30)-(2.31): c = 2 eta^2 - 1, s r = 2 eta epsilon,
        // (1 - c) r r^T = 2 epsilon epsilon^T
        Representation::Quaternion => {
            let eta = Poly::factor(Factor::Symbol(Symbol::Eta));
            let eps = vector([Symbol::EpsilonX, Symbol::EpsilonY, Symbol::EpsilonZ]);
            let d = eta.mul(&eta).scale(2.0).add(&Poly::constant(-1.0));
            let w = eps.clone().map(|e| eta.mul(&e).scale(2.0));
            axis_form(&d, &w, &Poly::constant(2.0), &eps)
        }
    };
    SymbolicRotation {
        representation,
        matrix,
    }
}
