//! The orientation lab's model, without egui: the representation being edited and its values
//! (degrees where they are angles, as the sliders show them), the rotation they give, how near
//! the edited Euler angles are to their singular case and what that loses, and the
//! composition's product written out.

pub use crate::animation::rotation::product_text;
use crate::kinematics::EulerKind;
use crate::kinematics::orientation::{
    Combination, Representations, angle_axis_from_rotation, quaternion, quaternion_from_rotation,
    rotation_from_angle_axis, wrap_angle,
};
use crate::lesson::OrientationRep;
use nalgebra::{Rotation3, Unit, Vector3};

/// How near the singular case the lab warns: |sin theta| (ZYZ, ZXZ) or |cos theta| (RPY) below
/// the sine of 10 degrees.
pub const NEAR_SINGULAR: f64 = 0.173_648_177_666_930_35;

/// A representation the lab can edit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rep {
    /// Euler angles of one convention (ZYZ, ZXZ, RPY).
    Euler(EulerKind),
    /// Angle and axis (2.25).
    AxisAngle,
    /// The unit quaternion (2.33).
    Quaternion,
}

impl Rep {
    /// Every representation, in the lab's order.
    pub const ALL: [Rep; 5] = [
        Rep::Euler(EulerKind::Zyz),
        Rep::Euler(EulerKind::Zxz),
        Rep::Euler(EulerKind::Rpy),
        Rep::AxisAngle,
        Rep::Quaternion,
    ];

    /// The button's name.
    pub fn name(self) -> &'static str {
        match self {
            Rep::Euler(EulerKind::Zyz) => "ZYZ",
            Rep::Euler(EulerKind::Zxz) => "ZXZ",
            Rep::Euler(EulerKind::Rpy) => "RPY",
            Rep::AxisAngle => "angle-axis",
            Rep::Quaternion => "quaternion",
        }
    }

    /// The values' names and whether each is an angle (degrees in the lab).
    pub fn fields(self) -> &'static [(&'static str, bool)] {
        match self {
            Rep::Euler(_) => &[("phi", true), ("theta", true), ("psi", true)],
            Rep::AxisAngle => &[
                ("theta", true),
                ("r_x", false),
                ("r_y", false),
                ("r_z", false),
            ],
            Rep::Quaternion => &[
                ("eta", false),
                ("eps_x", false),
                ("eps_y", false),
                ("eps_z", false),
            ],
        }
    }

    /// The values of `r` in this representation (degrees for angles; the first Euler solution).
    pub fn values_of(self, r: &Rotation3<f64>) -> [f64; 4] {
        match self {
            Rep::Euler(kind) => {
                let a = kind.from_rotation(r).angles.map(f64::to_degrees);
                [a[0], a[1], a[2], 0.0]
            }
            Rep::AxisAngle => {
                let aa = angle_axis_from_rotation(r);
                let r = aa.axis.into_inner();
                [aa.angle.to_degrees(), r[0], r[1], r[2]]
            }
            Rep::Quaternion => {
                let q = quaternion_from_rotation(r);
                [q.w, q.i, q.j, q.k]
            }
        }
    }

    /// The rotation of `values` (degrees for angles), or why they give none.
    pub fn rotation_of(self, v: [f64; 4]) -> Result<Rotation3<f64>, &'static str> {
        match self {
            Rep::Euler(kind) => {
                Ok(kind.to_rotation(&Vector3::new(v[0], v[1], v[2]).map(f64::to_radians)))
            }
            Rep::AxisAngle => {
                let r = Vector3::new(v[1], v[2], v[3]);
                if r.norm() < 1e-9 {
                    return Err("the axis r is zero: give it a direction");
                }
                // (2.25) with r normalised
                Ok(rotation_from_angle_axis(
                    v[0].to_radians(),
                    &Unit::new_normalize(r),
                ))
            }
            Rep::Quaternion => {
                let n = Vector3::new(v[1], v[2], v[3]).norm().hypot(v[0]);
                if n < 1e-9 {
                    return Err(
                        "the quaternion is zero: a unit quaternion has eta^2 + |eps|^2 = 1",
                    );
                }
                Ok(quaternion(v[0], Vector3::new(v[1], v[2], v[3])).to_rotation_matrix())
            }
        }
    }
}

/// The edited Euler angles near (or at) their singular case: what is lost, and the two axes
/// that phi and psi turn about, which meet there.
#[derive(Debug, Clone, PartialEq)]
pub struct NearSingular {
    /// The convention.
    pub kind: EulerKind,
    /// theta (rad) as edited.
    pub theta: f64,
    /// Its distance (rad) from the singular value.
    pub distance: f64,
    /// The combination still determined.
    pub combination: Combination,
    /// Its value (rad).
    pub value: f64,
    /// The axis phi turns about (z of the reference frame) and the one psi turns about (z'' for
    /// ZYZ and ZXZ, x'' for RPY), in the reference frame.
    pub axes: [Vector3<f64>; 2],
}

impl NearSingular {
    /// Where `angles` (rad) of `kind` are within [`NEAR_SINGULAR`] of the singular case.
    pub fn of(kind: EulerKind, angles: &Vector3<f64>) -> Option<Self> {
        let theta = angles[1];
        let (s, singular_theta) = match kind {
            EulerKind::Rpy => (
                theta.cos(),
                if theta.sin() >= 0.0 {
                    std::f64::consts::FRAC_PI_2
                } else {
                    -std::f64::consts::FRAC_PI_2
                },
            ),
            _ => (
                theta.sin(),
                if theta.cos() >= 0.0 {
                    0.0
                } else {
                    std::f64::consts::PI
                },
            ),
        };
        if s.abs() >= NEAR_SINGULAR {
            return None;
        }
        // ZYZ, ZXZ: theta = 0 keeps phi + psi, theta = pi keeps phi - psi; RPY: theta = +pi/2
        // keeps phi - psi, -pi/2 keeps phi + psi (the library's families, multiplied out there).
        let combination = if singular_theta > 0.0 {
            Combination::PhiMinusPsi
        } else {
            Combination::PhiPlusPsi
        };
        let r = kind.to_rotation(angles);
        let last = match kind {
            EulerKind::Rpy => Vector3::x(),
            _ => Vector3::z(),
        };
        Some(Self {
            kind,
            theta,
            distance: wrap_angle(theta - singular_theta).abs(),
            combination,
            value: combination.of(angles),
            axes: [Vector3::z(), r * last],
        })
    }

    /// What the lab says, in words.
    pub fn message(&self) -> String {
        let psi_axis = match self.kind {
            EulerKind::Rpy => "x''",
            _ => "z''",
        };
        let at = if self.distance < 1e-9 {
            "at".to_string()
        } else {
            format!("{:.1}° from", self.distance.to_degrees())
        };
        format!(
            "{at} the singular case of {} (theta = {:.1}°): phi turns about z and psi about \
             {psi_axis}, {} the same axis; phi and psi are lost one into the other, and only \
             {} is determined: {:.1}°.",
            self.kind.as_str().to_uppercase(),
            self.theta.to_degrees(),
            if self.distance < 1e-9 {
                "now"
            } else {
                "nearly"
            },
            self.combination,
            self.value.to_degrees()
        )
    }
}

/// Every representation of `r` in words, one line each, for the readouts.
pub fn readouts(r: &Rotation3<f64>) -> Vec<(&'static str, String)> {
    let all = Representations::of(r);
    let q = all.quaternion;
    vec![
        ("ZYZ angles", all.zyz.to_string()),
        ("ZXZ angles", all.zxz.to_string()),
        ("RPY angles", all.rpy.to_string()),
        ("Angle and axis", all.axis_angle.to_string()),
        (
            "Unit quaternion",
            format!(
                "eta = {:.4}, eps = ({:.4}, {:.4}, {:.4}); -Q is the same rotation",
                q.w, q.i, q.j, q.k
            ),
        ),
    ]
}

/// The lesson file's name of a representation.
pub fn lesson_rep(rep: Rep) -> OrientationRep {
    match rep {
        Rep::Euler(EulerKind::Zyz) => OrientationRep::Zyz,
        Rep::Euler(EulerKind::Zxz) => OrientationRep::Zxz,
        Rep::Euler(EulerKind::Rpy) => OrientationRep::Rpy,
        Rep::AxisAngle => OrientationRep::AxisAngle,
        Rep::Quaternion => OrientationRep::Quaternion,
    }
}

/// The representation a lesson file names.
pub fn tab_rep(rep: OrientationRep) -> Rep {
    match rep {
        OrientationRep::Zyz => Rep::Euler(EulerKind::Zyz),
        OrientationRep::Zxz => Rep::Euler(EulerKind::Zxz),
        OrientationRep::Rpy => Rep::Euler(EulerKind::Rpy),
        OrientationRep::AxisAngle => Rep::AxisAngle,
        OrientationRep::Quaternion => Rep::Quaternion,
    }
}
