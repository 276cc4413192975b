//! From the spanned TOML tree to a [`Robot`], checking the schema field by field.

use super::error::{CoupleProblem, ModelFileError as E, NameKind};
use super::value::{Ctx, Res, Span, Table, Val};
use crate::kinematics::pose::Pose;
use crate::kinematics::{
    Convention, DhRow, DisabledPair, Drive, EndEffector, Joint, JointGeometry, JointKind,
    ModelError, NamedConfig, PointMass, Robot,
};
use nalgebra::Vector3;
use std::collections::HashMap;
use std::f64::consts::PI;
use toml::de::DeTable;

const TOP_KEYS: &[&str] = &[
    "name",
    "description",
    "convention",
    "base",
    "tool",
    "joints",
    "end_effectors",
    "configurations",
    "disable_collisions",
];
const JOINT_KEYS: &[&str] = &[
    "type", "a", "alpha", "d", "theta", "offset", "limits", "name", "parent", "pre", "couple",
    "mass", "com",
];
const EE_KEYS: &[&str] = &["name", "parent", "tool"];
const CONFIG_KEYS: &[&str] = &["name", "q"];
const DISABLE_KEYS: &[&str] = &["link1", "link2", "reason"];

/// Names already used in one list: name -> (index, line of first use).
type Names = HashMap<String, (usize, usize)>;

/// Parses and validates a whole model file.
pub(super) fn build(ctx: &Ctx) -> Res<Robot> {
    let doc = DeTable::parse(ctx.text).map_err(|e| E::Syntax {
        message: e.message().to_string(),
        at: ctx.at(&e.span().unwrap_or(0..0)),
    })?;
    let top = Table {
        table: doc.get_ref(),
        span: doc.span(),
        field: String::new(),
    };
    top.check_keys(ctx, TOP_KEYS)?;
    let name = ctx.string("name", top.required(ctx, "name")?)?;
    let description = match top.get("description") {
        Some(v) => ctx.string("description", v)?,
        None => "",
    };
    let conv_v = top.required(ctx, "convention")?;
    let convention = match ctx.string("convention", conv_v)? {
        "standard" => Convention::Standard,
        "modified" => Convention::Modified,
        other => {
            return Err(E::UnknownConvention {
                field: "convention".into(),
                value: other.into(),
                at: ctx.at(&conv_v.span()),
            });
        }
    };
    let base = optional_pose(ctx, &top, "base")?;
    let tool = optional_pose(ctx, &top, "tool")?;
    let joints_v = top.required(ctx, "joints")?;
    let tables = top.tables(ctx, "joints")?;
    if tables.is_empty() {
        return Err(E::EmptyJoints {
            field: "joints".into(),
            at: ctx.at(&joints_v.span()),
        });
    }
    let mut joints: Vec<Joint> = Vec::with_capacity(tables.len());
    let mut names = Names::new();
    let mut masses = Vec::new();
    for (i, t) in tables.iter().enumerate() {
        let j = joint(ctx, t, i, tables.len(), convention, &joints, &mut names)?;
        joints.push(j);
        masses.extend(point_mass(ctx, t, i)?);
    }
    let ees = end_effectors(ctx, &top, &names, joints.len(), tool)?;
    let mut robot = Robot::new(name, base, joints, ees)
        .map_err(|e| model_error(ctx, e, &tables, top.key_span("joints")))?
        .with_description(description);
    robot.masses = masses;
    configurations(ctx, &top, &mut robot)?;
    robot.disabled_collisions = disabled_collisions(ctx, &top, robot.joints().len())?;
    Ok(robot)
}

/// The names collision reports give a model file's links: "base", then "link1".."linkN", link
/// i moving with joint i (file order, fixed joints included), as `crate::collision` names the
/// links of a robot without a URDF's link names.
fn link_names(joints: usize) -> Vec<String> {
    std::iter::once("base".to_string())
        .chain((1..=joints).map(|i| format!("link{i}")))
        .collect()
}

/// The stored allowed-collision matrix: `[[disable_collisions]]` tables with `link1`, `link2`
/// (links of this robot, see [`link_names`]) and `reason` (optional, default "User"; MoveIt's
/// words "Adjacent", "Always", "Default", "Never" or the user's own).
fn disabled_collisions(ctx: &Ctx, top: &Table, joints: usize) -> Res<Vec<DisabledPair>> {
    let links = link_names(joints);
    let mut out = Vec::new();
    for t in top.tables(ctx, "disable_collisions")? {
        t.check_keys(ctx, DISABLE_KEYS)?;
        let mut pair = [String::new(), String::new()];
        for (slot, key) in pair.iter_mut().zip(["link1", "link2"]) {
            let v = t.required(ctx, key)?;
            let name = ctx.string(&t.path(key), v)?;
            if !links.iter().any(|l| l == name) {
                return Err(E::UnknownLink {
                    field: t.path(key),
                    name: name.into(),
                    available: links.join(", "),
                    at: ctx.at(&v.span()),
                });
            }
            *slot = name.to_string();
        }
        if pair[0] == pair[1] {
            return Err(E::NotApplicable {
                field: t.path("link2"),
                reason: "a link is never checked against itself: name two different links",
                at: ctx.at(&t.key_span("link2")),
            });
        }
        let reason = match t.get("reason") {
            Some(v) => ctx.string(&t.path("reason"), v)?.to_string(),
            None => "User".to_string(),
        };
        let [link1, link2] = pair;
        out.push(DisabledPair {
            link1,
            link2,
            reason,
        });
    }
    Ok(out)
}

/// The link's mass (`mass`, kg, >= 0) at its centre of mass (`com`, m in the joint's frame;
/// default the frame's origin), if the joint gives one.
fn point_mass(ctx: &Ctx, t: &Table, i: usize) -> Res<Option<PointMass>> {
    let Some(v) = t.get("mass") else {
        if t.get("com").is_some() {
            return Err(t.missing(ctx, "mass"));
        }
        return Ok(None);
    };
    let mass = ctx.number(&t.path("mass"), v)?;
    if mass < 0.0 {
        return Err(ctx.wrong_type(&t.path("mass"), "a mass >= 0 (kg)", v));
    }
    let com = match t.get("com") {
        Some(c) => {
            let a = ctx.array_n(&t.path("com"), c, 3, "[x, y, z] in metres")?;
            let mut xyz = [0.0; 3];
            for (k, e) in a.iter().enumerate() {
                xyz[k] = ctx.number(&format!("{}[{k}]", t.path("com")), e)?;
            }
            Vector3::from(xyz)
        }
        None => Vector3::zeros(),
    };
    Ok(Some(PointMass {
        joint: Some(i),
        com,
        mass,
    }))
}

fn optional_pose(ctx: &Ctx, t: &Table, key: &str) -> Res<Pose> {
    t.get(key)
        .map_or(Ok(Pose::identity()), |v| ctx.pose(&t.path(key), v))
}

/// Records `name` (at `span`) in `names`, rejecting a duplicate.
fn unique_name(
    ctx: &Ctx,
    names: &mut Names,
    kind: NameKind,
    field: String,
    name: &str,
    index: usize,
    span: &Span,
) -> Res<()> {
    let at = ctx.at(span);
    if let Some(&(_, first_line)) = names.get(name) {
        return Err(E::DuplicateName {
            field,
            kind,
            name: name.into(),
            first_line,
            at,
        });
    }
    names.insert(name.into(), (index, at.line));
    Ok(())
}

/// A field that must be absent for this kind of joint.
fn reject(ctx: &Ctx, t: &Table, key: &str, reason: &'static str) -> Res<()> {
    match t.get(key) {
        None => Ok(()),
        Some(_) => Err(not_applicable(ctx, t, key, reason)),
    }
}

/// A field that must be absent or zero for this kind of joint (`angular`: an angle, else m).
fn reject_nonzero(ctx: &Ctx, t: &Table, key: &str, angular: bool, reason: &'static str) -> Res<()> {
    match t.get(key) {
        Some(v) if ctx.scalar(&t.path(key), v, angular)? != 0.0 => {
            Err(not_applicable(ctx, t, key, reason))
        }
        _ => Ok(()),
    }
}

fn not_applicable(ctx: &Ctx, t: &Table, key: &str, reason: &'static str) -> E {
    E::NotApplicable {
        field: t.path(key),
        reason,
        at: ctx.at(&t.key_span(key)),
    }
}

/// Joint `i` (0-based) of `count` from its `[[joints]]` table; `earlier` are the joints before
/// it and `names` their names (this joint's is added).
fn joint(
    ctx: &Ctx,
    t: &Table,
    i: usize,
    count: usize,
    convention: Convention,
    earlier: &[Joint],
    names: &mut Names,
) -> Res<Joint> {
    t.check_keys(ctx, JOINT_KEYS)?;
    let kind = joint_kind(ctx, t)?;
    let row = dh_row(ctx, t, kind)?;
    let (offset, limits) = joint_variable(ctx, t, kind)?;
    let (name, name_span) = joint_name(ctx, t, i)?;
    let parent = joint_parent(ctx, t, i, names)?;
    unique_name(
        ctx,
        names,
        NameKind::Joint,
        t.path("name"),
        &name,
        i,
        &name_span,
    )?;
    let pre = optional_pose(ctx, t, "pre")?;
    let drive = joint_drive(ctx, t, kind, i, count, earlier)?;
    Ok(Joint {
        name,
        kind,
        parent,
        pre,
        geometry: JointGeometry::Dh { row, convention },
        offset,
        drive,
        limits,
    })
}

/// The joint's `type`: revolute, prismatic or fixed.
fn joint_kind(ctx: &Ctx, t: &Table) -> Res<JointKind> {
    let type_v = t.required(ctx, "type")?;
    Ok(match ctx.string(&t.path("type"), type_v)? {
        "revolute" => JointKind::Revolute,
        "prismatic" => JointKind::Prismatic,
        "fixed" => JointKind::Fixed,
        other => {
            return Err(E::UnknownJointType {
                field: t.path("type"),
                value: other.into(),
                at: ctx.at(&type_v.span()),
            });
        }
    })
}

/// The DH row: `a` and `alpha` required; `d` required unless prismatic (then its variable, absent
/// or zero); `theta` absent or zero for a revolute joint (its variable), else 0 by default.
fn dh_row(ctx: &Ctx, t: &Table, kind: JointKind) -> Res<DhRow> {
    let a = ctx.number(&t.path("a"), t.required(ctx, "a")?)?;
    let alpha = ctx.angle(&t.path("alpha"), t.required(ctx, "alpha")?)?;
    let d = match (kind, t.get("d")) {
        (JointKind::Prismatic, _) => {
            reject_nonzero(ctx, t, "d", false, PRISMATIC_D)?;
            0.0
        }
        (_, Some(v)) => ctx.number(&t.path("d"), v)?,
        (_, None) => return Err(t.missing(ctx, "d")),
    };
    let theta = match (kind, t.get("theta")) {
        (JointKind::Revolute, _) => {
            reject_nonzero(ctx, t, "theta", true, REVOLUTE_THETA)?;
            0.0
        }
        (_, Some(v)) => ctx.angle(&t.path("theta"), v)?,
        (_, None) => 0.0,
    };
    Ok(DhRow { a, alpha, d, theta })
}

/// `offset` and `limits` of the joint variable (a fixed joint takes neither, nor `couple`);
/// limits default to [-pi, pi] for a revolute joint and are required for a prismatic one.
fn joint_variable(ctx: &Ctx, t: &Table, kind: JointKind) -> Res<(f64, [f64; 2])> {
    let revolute = kind == JointKind::Revolute;
    if kind == JointKind::Fixed {
        reject(ctx, t, "offset", FIXED_NO_VARIABLE)?;
        reject(ctx, t, "limits", FIXED_NO_VARIABLE)?;
        reject(ctx, t, "couple", FIXED_NO_VARIABLE)?;
        return Ok((0.0, [0.0, 0.0]));
    }
    let offset = match t.get("offset") {
        Some(v) => ctx.scalar(&t.path("offset"), v, revolute)?,
        None => 0.0,
    };
    let limits = match t.get("limits") {
        Some(v) => limits_of(ctx, &t.path("limits"), v, revolute)?,
        None if revolute => [-PI, PI],
        None => return Err(t.missing(ctx, "limits")),
    };
    Ok((offset, limits))
}

/// The joint's `name` and where it is (default `q{i+1}` at the table); "base" is reserved.
fn joint_name(ctx: &Ctx, t: &Table, i: usize) -> Res<(String, Span)> {
    let (name, name_span) = match t.get("name") {
        Some(v) => (ctx.string(&t.path("name"), v)?.to_string(), v.span()),
        None => (format!("q{}", i + 1), t.span.clone()),
    };
    if name == "base" {
        return Err(E::NotApplicable {
            field: t.path("name"),
            reason: "\"base\" is reserved for the robot base (see `parent`)",
            at: ctx.at(&name_span),
        });
    }
    Ok((name, name_span))
}

/// The joint's `parent`: a joint named earlier, "base" (none), or by default the joint before
/// it (none for the first).
fn joint_parent(ctx: &Ctx, t: &Table, i: usize, names: &Names) -> Res<Option<usize>> {
    Ok(match t.get("parent") {
        None => i.checked_sub(1),
        Some(v) => match ctx.string(&t.path("parent"), v)? {
            "base" => None,
            p => match names.get(p) {
                Some(&(id, _)) => Some(id),
                None => {
                    return Err(E::UnknownParent {
                        field: t.path("parent"),
                        name: p.into(),
                        at: ctx.at(&v.span()),
                    });
                }
            },
        },
    })
}

/// How the joint is driven: none (fixed), coupled to earlier joints (`couple`), or actuated as
/// the next actuated joint.
fn joint_drive(
    ctx: &Ctx,
    t: &Table,
    kind: JointKind,
    i: usize,
    count: usize,
    earlier: &[Joint],
) -> Res<Drive> {
    Ok(match (kind, t.get("couple")) {
        (JointKind::Fixed, _) => Drive::None,
        (_, Some(v)) => Drive::Coupled(couple(ctx, &t.path("couple"), v, i, count, earlier)?),
        (_, None) => {
            let dof = earlier
                .iter()
                .filter(|j| matches!(j.drive, Drive::Actuated(_)))
                .count();
            Drive::Actuated(dof)
        }
    })
}

const PRISMATIC_D: &str =
    "d of a prismatic joint is its variable (d = q + offset); put a constant length in `offset`";
const REVOLUTE_THETA: &str = "theta of a revolute joint is its variable (theta = q + offset); put a constant angle in `offset`";
const FIXED_NO_VARIABLE: &str =
    "a fixed joint has no variable, so it takes no `offset`, `limits` or `couple`";

fn limits_of(ctx: &Ctx, field: &str, v: &Val, angular: bool) -> Res<[f64; 2]> {
    if let toml::de::DeValue::String(s) = v.get_ref() {
        if s == "none" {
            return Ok(crate::kinematics::UNBOUNDED);
        }
        return Err(ctx.wrong_type(
            field,
            "2 values [lower, upper], or \"none\" for a joint without limits",
            v,
        ));
    }
    let a = ctx.array_n(field, v, 2, "2 values [lower, upper] (or \"none\")")?;
    let lower = ctx.scalar(&format!("{field}[1]"), &a[0], angular)?;
    let upper = ctx.scalar(&format!("{field}[2]"), &a[1], angular)?;
    if lower > upper {
        return Err(E::BadLimits {
            field: field.into(),
            lower,
            upper,
            at: ctx.at(&v.span()),
        });
    }
    Ok([lower, upper])
}

/// `couple = [[joint number, factor], ...]` of joint `i` (0-based).
fn couple(
    ctx: &Ctx,
    field: &str,
    v: &Val,
    i: usize,
    count: usize,
    earlier: &[Joint],
) -> Res<Vec<(usize, f64)>> {
    const PAIRS: &str = "an array of pairs [joint number, factor]";
    let terms = ctx.array(field, v, PAIRS)?;
    if terms.is_empty() {
        return Err(E::WrongLength {
            field: field.into(),
            expected: "at least one pair [joint number, factor]",
            found: 0,
            at: ctx.at(&v.span()),
        });
    }
    let mut out = Vec::with_capacity(terms.len());
    for (k, term) in terms.iter().enumerate() {
        let tf = format!("{field}[{}]", k + 1);
        let pair = ctx.array_n(&tf, term, 2, "a pair [joint number, factor]")?;
        let n = ctx.integer(&format!("{tf}[1]"), &pair[0])?;
        let coef = ctx.number(&format!("{tf}[2]"), &pair[1])?;
        let idx = usize::try_from(n).ok().and_then(|n| n.checked_sub(1));
        let problem = match idx {
            None => Some(CoupleProblem::NoSuchJoint),
            Some(j) if j >= count => Some(CoupleProblem::NoSuchJoint),
            Some(j) if j >= i => Some(CoupleProblem::NotEarlier),
            Some(j) if !matches!(earlier[j].drive, Drive::Actuated(_)) => {
                Some(CoupleProblem::NotActuated)
            }
            Some(_) => None,
        };
        match (problem, idx) {
            (None, Some(j)) => out.push((j, coef)),
            (p, _) => {
                return Err(E::BadCouple {
                    field: tf,
                    joint: n,
                    problem: p.unwrap_or(CoupleProblem::NoSuchJoint),
                    at: ctx.at(&pair[0].span()),
                });
            }
        }
    }
    Ok(out)
}

fn end_effectors(
    ctx: &Ctx,
    top: &Table,
    joints: &Names,
    count: usize,
    tool: Pose,
) -> Res<Vec<EndEffector>> {
    let tables = top.tables(ctx, "end_effectors")?;
    if tables.is_empty() {
        return Ok(vec![EndEffector {
            name: "tool".into(),
            parent: count - 1,
            tool,
        }]);
    }
    if top.get("tool").is_some() {
        return Err(E::NotApplicable {
            field: "tool".into(),
            reason: "the top-level `tool` is only used when there are no [[end_effectors]]; give each end-effector its own `tool`",
            at: ctx.at(&top.key_span("tool")),
        });
    }
    let mut names = Names::new();
    let mut out = Vec::with_capacity(tables.len());
    for (i, t) in tables.iter().enumerate() {
        t.check_keys(ctx, EE_KEYS)?;
        let name_v = t.required(ctx, "name")?;
        let name = ctx.string(&t.path("name"), name_v)?;
        let kind = NameKind::EndEffector;
        unique_name(
            ctx,
            &mut names,
            kind,
            t.path("name"),
            name,
            i,
            &name_v.span(),
        )?;
        let parent_v = t.required(ctx, "parent")?;
        let parent_name = ctx.string(&t.path("parent"), parent_v)?;
        let Some(&(parent, _)) = joints.get(parent_name) else {
            return Err(E::UnknownJoint {
                field: t.path("parent"),
                name: parent_name.into(),
                at: ctx.at(&parent_v.span()),
            });
        };
        out.push(EndEffector {
            name: name.into(),
            parent,
            tool: optional_pose(ctx, t, "tool")?,
        });
    }
    Ok(out)
}

fn configurations(ctx: &Ctx, top: &Table, robot: &mut Robot) -> Res<()> {
    let mut names = Names::new();
    for (i, t) in top.tables(ctx, "configurations")?.iter().enumerate() {
        t.check_keys(ctx, CONFIG_KEYS)?;
        let name_v = t.required(ctx, "name")?;
        let name = ctx.string(&t.path("name"), name_v)?;
        let kind = NameKind::Configuration;
        unique_name(
            ctx,
            &mut names,
            kind,
            t.path("name"),
            name,
            i,
            &name_v.span(),
        )?;
        let q_v = t.required(ctx, "q")?;
        let field = t.path("q");
        let values = ctx.array(&field, q_v, "an array of joint values")?;
        if values.len() != robot.dof() {
            return Err(E::ConfigLength {
                field,
                expected: robot.dof(),
                found: values.len(),
                at: ctx.at(&q_v.span()),
            });
        }
        let q = values
            .iter()
            .enumerate()
            .map(|(k, v)| {
                let angular = robot.dof_joint(k).kind == JointKind::Revolute;
                ctx.scalar(&format!("{field}[{}]", k + 1), v, angular)
            })
            .collect::<Res<Vec<f64>>>()?;
        robot.configurations.retain(|c| c.name != name);
        robot.configurations.push(NamedConfig {
            name: name.into(),
            q,
        });
    }
    Ok(())
}

/// Traces an error of [`Robot::new`] back to the joint (and field) it names.
fn model_error(ctx: &Ctx, e: ModelError, tables: &[Table], joints_key: Span) -> E {
    let (joint, key) = match &e {
        ModelError::NonFiniteParameter { joint, field, .. } => (Some(*joint), Some(*field)),
        ModelError::BadLimits { joint, .. } => (Some(*joint), Some("limits")),
        ModelError::OutOfRange { joint, field, .. } => (Some(*joint), Some(*field)),
        ModelError::BadParent { joint, .. } => (Some(*joint), Some("parent")),
        ModelError::BadCoupling { joint, .. } => (Some(*joint), Some("couple")),
        ModelError::ZeroAxis { joint } => (Some(*joint), None),
        _ => (None, None),
    };
    let (field, span) = match joint.and_then(|j| tables.get(j)) {
        Some(t) => match key.filter(|k| t.get(k).is_some()) {
            Some(k) => (t.path(k), t.key_span(k)),
            None => (t.field.clone(), t.span.clone()),
        },
        None => ("joints".to_string(), joints_key),
    };
    E::Model {
        field,
        source: e,
        at: ctx.at(&span),
    }
}
