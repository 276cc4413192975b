//! Grading a DH table by what it describes, not by its numbers: an answer is right when, for
//! some sign and offset per joint variable (the freedoms DH frame choice allows: which way z_i
//! points, where x_i points), its forward kinematics from the figure's base frame to its tool
//! frame is the reference's for every q. Either convention is accepted.
//!
//! How: by the product of exponentials, FK(q) = exp(xi_1 q_1) ... exp(xi_n q_n) M, two chains
//! agree for all q exactly when their joint axes (as lines, each up to its direction, which is
//! the variable's sign) and their tool frames agree at one configuration each. The reference is
//! taken at q = 0; the answer's configuration `delta` (the offsets) is found joint by joint: the
//! axis of joint k must coincide with the reference's, then joint k is turned (or slid) until
//! the axis of joint k + 1 (for the last joint: the tool frame) coincides too; where two
//! values do that, both are followed. Where an axis cannot be made to coincide, the row that
//! places it is wrong; single-parameter repairs (a sign, a right angle, a swapped a and d) say
//! which parameter, and grading goes on with the repaired row.

use super::Mistake;
use crate::kinematics::{Convention, DhJoint, JointKind, Pose, Robot};
use nalgebra::Vector3;
use std::f64::consts::{FRAC_PI_2, PI};

/// Tolerances of the comparison (typed answers round: `1.5708` for pi/2).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Tolerance {
    /// Distances between axes and tool origins (m).
    pub length: f64,
    /// Angles between axes and tool orientations (rad).
    pub angle: f64,
}

impl Default for Tolerance {
    fn default() -> Self {
        Self {
            length: 1e-3,
            angle: 1e-3,
        }
    }
}

/// The verdict on one row.
#[derive(Debug, Clone, PartialEq)]
pub struct RowVerdict {
    /// The row (1-based).
    pub row: usize,
    /// Whether the row places its frame where the figure's arm has it.
    pub correct: bool,
    /// What is wrong in words, or how the answer's variable relates to the figure's.
    pub feedback: String,
    /// The mistake, named (None where the row is right or was not graded).
    pub mistake: Option<Mistake>,
}

/// The verdict on a DH-table answer.
#[derive(Debug, Clone, PartialEq)]
pub struct DhVerdict {
    /// Per row.
    pub rows: Vec<RowVerdict>,
    /// Whether the answer describes the same arm (every row correct).
    pub equivalent: bool,
    /// For an equivalent answer: per joint, (sign, offset) with `q_answer = sign * q + offset`
    /// (rad or m).
    pub mapping: Option<Vec<(f64, f64)>>,
}

/// One joint axis in the world frame: a line for a revolute joint, a direction for a
/// prismatic one (its position does not change the motion).
#[derive(Debug, Clone, Copy)]
struct Axis {
    dir: Vector3<f64>,
    point: Vector3<f64>,
    revolute: bool,
}

/// The joint axes of `robot` (end-effector 0) at `q`, from its geometric Jacobian: a revolute
/// column `[w x (p_e - p); w]` gives the foot `p_e + w x v`.
fn axes(robot: &Robot, q: &[f64]) -> Option<(Vec<Axis>, Pose)> {
    let jac = robot.jacobian(q, 0).ok()?;
    let tool = robot.fk_ee(q, 0).ok()?;
    let pe = tool.translation.vector;
    let out = (0..robot.dof())
        .map(|k| {
            let col = jac.column(k);
            let v = Vector3::new(col[0], col[1], col[2]);
            let w = Vector3::new(col[3], col[4], col[5]);
            if robot.dof_joint(k).kind == JointKind::Revolute {
                Axis {
                    dir: w,
                    point: pe + w.cross(&v),
                    revolute: true,
                }
            } else {
                Axis {
                    dir: v,
                    point: pe,
                    revolute: false,
                }
            }
        })
        .collect();
    Some((out, tool))
}

/// How far two axes are from coinciding: (angle between the directions up to sign, rad;
/// distance between the lines, m; 0 for a prismatic axis).
fn mismatch(a: &Axis, b: &Axis) -> (f64, f64) {
    let cross = a.dir.cross(&b.dir);
    let angle = cross.norm().asin();
    if !a.revolute || !b.revolute {
        return (angle, 0.0);
    }
    let w = b.point - a.point;
    let dist = if cross.norm() < 1e-9 {
        w.cross(&a.dir).norm()
    } else {
        (w.dot(&cross) / cross.norm()).abs().max(
            // nearly parallel lines: the perpendicular offset dominates
            if cross.norm() < 1e-3 {
                w.cross(&a.dir).norm()
            } else {
                0.0
            },
        )
    };
    (angle, dist)
}

/// How far two tool frames are apart: (rotation, rad-like; position, m).
fn tool_mismatch(a: &Pose, b: &Pose) -> (f64, f64) {
    let r = (a.rotation.matrix() - b.rotation.matrix()).abs().max();
    let p = (a.translation.vector - b.translation.vector).norm();
    (r, p)
}

/// The reference's axes and tool at q = 0, and the tolerances, for the search.
struct Target<'a> {
    reference: &'a Robot,
    axes: Vec<Axis>,
    tool: Pose,
    tol: Tolerance,
    scale: f64,
}

impl Target<'_> {
    fn fits(&self, (angle, dist): (f64, f64)) -> bool {
        angle <= self.tol.angle && dist <= self.tol.length
    }

    /// One number for the 1-D searches: angle plus distance over the arm's size.
    fn cost(&self, (angle, dist): (f64, f64)) -> f64 {
        angle + dist / self.scale
    }

    /// The check behind the theory: with each variable's sign and offset, the answer's FK is
    /// the reference's at spread joint vectors (ten times the tolerances).
    fn same_motion(&self, answer: &Robot, delta: &[f64]) -> bool {
        let Some((ax, _)) = axes(answer, delta) else {
            return false;
        };
        let signs: Vec<f64> = ax
            .iter()
            .zip(&self.axes)
            .map(|(a, r)| a.dir.dot(&r.dir).signum())
            .collect();
        (1..=6u32).all(|trial| {
            let q: Vec<f64> = (0..delta.len())
                .map(|k| ((trial * 7 + k as u32 * 3) % 11) as f64 * 0.23 - 1.1)
                .collect();
            let q_answer: Vec<f64> = q
                .iter()
                .zip(&signs)
                .zip(delta)
                .map(|((x, s), d)| s * x + d)
                .collect();
            match (self.reference.fk_ee(&q, 0), answer.fk_ee(&q_answer, 0)) {
                (Ok(a), Ok(b)) => {
                    let (r, p) = tool_mismatch(&a, &b);
                    r <= 10.0 * self.tol.angle && p <= 10.0 * self.tol.length
                }
                _ => false,
            }
        })
    }

    /// The misfit of the feature that joint `k`'s value places: axis k + 1, or the tool.
    fn feature(&self, answer: &Robot, delta: &[f64], k: usize) -> Option<(f64, f64)> {
        let (ax, tool) = axes(answer, delta)?;
        Some(if k + 1 < self.axes.len() {
            mismatch(&ax[k + 1], &self.axes[k + 1])
        } else {
            tool_mismatch(&tool, &self.tool)
        })
    }
}

/// Where the search got: the joint values so far and the deepest level reached.
struct Search {
    deepest: usize,
    found: Option<Vec<f64>>,
}

/// The values of joint `k` that bring the next feature into place (revolute: a scan of the
/// turn with each dip refined; prismatic: the slide that closes the gap).
fn candidates(t: &Target, answer: &Robot, delta: &[f64], k: usize) -> Vec<f64> {
    let mut d = delta.to_vec();
    let mut misfit = |v: f64| {
        d[k] = v;
        t.feature(answer, &d, k)
            .map_or(f64::INFINITY, |m| t.cost(m))
    };
    if answer.dof_joint(k).kind == JointKind::Prismatic {
        return prismatic_candidate(t, answer, delta, k)
            .into_iter()
            .collect();
    }
    const STEPS: usize = 144;
    let ts: Vec<f64> = (0..STEPS)
        .map(|i| -PI + 2.0 * PI * i as f64 / STEPS as f64)
        .collect();
    let ms: Vec<f64> = ts.iter().map(|&v| misfit(v)).collect();
    let small = t.cost((t.tol.angle, t.tol.length));
    if ms.iter().all(|&m| m <= small) {
        // the feature turns about this axis's own line (coincident axes): any value will do
        return vec![0.0];
    }
    let mut out: Vec<f64> = Vec::new();
    for i in 0..STEPS {
        let (prev, next) = (ms[(i + STEPS - 1) % STEPS], ms[(i + 1) % STEPS]);
        if ms[i] <= prev && ms[i] <= next && ms[i] < 0.5 {
            let v = golden(
                &mut misfit,
                ts[i] - 2.0 * PI / STEPS as f64,
                ts[i] + 2.0 * PI / STEPS as f64,
            );
            if misfit(v) <= small && !out.iter().any(|&o| (o - v).abs() < 1e-6) {
                out.push(v);
            }
        }
    }
    // the smallest offsets first: a table like the figure's maps each q to itself
    out.sort_by(|a, b| a.abs().total_cmp(&b.abs()));
    out
}

/// Golden-section minimum of `f` on `[lo, hi]`.
fn golden(f: &mut impl FnMut(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..60 {
        let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if f(x1) < f(x2) {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    0.5 * (lo + hi)
}

/// The slide of prismatic joint `k` that brings the next axis (least squares on the lines'
/// offset) or the tool origin into place.
fn prismatic_candidate(t: &Target, answer: &Robot, delta: &[f64], k: usize) -> Option<f64> {
    let (ax, tool) = axes(answer, delta)?;
    let u = ax[k].dir;
    let slide = if k + 1 < t.axes.len() {
        let (a, r) = (&ax[k + 1], &t.axes[k + 1]);
        let w = r.point - a.point;
        let uz = u.cross(&a.dir);
        if uz.norm() < 1e-9 || !a.revolute {
            0.0
        } else {
            w.cross(&a.dir).dot(&uz) / uz.norm_squared()
        }
    } else {
        u.dot(&(t.tool.translation.vector - tool.translation.vector))
    };
    let mut d = delta.to_vec();
    d[k] += slide;
    let m = t.feature(answer, &d, k)?;
    t.fits(m).then_some(d[k])
}

/// Depth-first search over the joints: axis k must coincide, then each value of joint k that
/// places the next feature is followed.
fn search(t: &Target, answer: &Robot, delta: &mut Vec<f64>, k: usize, out: &mut Search) {
    if out.found.is_some() {
        return;
    }
    let Some((ax, _)) = axes(answer, delta) else {
        return;
    };
    if ax[k].revolute != t.axes[k].revolute || !t.fits(mismatch(&ax[k], &t.axes[k])) {
        out.deepest = out.deepest.max(k);
        return;
    }
    out.deepest = out.deepest.max(k + 1);
    for v in candidates(t, answer, delta, k) {
        delta[k] = v;
        if k + 1 == t.axes.len() {
            if t.same_motion(answer, delta) {
                out.deepest = t.axes.len() + 1;
                out.found = Some(delta.clone());
                return;
            }
            continue;
        }
        search(t, answer, delta, k + 1, out);
        if out.found.is_some() {
            return;
        }
    }
    delta[k] = 0.0;
}

/// Runs the search; `Ok(offsets)` or `Err(level)`: the first feature that could not be placed
/// (k < n: the axis of joint k + 1; n: the tool frame).
fn place(t: &Target, answer: &Robot) -> Result<Vec<f64>, usize> {
    let mut out = Search {
        deepest: 0,
        found: None,
    };
    let mut delta = vec![0.0; answer.dof()];
    search(t, answer, &mut delta, 0, &mut out);
    match out.found {
        Some(d) => Ok(d),
        // deepest = k: axis k did not fit, or (k + 1 on a fit) no value of joint k placed the
        // next feature; either way feature `deepest` is the one not placed
        None => Err(out.deepest),
    }
}

impl DhVerdict {
    /// The whole answer wrong for one reason (given on row 1).
    fn wrong(feedback: String, mistake: Option<Mistake>) -> Self {
        DhVerdict {
            rows: vec![RowVerdict {
                row: 1,
                correct: false,
                feedback,
                mistake,
            }],
            equivalent: false,
            mapping: None,
        }
    }
}

/// A serial DH robot from a table (convention, rows), base and tool identity.
fn robot_from(conv: Convention, rows: &[DhJoint]) -> Option<Robot> {
    Robot::from_dh("answer", conv, rows, Pose::identity(), Pose::identity()).ok()
}

/// One candidate repair of a row: what it changes and how to say it.
struct Repair {
    rows: Vec<DhJoint>,
    feedback: String,
    mistake: Mistake,
}

/// Single-parameter changes of row `r` (0-based) that a student's slip would explain.
fn repairs(conv: Convention, rows: &[DhJoint], r: usize, reference: &[DhJoint]) -> Vec<Repair> {
    let i = r + 1;
    let j = match conv {
        Convention::Standard => i,
        Convention::Modified => i - 1,
    };
    let mut out = Vec::new();
    let mut push = |change: &dyn Fn(&mut DhJoint), feedback: String, mistake: Mistake| {
        let mut rs = rows.to_vec();
        change(&mut rs[r]);
        out.push(Repair {
            rows: rs,
            feedback,
            mistake,
        });
    };
    let reference_row = reference.get(r).map(|d| d.row);
    let turn = format!("z{} turns into z{} the other way", i - 1, i);
    push(
        &|d| d.row.alpha = -d.row.alpha,
        format!("row {i}: alpha{j} has the wrong sign: {turn}"),
        Mistake::AlphaSign,
    );
    let d_axis = match conv {
        Convention::Standard => format!("z{}", i - 1),
        Convention::Modified => format!("z{i}"),
    };
    push(
        &|d| d.row.a = -d.row.a,
        format!(
            "row {i}: a{j} has the wrong sign: it is measured along x{j}, from z{} to z{i}",
            i - 1
        ),
        Mistake::ASign,
    );
    push(
        &|d| d.row.d = -d.row.d,
        format!(
            "row {i}: d{i} has the wrong sign: it is measured along {d_axis}, from x{} to x{i}",
            i - 1
        ),
        Mistake::DSign,
    );
    push(
        &|d| std::mem::swap(&mut d.row.a, &mut d.row.d),
        format!("row {i}: a{j} and d{i} are swapped"),
        Mistake::ASwappedWithD,
    );
    for delta in [FRAC_PI_2, -FRAC_PI_2, PI] {
        push(
            &move |d| d.row.alpha += delta,
            format!(
                "row {i}: alpha{j} is wrong: it is the angle from z{} to z{i} about x{j}",
                i - 1
            ),
            Mistake::AlphaWrong,
        );
    }
    out.extend(length_repairs(rows, r, reference_row, i, j, &d_axis));
    out
}

/// Changes of row `r`'s a or d to zero or to the reference's value (either sign).
fn length_repairs(
    rows: &[DhJoint],
    r: usize,
    reference_row: Option<crate::kinematics::DhRow>,
    i: usize,
    j: usize,
    d_axis: &str,
) -> Vec<Repair> {
    let row = rows[r].row;
    let mut out = Vec::new();
    for (value, what) in [
        (0.0, "a"),
        (reference_row.map_or(row.a, |r| r.a), "a"),
        (reference_row.map_or(row.a, |r| -r.a), "a"),
        (reference_row.map_or(row.d, |r| r.d), "d"),
        (reference_row.map_or(row.d, |r| -r.d), "d"),
        (0.0, "d"),
    ] {
        let text = if what == "a" {
            format!(
                "row {i}: a{j} is wrong: it is the distance from z{} to z{i} along their common normal x{j}",
                i - 1
            )
        } else {
            format!(
                "row {i}: d{i} is wrong: it is the distance along {d_axis} from x{} to x{i}",
                i - 1
            )
        };
        let mut rs = rows.to_vec();
        {
            let d = &mut rs[r];
            {
                if what == "a" {
                    d.row.a = value
                } else {
                    d.row.d = value
                }
            }
        }
        out.push(Repair {
            rows: rs,
            feedback: text,
            mistake: if what == "a" {
                Mistake::AWrong
            } else {
                Mistake::DWrong
            },
        });
    }
    out
}

/// The rows that place feature `level` (the axis of joint level + 1, or the tool at n).
fn responsible_rows(conv: Convention, level: usize, n: usize) -> Vec<usize> {
    let mut rows = match conv {
        // z_k is placed by row k (1-based) = index k - 1
        Convention::Standard => vec![level.saturating_sub(1)],
        // z_k is placed by row k+1's a_k, alpha_k and by row k's d_k
        Convention::Modified => vec![level.min(n - 1), level.saturating_sub(1)],
    };
    rows.dedup();
    rows
}

/// Grades `answer` (a DH model) against `reference`: both with their base and end-effector 0.
pub fn check(reference: &Robot, answer: &Robot, tol: Tolerance) -> DhVerdict {
    let n = reference.dof();
    if answer.dof() != n {
        return DhVerdict::wrong(
            format!(
                "the answer has {} joint variables, the arm in the figure has {n}",
                answer.dof()
            ),
            Some(Mistake::JointCount),
        );
    }
    let Some((conv, table)) = answer.dh_table() else {
        return DhVerdict::wrong(
            "the answer is not a serial DH table".into(),
            Some(Mistake::NotDhTable),
        );
    };
    let mut rows: Vec<DhJoint> = table
        .iter()
        .map(|(kind, row, off)| DhJoint::new(*kind, *row).offset(*off).unbounded())
        .collect();
    let reference_rows: Vec<DhJoint> = reference
        .dh_table()
        .filter(|(c, _)| *c == conv)
        .map(|(_, t)| t.iter().map(|(k, r, _)| DhJoint::new(*k, *r)).collect())
        .unwrap_or_default();
    let Some((ref_axes, ref_tool)) = axes(reference, &vec![0.0; n]) else {
        return DhVerdict::wrong("the reference arm cannot be evaluated".into(), None);
    };
    let target = Target {
        reference,
        axes: ref_axes,
        tool: ref_tool,
        tol,
        scale: reference.characteristic_length().max(1e-3),
    };
    let mut verdicts = fix_joint_kinds(&mut rows, &target);
    let mut ungraded_from = None;
    let mut mapping = None;
    for _ in 0..=2 * n {
        let Some(robot) = robot_from(conv, &rows) else {
            ungraded_from = Some(0);
            break;
        };
        match place(&target, &robot) {
            Ok(delta) => {
                mapping = Some(signs_and_offsets(&target, &robot, &delta));
                break;
            }
            Err(level) => {
                let fixed = explain(&target, conv, &rows, &reference_rows, level);
                match fixed {
                    Some((r, rep)) => {
                        verdicts[r].get_or_insert((rep.feedback, rep.mistake));
                        rows = rep.rows;
                    }
                    None => {
                        let r = responsible_rows(conv, level, n)[0];
                        verdicts[r].get_or_insert((unplaced(level, n), Mistake::Unplaced));
                        ungraded_from = Some(r + 1);
                        break;
                    }
                }
            }
        }
    }
    let row_verdicts = row_verdicts(&verdicts, ungraded_from, mapping.as_deref(), &rows);
    let equivalent = row_verdicts.iter().all(|v| v.correct);
    DhVerdict {
        rows: row_verdicts,
        equivalent,
        mapping: if equivalent { mapping } else { None },
    }
}

/// The verdicts per row: wrong with what was said, not graded after a row that could not be
/// explained, otherwise right (saying how the variable maps where frames differ).
fn row_verdicts(
    verdicts: &[Option<(String, Mistake)>],
    ungraded_from: Option<usize>,
    mapping: Option<&[(f64, f64)]>,
    rows: &[DhJoint],
) -> Vec<RowVerdict> {
    (0..verdicts.len())
        .map(|r| match (&verdicts[r], ungraded_from) {
            (Some((f, mistake)), _) => RowVerdict {
                row: r + 1,
                correct: false,
                feedback: f.clone(),
                mistake: Some(*mistake),
            },
            (None, Some(u)) if r >= u => RowVerdict {
                row: r + 1,
                correct: false,
                feedback: format!(
                    "row {}: not graded: the rows before it must be right first",
                    r + 1
                ),
                mistake: None,
            },
            (None, _) => RowVerdict {
                row: r + 1,
                correct: true,
                feedback: mapping.map_or(String::new(), |m| describe_mapping(r, m[r], &rows[r])),
                mistake: None,
            },
        })
        .collect()
}

/// Rows whose joint type differs from the figure's get that type (and a verdict saying so),
/// so that the rest of the table can still be graded.
fn fix_joint_kinds(rows: &mut [DhJoint], target: &Target) -> Vec<Option<(String, Mistake)>> {
    let mut verdicts: Vec<Option<(String, Mistake)>> = vec![None; rows.len()];
    for (r, (ours, theirs)) in rows.iter_mut().zip(&target.axes).enumerate() {
        let figure_revolute = theirs.revolute;
        if (ours.kind == JointKind::Revolute) != figure_revolute {
            let kind = if figure_revolute {
                "revolute"
            } else {
                "prismatic"
            };
            verdicts[r] = Some((
                format!("row {}: joint {} is {kind} in the figure", r + 1, r + 1),
                Mistake::JointKind,
            ));
            *ours = DhJoint::new(
                if figure_revolute {
                    JointKind::Revolute
                } else {
                    JointKind::Prismatic
                },
                ours.row,
            )
            .unbounded();
        }
    }
    verdicts
}

/// The repair that explains a failure at `level`: first one change that makes the whole table
/// right, tried in the rows that place the feature, then in the rows before them (nearest
/// first), else a change of a responsible row that gets the search further.
fn explain(
    target: &Target,
    conv: Convention,
    rows: &[DhJoint],
    reference_rows: &[DhJoint],
    level: usize,
) -> Option<(usize, Repair)> {
    let n = rows.len();
    let responsible = responsible_rows(conv, level, n);
    let last = responsible.iter().copied().max().unwrap_or(0);
    let progress = |rep: &Repair, full: bool| {
        robot_from(conv, &rep.rows).is_some_and(|rb| match place(target, &rb) {
            Ok(_) => true,
            Err(l) => !full && l > level,
        })
    };
    // every single change of the rows that place the feature, then of the rows before them
    // (nearest first); those that give a row the reference's values first: when a table
    // differs from the reference by one slip, that slip is what is named
    let order: Vec<usize> = responsible
        .iter()
        .copied()
        .chain((0..=last).rev())
        .collect();
    let restores = |r: usize, rep: &Repair| {
        reference_rows
            .get(r)
            .is_some_and(|want| same_row(&rep.rows[r], want, target.tol))
    };
    let mut all: Vec<(bool, usize, usize, Repair)> = Vec::new();
    for (rank, &r) in order.iter().enumerate() {
        for rep in repairs(conv, rows, r, reference_rows) {
            all.push((!restores(r, &rep), rank, r, rep));
        }
    }
    all.sort_by_key(|(not_restoring, rank, _, _)| (*not_restoring, *rank));
    if let Some(i) = all.iter().position(|(_, _, _, rep)| progress(rep, true)) {
        let (_, _, r, rep) = all.swap_remove(i);
        return Some((r, rep));
    }
    all.into_iter()
        .filter(|(_, _, r, _)| responsible.contains(r))
        .find(|(_, _, _, rep)| progress(rep, false))
        .map(|(_, _, r, rep)| (r, rep))
}

/// Whether two rows have the same a, alpha, d (within the tolerances).
fn same_row(a: &DhJoint, b: &DhJoint, tol: Tolerance) -> bool {
    (a.row.a - b.row.a).abs() <= tol.length
        && (a.row.d - b.row.d).abs() <= tol.length
        && (a.row.alpha - b.row.alpha).abs() <= tol.angle
}

/// Why a feature could not be placed, when no single repair explains it.
fn unplaced(level: usize, n: usize) -> String {
    if level >= n {
        format!("row {n}: the last frame is not the tool frame of the figure")
    } else if level == 0 {
        "row 1: z0 must lie along the axis of joint 1, with frame 0 the figure's base frame".into()
    } else {
        format!(
            "row {level}: z{level} (the axis of joint {}) is not where this row puts it",
            level + 1
        )
    }
}

/// Per joint, the sign (the answer's axis against the figure's) and the offset (the answer's
/// value when the figure's arm is at q = 0).
fn signs_and_offsets(t: &Target, answer: &Robot, delta: &[f64]) -> Vec<(f64, f64)> {
    let ax = axes(answer, delta).map(|(a, _)| a).unwrap_or_default();
    t.axes
        .iter()
        .zip(&ax)
        .zip(delta)
        .map(|((r, a), d)| (r.dir.dot(&a.dir).signum(), *d))
        .collect()
}

/// "q3 here is -q3 + 90 deg of the figure's arm" for a correct row whose frames differ.
fn describe_mapping(r: usize, (sign, offset): (f64, f64), row: &DhJoint) -> String {
    let k = r + 1;
    let revolute = row.kind == JointKind::Revolute;
    let off = if revolute {
        format!("{:+.1} deg", offset.to_degrees())
    } else {
        format!("{:+.4} m", offset)
    };
    match (sign < 0.0, offset.abs() > 1e-9) {
        (false, false) => "right".into(),
        (true, false) => format!("right, with z{} the other way: your q{k} = -q{k}", k - 1),
        (false, true) => format!("right, with another x axis: your q{k} = q{k} {off}"),
        (true, true) => format!("right, with other frames: your q{k} = -q{k} {off}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::DhRow;

    fn arm(rows: &[(f64, f64, f64)]) -> Robot {
        let joints: Vec<DhJoint> = rows
            .iter()
            .map(|&(a, alpha, d)| {
                DhJoint::revolute(DhRow {
                    a,
                    alpha,
                    d,
                    theta: 0.0,
                })
            })
            .collect();
        robot_from(Convention::Standard, &joints).unwrap()
    }

    /// Table 2.7's arm (anthropomorphic arm with spherical wrist), a2 = d4 = 0.5, d6 = 0.1.
    fn wrist_arm(alpha1: f64, alpha3: f64, d4: f64) -> Robot {
        arm(&[
            (0.0, alpha1, 0.0),
            (0.5, 0.0, 0.0),
            (0.0, alpha3, 0.0),
            (0.0, -FRAC_PI_2, d4),
            (0.0, FRAC_PI_2, 0.0),
            (0.0, 0.0, 0.1),
        ])
    }

    #[test]
    fn other_valid_frames_are_right_and_a_wrong_sign_is_named() {
        let reference = wrist_arm(FRAC_PI_2, FRAC_PI_2, 0.5);
        assert!(check(&reference, &reference, Tolerance::default()).equivalent);
        // x1 the other way: alpha1 = -pi/2 with q1, q2 offset by pi is the same arm
        let v = check(
            &reference,
            &wrist_arm(-FRAC_PI_2, FRAC_PI_2, 0.5),
            Tolerance::default(),
        );
        assert!(v.equivalent, "{v:?}");
        // d6 the other way moves the tool frame: a real error, named
        let mut wrong = arm(&[
            (0.0, FRAC_PI_2, 0.0),
            (0.5, 0.0, 0.0),
            (0.0, FRAC_PI_2, 0.0),
            (0.0, -FRAC_PI_2, 0.5),
            (0.0, FRAC_PI_2, 0.0),
            (0.0, 0.0, -0.1),
        ]);
        let v = check(&reference, &wrong, Tolerance::default());
        assert!(!v.equivalent, "{v:?}");
        assert_eq!(
            v.rows[5].feedback,
            "row 6: d6 has the wrong sign: it is measured along z5, from x5 to x6"
        );
        wrong = arm(&[(0.0, FRAC_PI_2, 0.0)]);
        assert!(!check(&reference, &wrong, Tolerance::default()).equivalent);
    }
}
