//! `armlab._core.CoreRobot`: one robot and its closed-form solver, detected once.
//!
//! Single calls take one joint vector or one pose; the batch calls are in `batch.rs`, the
//! figures in `figures.rs`, the reports (workspace, self-motion, symbolic) in `reports.rs`.

use crate::arrays::{checked, pose_of, to_numpy, write_pose};
use crate::errors::{IntoPy, value_error};
use armlab::collision::{CellScene, CollisionWorld};
use armlab::kinematics::ik::closed_form::ClosedForm;
use armlab::kinematics::ik::numerical::{self, Method, NumericalOptions};
use armlab::kinematics::ik::solver::{self, SolverChoice};
use armlab::kinematics::ik::{IkResult, IkStatus, Target};
use armlab::kinematics::singularity::SingularityAnalyzer;
use armlab::kinematics::{JointKind, Robot};
use armlab::nalgebra::Vector3;
use numpy::{PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use serde_json::json;
use std::sync::OnceLock;

/// A robot of the library with its closed form (if its structure has one).
#[pyclass(module = "armlab._core", frozen)]
pub struct CoreRobot {
    /// The model.
    pub robot: Robot,
    /// What it was loaded from: a built-in name or a path (the CLI-driven calls take it).
    pub spec: String,
    /// The closed-form solver of the arm of end-effector 0, or why there is none.
    pub closed_form: Result<ClosedForm, String>,
    /// The whole robot's q index of each of that arm's joints (0..dof for a robot with one
    /// end-effector).
    pub arm_free: Vec<usize>,
    /// The whole robot's q that the joints off that arm keep ("ready", else zero).
    pub arm_base: Vec<f64>,
    /// Whether each joint variable is an angle.
    pub revolute: Vec<bool>,
    /// The checker of the robot's own links (its stored matrix, or one sampled at first use),
    /// built when first asked for.
    self_world: OnceLock<CollisionWorld>,
}

impl CoreRobot {
    /// Wraps `robot`, detecting the closed form of end-effector 0's arm (the chain from the
    /// root to it alone, for a robot with several end-effectors: a URDF's extra links, a
    /// humanoid's hands).
    pub fn new(robot: Robot, spec: String) -> Self {
        let arm_base = robot.ready_or_zero();
        let (closed_form, arm_free) = if robot.end_effectors().len() == 1 {
            let cf = ClosedForm::detect(&robot).map_err(|e| e.to_string());
            (cf, (0..robot.dof()).collect())
        } else {
            match armlab::kinematics::arm::arm_of(&robot, 0, &arm_base) {
                Ok(arm) => (
                    ClosedForm::detect(&arm.robot).map_err(|e| e.to_string()),
                    arm.free,
                ),
                Err(e) => (Err(e.to_string()), Vec::new()),
            }
        };
        let revolute = (0..robot.dof())
            .map(|k| robot.dof_joint(k).kind == JointKind::Revolute)
            .collect();
        Self {
            robot,
            spec,
            closed_form,
            arm_free,
            arm_base,
            revolute,
            self_world: OnceLock::new(),
        }
    }

    /// The checker of the robot's own links, no obstacles (built on first use: the geometry
    /// and the allowed-collision matrix, sampled quickly when the model stores none).
    pub fn self_world(&self) -> PyResult<&CollisionWorld> {
        if let Some(w) = self.self_world.get() {
            return Ok(w);
        }
        let w = CollisionWorld::new(&self.robot, &CellScene::default()).py_err()?;
        Ok(self.self_world.get_or_init(|| w))
    }

    /// A checked joint vector.
    pub fn q(&self, q: &PyReadonlyArrayDyn<'_, f64>, name: &str) -> PyResult<Vec<f64>> {
        Ok(checked(
            q,
            name,
            &[Some(self.robot.dof())],
            "one value per joint, rad or m",
        )?
        .into_owned())
    }

    /// A checked end-effector index.
    pub fn ee(&self, ee: usize) -> PyResult<usize> {
        let count = self.robot.end_effectors().len();
        if ee < count {
            Ok(ee)
        } else {
            Err(value_error(format!(
                "ee = {ee}: {} has {count} end-effector(s), numbered from 0",
                self.robot.name
            )))
        }
    }

    /// A pose (4x4) or position (3,) target.
    pub fn target(&self, t: &PyReadonlyArrayDyn<'_, f64>, name: &str) -> PyResult<Target> {
        match t.shape().len() {
            1 => {
                let p = checked(t, name, &[Some(3)], "a position x, y, z in m")?;
                Ok(Target::Position(Vector3::new(p[0], p[1], p[2])))
            }
            _ => {
                let m = checked(t, name, &[Some(4), Some(4)], "a homogeneous transform")?;
                Ok(Target::Pose(pose_of(&m, name)?))
            }
        }
    }
}

/// One IK solution as Python receives it: (q, posture label, within_limits, position_error,
/// orientation_error, free joints as (index, why), the posture's fields as JSON (the
/// `posture_parts` of `armlab ik --format json`), read when Python asks, and what it hits as
/// JSON (`armlab collisions --format json`'s report), with its summary in words).
pub type SolutionTuple = (
    Vec<f64>,
    String,
    bool,
    f64,
    f64,
    Vec<(usize, &'static str)>,
    String,
    String,
    String,
);

/// An IK result as Python receives it: (status, distance to the workspace when unreachable,
/// the solver that answered, the solutions).
pub type IkTuple = (&'static str, Option<f64>, String, Vec<SolutionTuple>);

/// An IK result as plain tuples, each solution with what it hits in `world` (the posture's
/// fields and the collision report as JSON, read when Python asks).
fn ik_tuple(
    result: IkResult,
    used: &str,
    robot: &Robot,
    world: &CollisionWorld,
) -> PyResult<IkTuple> {
    let (status, distance) = match result.status {
        IkStatus::Ok => ("ok", None),
        IkStatus::Singular => ("singular", None),
        IkStatus::Unreachable { distance } => ("unreachable", Some(distance)),
    };
    let mut solutions = Vec::with_capacity(result.solutions.len());
    for s in result.solutions {
        let free = s.free_joints.iter().map(|f| (f.index, f.reason)).collect();
        // A posture is plain data (enums, numbers): it always serialises.
        let parts = serde_json::to_string(&s.posture).unwrap_or_default();
        let report = world.check(robot, &s.q).py_err()?;
        solutions.push((
            s.q,
            s.posture.to_string(),
            s.within_limits,
            s.position_error,
            s.orientation_error,
            free,
            parts,
            crate::collision::report_json(&report),
            report.summary(),
        ));
    }
    Ok((status, distance, used.to_string(), solutions))
}

#[pymethods]
impl CoreRobot {
    /// A robot from a built-in name or a path to a `.toml` model file or a `.urdf`.
    #[staticmethod]
    fn load(spec: &str) -> PyResult<Self> {
        let robot = armlab::model_file::load_model(spec).py_err()?;
        Ok(Self::new(robot, spec.to_string()))
    }

    /// The built-in models: (name, one-line summary) pairs.
    #[staticmethod]
    fn builtins() -> Vec<(String, String)> {
        armlab::kinematics::models::BUILT_INS
            .iter()
            .map(|b| (b.name.to_string(), b.summary.to_string()))
            .collect()
    }

    /// The model's name.
    #[getter]
    fn name(&self) -> String {
        self.robot.name.clone()
    }

    /// What it was loaded from.
    #[getter]
    fn spec(&self) -> String {
        self.spec.clone()
    }

    /// Number of joint variables.
    #[getter]
    fn dof(&self) -> usize {
        self.robot.dof()
    }

    /// The joints: (name, "revolute" | "prismatic", lower, upper) per joint variable.
    fn joints(&self) -> Vec<(String, String, f64, f64)> {
        (0..self.robot.dof())
            .map(|k| {
                let j = self.robot.dof_joint(k);
                (
                    j.name.clone(),
                    j.kind.as_str().to_string(),
                    j.limits[0],
                    j.limits[1],
                )
            })
            .collect()
    }

    /// The end-effectors' names.
    fn end_effectors(&self) -> Vec<String> {
        self.robot
            .end_effectors()
            .iter()
            .map(|e| e.name.clone())
            .collect()
    }

    /// The closed-form family's name, or `None`.
    fn closed_form(&self) -> Option<String> {
        self.closed_form.as_ref().ok().map(|c| c.name().to_string())
    }

    /// Why there is no closed form (`None` when there is one).
    fn no_closed_form_reason(&self) -> Option<String> {
        self.closed_form.as_ref().err().cloned()
    }

    /// The named configurations ("zero", "ready", ...) as (name, q).
    fn configs(&self) -> Vec<(String, Vec<f64>)> {
        self.robot
            .configurations
            .iter()
            .map(|c| (c.name.clone(), c.q.clone()))
            .collect()
    }

    /// `world_from_tool` of end-effector `ee` at `q`, a (4, 4) array.
    fn fk<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArrayDyn<'py, f64>,
        ee: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let q = self.q(&q, "q")?;
        let pose = self.robot.fk_ee(&q, self.ee(ee)?).py_err()?;
        let mut out = vec![0.0; 16];
        write_pose(&pose, &mut out);
        to_numpy(py, out, &[4, 4])
    }

    /// `world_from_frame_j` of every joint frame j at `q`, a (frames, 4, 4) array.
    fn fk_frames<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArrayDyn<'py, f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let q = self.q(&q, "q")?;
        let frames = self.robot.fk_frames(&q).py_err()?;
        let mut out = vec![0.0; 16 * frames.len()];
        for (f, o) in frames.iter().zip(out.chunks_exact_mut(16)) {
            write_pose(f, o);
        }
        to_numpy(py, out, &[frames.len(), 4, 4])
    }

    /// The names of the frames `fk_frames` returns (the joints'), in order.
    fn frame_names(&self) -> Vec<String> {
        self.robot.joints().iter().map(|j| j.name.clone()).collect()
    }

    /// The geometric Jacobian (6, dof) of end-effector `ee` at `q`: rows v (m/s), omega (rad/s)
    /// in the world frame (Sect. 3.1).
    fn jacobian<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArrayDyn<'py, f64>,
        ee: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let q = self.q(&q, "q")?;
        let j = self.robot.jacobian(&q, self.ee(ee)?).py_err()?;
        let n = j.ncols();
        let mut out = vec![0.0; 6 * n];
        for r in 0..6 {
            for c in 0..n {
                out[r * n + c] = j[(r, c)];
            }
        }
        to_numpy(py, out, &[6, n])
    }

    /// Yoshikawa's manipulability sqrt(det(J J^T)) over the rows the arm controls (e.g. v_x,
    /// v_y for a two-link planar arm; all six for a six-joint arm), and those rows.
    fn manipulability(
        &self,
        q: PyReadonlyArrayDyn<'_, f64>,
        ee: usize,
    ) -> PyResult<(f64, Vec<usize>)> {
        let q = self.q(&q, "q")?;
        let analyzer = SingularityAnalyzer::new(&self.robot);
        let j = analyzer
            .task_jacobian(&self.robot, &q, self.ee(ee)?)
            .py_err()?;
        let a = armlab::kinematics::jacobian::analyze(&j);
        Ok((a.manipulability, analyzer.task_rows().to_vec()))
    }

    /// Every IK solution of a pose (4x4) or position (3,) target: the closed form with
    /// its labelled postures where the structure has one, else the numerical solver from
    /// `seed` (`solver` = "auto", "closed-form" or "numerical"). Each solution says what it
    /// hits: the arm's own links and the obstacles of the scene file `scene_path` (or of the
    /// scene text `scene_text`); and the checker's warnings.
    #[pyo3(signature = (target, ee=0, seed=None, solver="auto", scene_path=None, scene_text=None))]
    fn ik(
        &self,
        target: PyReadonlyArrayDyn<'_, f64>,
        ee: usize,
        seed: Option<PyReadonlyArrayDyn<'_, f64>>,
        solver: &str,
        scene_path: Option<&str>,
        scene_text: Option<&str>,
    ) -> PyResult<(IkTuple, Vec<String>)> {
        let t = self.target(&target, "T")?;
        let seed = seed.map(|s| self.q(&s, "seed")).transpose()?;
        let choice = match solver {
            "auto" => SolverChoice::Auto,
            "closed-form" | "closed_form" => SolverChoice::ClosedForm,
            "numerical" => SolverChoice::Numerical,
            other => {
                return Err(value_error(format!(
                    "solver = {other:?}: use \"auto\", \"closed-form\" or \"numerical\""
                )));
            }
        };
        let (result, used) = solver::solve(
            &self.robot,
            self.ee(ee)?,
            &t,
            seed.as_deref(),
            choice,
            &NumericalOptions::default(),
        )
        .py_err()?;
        let world = crate::collision::world(self, scene_path, scene_text)?;
        let tuple = ik_tuple(result, &used.to_string(), &self.robot, &world)?;
        Ok((tuple, world.warnings.clone()))
    }

    /// The numerical solver alone, from `q0`: its report as JSON (q, converged, iterations,
    /// restarts, position_error, orientation_error).
    #[pyo3(signature = (target, q0, ee=0, method="lm", tolerance=1e-10, max_iterations=100, restarts=50, seed=0x5EED))]
    #[allow(clippy::too_many_arguments)]
    fn ik_numerical(
        &self,
        target: PyReadonlyArrayDyn<'_, f64>,
        q0: PyReadonlyArrayDyn<'_, f64>,
        ee: usize,
        method: &str,
        tolerance: f64,
        max_iterations: usize,
        restarts: usize,
        seed: u64,
    ) -> PyResult<String> {
        let t = self.target(&target, "T")?;
        let q0 = self.q(&q0, "q0")?;
        let method = match method {
            "lm" => Method::LevenbergMarquardt,
            "dls" => Method::DampedLeastSquares,
            "pinv" => Method::PseudoInverse,
            "transpose" => Method::Transpose,
            other => {
                return Err(value_error(format!(
                    "method = {other:?}: use \"lm\", \"dls\", \"pinv\" or \"transpose\""
                )));
            }
        };
        if !(tolerance > 0.0 && tolerance.is_finite()) || max_iterations == 0 {
            return Err(value_error(
                "tolerance must be positive and max_iterations at least 1",
            ));
        }
        let opts = NumericalOptions {
            method,
            tolerance,
            max_iterations,
            restarts,
            seed,
            ..NumericalOptions::default()
        };
        let r = numerical::solve(&self.robot, self.ee(ee)?, &t, &q0, &opts).py_err()?;
        Ok(json!({
            "q": r.q,
            "converged": r.converged,
            "iterations": r.iterations,
            "restarts": r.restarts,
            "position_error": r.position_error,
            "orientation_error": r.orientation_error,
        })
        .to_string())
    }

    fn __repr__(&self) -> String {
        format!("CoreRobot({:?}, dof={})", self.robot.name, self.robot.dof())
    }
}
