//! Heavy computations handed to another worker (a browser's web worker, where the page has no
//! threads): the request (a robot that travels as a built-in model's name or a model file's text,
//! and what to compute), the answer, and the function the worker runs. Graphics-free; the app
//! sends them as JSON ([`answer`] is the worker's entry point).

use crate::kinematics::Robot;
use crate::urdf::UrdfExportError;
use crate::workspace::{
    FigureData, FigureRequest, MapForming, OneShot, WorkspaceMap, compute_figure_data_forming,
};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Runs requests somewhere else and hands the answers back, one at a time.
pub trait Offload {
    /// Starts computing `request` ([`Request`] as JSON); `false` if it cannot.
    fn submit(&mut self, request: String) -> bool;
    /// The answer ([`Answer`] as JSON) to the request submitted last, once it is there.
    fn poll(&mut self) -> Option<String>;
}

/// A computation for a robot.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Request {
    /// The robot.
    pub model: Model,
    /// What to compute: everything a workspace figure paints.
    pub task: FigureRequest,
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

/// The answer to a [`Request`].
#[derive(Debug, Clone, Serialize, Deserialize)]
pub enum Answer {
    /// What the figure paints.
    Data(Box<FigureData>),
    /// The map while it forms, before the data ([`crate::workspace::MapForming::partial`]).
    Partial {
        /// The map so far.
        map: Box<WorkspaceMap>,
        /// Rows decided from the top (the rest is the coarse look).
        rows_done: usize,
    },
    /// Why not (the model did not load, the computation failed).
    Error(String),
}

/// Why a robot cannot travel to a worker.
#[derive(Debug, Error)]
#[error("the robot cannot be sent to the worker: {0}")]
pub struct NotTransferable(#[from] UrdfExportError);

impl Request {
    /// A request for `robot` (opened as `spec`): by name when it is that built-in model
    /// unedited, else as a TOML model file where it is one serial DH table, else as URDF; `Err`
    /// when it has no form that travels (a tree with coupled joints, edited).
    pub fn new(robot: &Robot, spec: &str, task: FigureRequest) -> Result<Self, NotTransferable> {
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
                text: crate::urdf::to_urdf(robot)?,
            }
        };
        Ok(Self { model, task })
    }
}

impl Model {
    /// The robot it names or holds.
    pub fn robot(&self) -> Result<Robot, String> {
        match self {
            Model::BuiltIn(name) => crate::kinematics::models::built_in(name)
                .ok_or_else(|| format!("no built-in model \"{name}\"")),
            Model::File { name, text } => {
                crate::model_file::parse_model_text(name, text).map_err(|e| e.to_string())
            }
        }
    }
}

/// Computes the answer to `request`.
pub fn run(request: &Request) -> Answer {
    run_forming(request, &mut OneShot)
}

/// Computes the answer to `request`, handing `forming` the map as it forms.
pub fn run_forming(request: &Request, forming: &mut dyn MapForming) -> Answer {
    let answer = request.model.robot().and_then(|robot| {
        compute_figure_data_forming(&robot, &request.task, &|_| {}, forming)
            .map_err(|e| e.to_string())
    });
    match answer {
        Ok(data) => Answer::Data(Box::new(data)),
        Err(e) => Answer::Error(e),
    }
}

/// Computes the answer to `request` (JSON in, JSON out): what the worker runs.
#[cfg(feature = "gui")]
pub fn answer(request: &str) -> String {
    answer_forming(request, &mut || false, &mut |_| {})
}

/// [`answer`], handing `partial` each partial map as an [`Answer::Partial`] in JSON whenever
/// `wants()` (asked after each tile) says it wants one (a worker throttles there).
#[cfg(feature = "gui")]
pub fn answer_forming(
    request: &str,
    wants: &mut dyn FnMut() -> bool,
    partial: &mut dyn FnMut(String),
) -> String {
    struct Sink<'a> {
        wants: &'a mut dyn FnMut() -> bool,
        partial: &'a mut dyn FnMut(String),
    }
    impl MapForming for Sink<'_> {
        fn wants(&mut self) -> bool {
            (self.wants)()
        }
        fn partial(&mut self, map: &WorkspaceMap, rows_done: usize) {
            let answer = Answer::Partial {
                map: Box::new(map.clone()),
                rows_done,
            };
            if let Ok(json) = serde_json::to_string(&answer) {
                (self.partial)(json);
            }
        }
    }
    let answer = match serde_json::from_str::<Request>(request) {
        Ok(r) => run_forming(&r, &mut Sink { wants, partial }),
        Err(e) => Answer::Error(format!("bad request: {e}")),
    };
    serde_json::to_string(&answer).unwrap_or_else(|e| format!("{{\"Error\":\"{e}\"}}"))
}
