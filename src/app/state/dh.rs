//! The live-editable DH table: one text cell per joint and field, parsed on every keystroke.
//! A cell that parses and fits is applied at once (the arm follows as you type); a cell that
//! does not keeps its text, is marked with the reason, and the robot keeps its last valid value.

use super::units::{EntryError, Quantity, format_entry, parse_entry};
use super::{AppState, StateError};
use crate::kinematics::{Drive, Joint, JointGeometry, JointKind, Robot};

/// A column of the DH table editor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DhField {
    /// Link length a (mm at the UI).
    A,
    /// Link twist alpha (angle unit at the UI).
    Alpha,
    /// Link offset d (mm); the variable of a prismatic joint, so not editable there.
    D,
    /// Joint angle theta; the variable of a revolute joint, so not editable there.
    Theta,
    /// Joint offset: theta = q + offset (revolute, angle unit) or d = q + offset (prismatic, mm).
    Offset,
    /// Lower joint limit (angle unit or mm).
    Lower,
    /// Upper joint limit (angle unit or mm).
    Upper,
}

/// Number of DH table columns.
pub const DH_FIELDS: usize = 7;

impl DhField {
    /// Every column, in table order.
    pub const ALL: [DhField; DH_FIELDS] = [
        DhField::A,
        DhField::Alpha,
        DhField::D,
        DhField::Theta,
        DhField::Offset,
        DhField::Lower,
        DhField::Upper,
    ];

    /// Position in [`DhField::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// Column header: "a", "alpha", "d", "theta", "offset", "lower", "upper".
    pub fn name(self) -> &'static str {
        match self {
            DhField::A => "a",
            DhField::Alpha => "alpha",
            DhField::D => "d",
            DhField::Theta => "theta",
            DhField::Offset => "offset",
            DhField::Lower => "lower",
            DhField::Upper => "upper",
        }
    }

    /// What the column measures for a joint of this kind.
    pub fn quantity(self, kind: JointKind) -> Quantity {
        match self {
            DhField::A | DhField::D => Quantity::Length,
            DhField::Alpha | DhField::Theta => Quantity::Angle,
            DhField::Offset | DhField::Lower | DhField::Upper => match kind {
                JointKind::Prismatic => Quantity::Length,
                _ => Quantity::Angle,
            },
        }
    }

    /// Why this column cannot be edited for `joint`, or `None` if it can.
    pub fn not_editable(self, joint: &Joint) -> Option<&'static str> {
        let dh = matches!(joint.geometry, JointGeometry::Dh { .. });
        if matches!(joint.drive, Drive::Closure(_)) {
            return Some("this joint follows its closed chain's loop: its row is the mechanism's");
        }
        match self {
            DhField::A | DhField::Alpha | DhField::D | DhField::Theta if !dh => {
                Some("this joint is not described by a DH row (URDF origin)")
            }
            DhField::D if joint.kind == JointKind::Prismatic => {
                Some("d is the variable of a prismatic joint: edit its offset or move its slider")
            }
            DhField::Theta if joint.kind == JointKind::Revolute => Some(
                "theta is the variable of a revolute joint: edit its offset or move its slider",
            ),
            DhField::Offset if joint.kind == JointKind::Fixed => {
                Some("a fixed joint has no variable, hence no offset")
            }
            DhField::Lower | DhField::Upper if !matches!(joint.drive, Drive::Actuated(_)) => {
                Some("only actuated joints have limits")
            }
            _ => None,
        }
    }

    /// The current value (rad or m) of this column for `joint`; 0 where it does not apply.
    pub fn value(self, joint: &Joint) -> f64 {
        let row = match joint.geometry {
            JointGeometry::Dh { row, .. } => Some(row),
            JointGeometry::Origin { .. } => None,
        };
        match self {
            DhField::A => row.map_or(0.0, |r| r.a),
            DhField::Alpha => row.map_or(0.0, |r| r.alpha),
            DhField::D => row.map_or(0.0, |r| r.d),
            DhField::Theta => row.map_or(0.0, |r| r.theta),
            DhField::Offset => joint.offset,
            DhField::Lower => joint.limits[0],
            DhField::Upper => joint.limits[1],
        }
    }
}

/// One cell of the DH table editor.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DhCell {
    /// The text as typed (or as formatted from the model, in display units: mm and the angle
    /// unit). A non-editable cell holds a placeholder ("q3" for a joint variable, "-").
    pub text: String,
    /// Why the text is not applied, if it is not (its `Display` is the message to show).
    pub error: Option<EntryError>,
    /// Whether the cell can be edited.
    pub editable: bool,
}

/// Cells of one joint, indexed by [`DhField::index`].
pub type DhRowCells = [DhCell; DH_FIELDS];

/// Fresh cells for every joint of `robot`, formatted in display units.
pub(super) fn build_cells(robot: &Robot, unit: super::AngleUnit) -> Vec<DhRowCells> {
    robot
        .joints()
        .iter()
        .map(|joint| {
            std::array::from_fn(|i| {
                let f = DhField::ALL[i];
                let editable = f.not_editable(joint).is_none();
                let text = if editable {
                    format_entry(f.value(joint), f.quantity(joint.kind), unit)
                } else if matches!(f, DhField::D | DhField::Theta)
                    && matches!(joint.geometry, JointGeometry::Dh { .. })
                    && joint.kind != JointKind::Fixed
                {
                    format!("{} (variable)", joint.name)
                } else {
                    "-".to_string()
                };
                DhCell {
                    text,
                    error: None,
                    editable,
                }
            })
        })
        .collect()
}

impl AppState {
    /// The DH table editor's cells, one row per joint (all joints, in [`Robot::joints`] order).
    pub fn dh_cells(&self) -> &[DhRowCells] {
        &self.dh
    }

    /// One cell.
    pub fn dh_cell(&self, joint: usize, field: DhField) -> Option<&DhCell> {
        self.dh.get(joint).map(|r| &r[field.index()])
    }

    /// Whether any cell holds text that is not applied.
    pub fn dh_has_errors(&self) -> bool {
        self.dh.iter().flatten().any(|c| c.error.is_some())
    }

    /// Types `text` into a cell of the DH table (display units: mm, and the angle unit; explicit
    /// units such as "pi/2", "90deg", "0.5 m" are accepted, see [`super::parse_entry`]).
    ///
    /// Every cell of that joint is re-read: the ones that parse and fit are applied to the robot
    /// at once (the arm keeps q and changes shape; targets follow the end-effectors), the others
    /// keep their text and get an error. Returns the edited cell's error, if any: not a number,
    /// NaN or infinite, lower limit above upper limit, or a cell that cannot be edited.
    pub fn edit_dh(&mut self, joint: usize, field: DhField, text: &str) -> Result<(), StateError> {
        let count = self.robot.joints().len();
        let j = self
            .robot
            .joints()
            .get(joint)
            .ok_or(StateError::NoSuchJoint {
                index: joint,
                count,
            })?;
        if let Some(why) = field.not_editable(j) {
            return Err(StateError::InvalidEntry {
                joint,
                field,
                reason: EntryError::NotEditable(why),
            });
        }
        self.dh[joint][field.index()].text = text.to_string();
        let before = self.robot.clone();
        if self.apply_joint_cells(joint) {
            self.undo.push(before);
            self.redo.clear();
            self.after_model_edit();
        }
        match &self.dh[joint][field.index()].error {
            None => Ok(()),
            Some(e) => Err(StateError::InvalidEntry {
                joint,
                field,
                reason: e.clone(),
            }),
        }
    }

    /// Parses every editable cell of joint `j` and applies what is valid. Returns whether the
    /// robot changed.
    fn apply_joint_cells(&mut self, j: usize) -> bool {
        let joint = self.robot.joints()[j].clone();
        let unit = self.angle_unit;
        let mut parsed: [Option<f64>; DH_FIELDS] = [None; DH_FIELDS];
        for f in DhField::ALL {
            let cell = &mut self.dh[j][f.index()];
            if !cell.editable {
                continue;
            }
            match parse_entry(&cell.text, f.quantity(joint.kind), unit) {
                Ok(v) => {
                    parsed[f.index()] = Some(v);
                    cell.error = None;
                }
                Err(e) => cell.error = Some(e),
            }
        }
        let get = |f: DhField| parsed[f.index()].unwrap_or_else(|| f.value(&joint));
        let mut changed = false;
        if let JointGeometry::Dh { row, .. } = joint.geometry {
            let mut new = row;
            new.a = get(DhField::A);
            new.alpha = get(DhField::Alpha);
            new.d = get(DhField::D);
            new.theta = get(DhField::Theta);
            if new != row {
                match self.robot.set_dh_row(j, new) {
                    Ok(()) => changed = true,
                    Err(e) => self.mark(
                        j,
                        &[DhField::A, DhField::Alpha, DhField::D, DhField::Theta],
                        &parsed,
                        &EntryError::Rejected(e.to_string()),
                    ),
                }
            }
        }
        let offset = get(DhField::Offset);
        let (lower, upper) = (get(DhField::Lower), get(DhField::Upper));
        let mut limits = joint.limits;
        if lower > upper {
            let q = DhField::Lower.quantity(joint.kind);
            let err = EntryError::LimitsInverted {
                lower: format!("{} {}", format_entry(lower, q, unit), q.symbol(unit)),
                upper: format!("{} {}", format_entry(upper, q, unit), q.symbol(unit)),
            };
            self.mark(j, &[DhField::Lower, DhField::Upper], &parsed, &err);
        } else {
            limits = [lower, upper];
        }
        if offset != joint.offset || limits != joint.limits {
            match self.robot.set_offset_limits(j, offset, limits) {
                Ok(()) => changed = true,
                Err(e) => self.mark(
                    j,
                    &[DhField::Offset, DhField::Lower, DhField::Upper],
                    &parsed,
                    &EntryError::Rejected(e.to_string()),
                ),
            }
        }
        changed
    }

    /// Marks the cells among `fields` that parsed (and so were about to be applied).
    fn mark(&mut self, j: usize, fields: &[DhField], parsed: &[Option<f64>], err: &EntryError) {
        for &f in fields {
            if parsed[f.index()].is_some() {
                self.dh[j][f.index()].error = Some(err.clone());
            }
        }
    }

    /// Whether an edit can be undone.
    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    /// Whether an undone edit can be redone.
    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }

    /// Whether the model differs from the one opened.
    pub fn is_edited(&self) -> bool {
        self.robot != self.opened
    }

    /// Undoes the last model edit (the DH table shows the restored values; cells in error
    /// are cleared); `false` when there is nothing to undo.
    pub fn undo_edit(&mut self) -> bool {
        let Some(previous) = self.undo.pop() else {
            return false;
        };
        let current = std::mem::replace(&mut self.robot, previous);
        self.redo.push(current);
        self.restore_cells();
        true
    }

    /// Redoes the last undone edit; `false` when there is none.
    pub fn redo_edit(&mut self) -> bool {
        let Some(next) = self.redo.pop() else {
            return false;
        };
        let current = std::mem::replace(&mut self.robot, next);
        self.undo.push(current);
        self.restore_cells();
        true
    }

    /// Back to the model as it was opened (an edit that can be undone).
    pub fn reset_edits(&mut self) {
        if !self.is_edited() && !self.dh_has_errors() {
            return;
        }
        let opened = self.opened.clone();
        let current = std::mem::replace(&mut self.robot, opened);
        self.undo.push(current);
        self.redo.clear();
        self.restore_cells();
    }

    /// After the robot was replaced by an undo, a redo or a reset: every cell formatted from it
    /// anew, the solvers and targets brought up to date.
    fn restore_cells(&mut self) {
        self.dh = build_cells(&self.robot, self.angle_unit);
        self.after_model_edit();
    }

    /// Re-formats every cell that holds no error (after a unit change or a model load); cells
    /// in error keep the user's text.
    pub(super) fn refresh_dh_cells(&mut self) {
        let fresh = build_cells(&self.robot, self.angle_unit);
        if self.dh.len() != fresh.len() {
            self.dh = fresh;
            return;
        }
        for (row, new) in self.dh.iter_mut().zip(fresh) {
            for (cell, new) in row.iter_mut().zip(new) {
                if cell.error.is_none() {
                    *cell = new;
                }
            }
        }
    }
}
