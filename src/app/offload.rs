//! Heavy workspace computations handed to another worker (the browser's web worker, where the
//! page has no threads): the requests and answers as JSON, the function the worker runs, and the
//! figure's source that serves handed-in results ([`Handed`]).

use crate::figure::FigureError;
use crate::figure::workspace::WorkspaceSource;
use crate::kinematics::Robot;
use crate::workspace::{MapRequest, StatsOptions, TrackedPoint, WorkspaceMap, WorkspaceStats};
use serde::{Deserialize, Serialize};

/// Runs requests somewhere else and hands the answers back (one at a time).
pub trait Offload {
    /// Starts computing `request` ([`Request`] as JSON); `false` if it cannot.
    fn submit(&mut self, request: String) -> bool;
    /// The answer ([`Answer`] as JSON) to the request submitted last, once it is there.
    fn poll(&mut self) -> Option<String>;
}

/// A computation for a robot sent as a built-in model's name or as the text of a model file.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Request {
    /// The robot.
    pub model: Model,
    /// What to compute.
    pub task: Task,
}

/// A robot as it travels to the worker.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub enum Model {
    /// An unedited built-in model, by name.
    BuiltIn(String),
    /// A model file: its name (`robot.toml` or `robot.urdf`: the format) and text.
    File {
        /// The file's name.
        name: String,
        /// Its text.
        text: String,
    },
}

/// What to compute.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Task {
    /// [`crate::workspace::map_statistics`].
    Statistics {
        /// The tracked point.
        point: TrackedPoint,
        /// Options where no exact method applies.
        fallback: StatsOptions,
    },
    /// [`crate::workspace::compute_map`].
    Map(MapRequest),
}

/// The answer to a [`Request`].
#[derive(Debug, Clone, Serialize, Deserialize)]
pub enum Answer {
    /// The statistics.
    Statistics(WorkspaceStats),
    /// The map.
    Map(WorkspaceMap),
    /// Why not (the model did not load, the computation failed).
    Error(String),
}

impl Request {
    /// A request for `robot` (opened as `spec`): by name when it is that built-in model
    /// unedited, else as a TOML model file where it is one serial DH table, else as URDF; `Err`
    /// when it has no form that travels (a tree with coupled joints, edited).
    pub fn new(robot: &Robot, spec: &str, task: Task) -> Result<Self, String> {
        let model = if crate::kinematics::models::built_in(spec).as_ref() == Some(robot) {
            Model::BuiltIn(spec.to_string())
        } else if let Some(text) = crate::model_file::to_toml(robot) {
            Model::File {
                name: "robot.toml".into(),
                text,
            }
        } else {
            Model::File {
                name: "robot.urdf".into(),
                text: crate::urdf::to_urdf(robot).map_err(|e| e.to_string())?,
            }
        };
        Ok(Self { model, task })
    }
}

impl Model {
    fn robot(&self) -> Result<Robot, String> {
        match self {
            Model::BuiltIn(name) => crate::kinematics::models::built_in(name)
                .ok_or_else(|| format!("no built-in model \"{name}\"")),
            Model::File { name, text } => {
                crate::model_file::parse_model_text(name, text).map_err(|e| e.to_string())
            }
        }
    }
}

/// Computes the answer to `request` (JSON in, JSON out): what the worker runs.
pub fn answer(request: &str) -> String {
    let answer = serde_json::from_str::<Request>(request)
        .map_err(|e| format!("bad request: {e}"))
        .and_then(|r| {
            let robot = r.model.robot()?;
            match r.task {
                Task::Statistics { point, fallback } => {
                    crate::workspace::map_statistics(&robot, point, &fallback)
                        .map(Answer::Statistics)
                }
                Task::Map(req) => crate::workspace::compute_map(&robot, &req).map(Answer::Map),
            }
            .map_err(|e| e.to_string())
        })
        .unwrap_or_else(Answer::Error);
    serde_json::to_string(&answer).unwrap_or_else(|e| format!("{{\"Error\":\"{e}\"}}"))
}

/// A figure's source of results handed in from elsewhere: what it has is served, what it lacks
/// is noted in [`Handed::wanted`] and answered [`FigureError::Pending`].
#[derive(Debug, Default)]
pub struct Handed {
    stats: Option<(TrackedPoint, StatsOptions, WorkspaceStats)>,
    map: Option<(MapRequest, WorkspaceMap)>,
    /// The computation the last attempt lacked.
    pub wanted: Option<Task>,
}

impl Handed {
    /// Files the answer to `task` for the next attempt.
    pub fn hand_in(&mut self, task: Task, answer: Answer) -> Result<(), String> {
        match (task, answer) {
            (Task::Statistics { point, fallback }, Answer::Statistics(s)) => {
                self.stats = Some((point, fallback, s))
            }
            (Task::Map(req), Answer::Map(m)) => self.map = Some((req, m)),
            (_, Answer::Error(e)) => return Err(e),
            _ => return Err("the worker answered another question".into()),
        }
        Ok(())
    }
}

impl WorkspaceSource for Handed {
    fn statistics(
        &mut self,
        _robot: &Robot,
        point: TrackedPoint,
        fallback: &StatsOptions,
    ) -> Result<WorkspaceStats, FigureError> {
        match &self.stats {
            Some((p, f, s)) if *p == point && f == fallback => Ok(s.clone()),
            _ => {
                self.wanted = Some(Task::Statistics {
                    point,
                    fallback: fallback.clone(),
                });
                Err(FigureError::Pending("workspace statistics"))
            }
        }
    }

    fn map(&mut self, _robot: &Robot, req: &MapRequest) -> Result<WorkspaceMap, FigureError> {
        match &self.map {
            Some((r, m)) if r == req => Ok(m.clone()),
            _ => {
                self.wanted = Some(Task::Map(req.clone()));
                Err(FigureError::Pending("workspace map"))
            }
        }
    }
}
