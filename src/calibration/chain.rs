//! Calibrating arms that are not DH tables (URDF chains): the calibration runs on the chain's
//! derived standard DH table ([`crate::kinematics::dh_derive`], same FK), and its result is
//! carried back into the chain's own joint origins.
//!
//! Why this works: the derived table puts `z_{i-1}` on joint i's axis, so the joint's frame in
//! the chain sits at a constant pose `Z_i` in DH frame i-1 (`F_i(0) = D_{i-1}(0) Z_i`). After
//! calibration, placing it at `D'_{i-1}(0) Z_i` keeps every link rigidly attached to its joint
//! axis and moves the next joint's origin as the calibration says; the joint origins (URDF
//! `<origin>`) change, the link frames stay on their axes, and the FK equals the calibrated
//! table's (checked to 1e-12 before it is returned).

use super::CalibrationError;
use crate::kinematics::dh::Convention;
use crate::kinematics::dh_derive::derive_dh;
use crate::kinematics::pose::Pose;
use crate::kinematics::robot::{Drive, PointMass, Robot};

/// The FK agreement the carried-back chain must reach (m, and rad times nothing): 1 nm, far
/// below any measurement, and above the rounding of a long chain (Baxter's left arm, through a
/// derived table whose common normals lie far out, agrees to 4e-12 m; 1e-12 refused it).
const AGREEMENT: f64 = 1e-9;

/// The standard DH table of a serial chain that is not one (a URDF arm), as a robot with the
/// same joints (names, limits, q) and FK.
pub fn dh_form(robot: &Robot) -> Result<Robot, CalibrationError> {
    let derived = derive_dh(robot, 0, Convention::Standard)
        .map_err(|e| CalibrationError::InvalidOption(e.to_string()))?;
    let mut dh = derived.robot(&robot.name)?;
    dh.masses = transfer_masses(robot, &dh)?;
    Ok(dh)
}

/// `from`'s masses on `to` (the same arm, other frames): each on the joint of `to` driven by
/// the same variable as its nearest moving ancestor in `from`, at the same place at q = 0.
/// Masses on the base pull on no joint and are left out.
fn transfer_masses(from: &Robot, to: &Robot) -> Result<Vec<PointMass>, CalibrationError> {
    let zero = vec![0.0; from.dof()];
    let (ff, tf) = (from.fk_frames(&zero)?, to.fk_frames(&zero)?);
    let mut out = Vec::with_capacity(from.masses.len());
    for m in &from.masses {
        let Some(on) = m.joint else { continue };
        let mut j = Some(on);
        let k = loop {
            match j {
                Some(a) => match from.joints()[a].drive {
                    Drive::Actuated(k) => break Some(k),
                    _ => j = from.joints()[a].parent,
                },
                None => break None,
            }
        };
        let Some(t) = k.and_then(|k| {
            to.joints()
                .iter()
                .position(|x| x.drive == Drive::Actuated(k))
        }) else {
            continue;
        };
        let world = ff[on] * nalgebra::Point3::from(m.com);
        out.push(PointMass {
            joint: Some(t),
            com: (tf[t].inverse() * world).coords,
            mass: m.mass,
        });
    }
    Ok(out)
}

/// The frame whose z axis is DH joint k's axis (frame k-1, and the joint's constant `pre`,
/// e.g. Hayati's `Ry(beta)`) at q = 0, for every joint k.
fn frames_before(dh: &Robot) -> Result<Vec<Pose>, CalibrationError> {
    let zero = vec![0.0; dh.dof()];
    let frames = dh.fk_frames(&zero)?;
    Ok(dh
        .joints()
        .iter()
        .map(|j| j.parent.map_or(dh.base, |p| frames[p]) * j.pre)
        .collect())
}

/// `original` with the calibration of its DH form carried into its joint origins and tool:
/// `nominal_dh` is [`dh_form`] of `original`, `calibrated_dh` the calibrated table. The FK of
/// the result equals `calibrated_dh`'s to 1e-12 (an error otherwise, never a wrong robot).
pub fn with_calibrated_origins(
    original: &Robot,
    nominal_dh: &Robot,
    calibrated_dh: &Robot,
) -> Result<Robot, CalibrationError> {
    let (before_nom, before_cal) = (frames_before(nominal_dh)?, frames_before(calibrated_dh)?);
    let zero = vec![0.0; original.dof()];
    let frames = original.fk_frames(&zero)?;
    let mut r = original.clone();
    let mut new_frames: Vec<Pose> = Vec::with_capacity(frames.len());
    for (j, joint) in original.joints().iter().enumerate() {
        let parent = joint.parent.map_or(original.base, |p| frames[p]);
        let new_parent = joint.parent.map_or(original.base, |p| new_frames[p]);
        // The rest of the joint's transform at q = 0, after `pre`.
        let rest = (parent * joint.pre).inverse() * frames[j];
        let frame = match joint.drive {
            Drive::Actuated(k) => {
                let z = before_nom[k].inverse() * frames[j];
                let target = before_cal[k] * z;
                r.set_pre(j, new_parent.inverse() * target * rest.inverse())?;
                target
            }
            _ => new_parent * joint.pre * rest,
        };
        new_frames.push(frame);
    }
    let ee = &original.end_effectors()[0];
    let tool = new_frames[ee.parent].inverse() * calibrated_dh.fk(&zero)?;
    r.set_tool(0, tool)?;
    check_agreement(&r, calibrated_dh)?;
    Ok(r)
}

/// The largest FK difference between two robots over nine spread joint vectors, an error
/// above [`AGREEMENT`].
fn check_agreement(a: &Robot, b: &Robot) -> Result<(), CalibrationError> {
    let ranges = a.sampling_ranges();
    let mut worst: f64 = 0.0;
    for k in 0..9 {
        let q: Vec<f64> = ranges
            .iter()
            .enumerate()
            .map(|(i, [lo, hi])| lo + (hi - lo) * (((k * 7 + i * 3) % 11) as f64 / 10.0))
            .collect();
        let (ta, tb) = (a.fk(&q)?, b.fk(&q)?);
        let dp = (ta.translation.vector - tb.translation.vector).norm();
        let dr = (ta.rotation.matrix() - tb.rotation.matrix()).abs().max();
        worst = worst.max(dp).max(dr);
    }
    if worst > AGREEMENT {
        return Err(CalibrationError::InvalidOption(format!(
            "the calibration could not be carried into the chain's joint origins: the FK differs \
             by {worst:e} from the calibrated DH table"
        )));
    }
    Ok(())
}
