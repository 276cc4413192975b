//! Heavy computations handed to another worker (a browser's web worker, where the page has no
//! threads): the request (a robot that travels as a built-in model's name or a model file's text,
//! and what to compute), the answer, and the function the worker runs. Graphics-free; the app
//! sends them as JSON ([`answer`] is the worker's entry point). A figure's work can be spread
//! over a pool of workers in parts ([`Spread`]).

mod spread;
pub use spread::{Spread, SpreadStep};

use crate::kinematics::Robot;
use crate::urdf::UrdfExportError;
use crate::workspace::figure_data::{PlaneMarks, coarse_map, figure_stats};
use crate::workspace::{
    ContentRequest, FigureData, FigureRequest, MapForming, OneShot, TiledMap, WorkspaceMap,
    WorkspaceStats, compute_figure_data_forming,
};
use serde::{Deserialize, Serialize};
use std::sync::{Arc, Mutex};
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
    /// Which part of it (all of it unless the work is spread over several workers).
    #[serde(default)]
    pub part: Part,
}

/// A part of a figure's work ([`Spread`]).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub enum Part {
    /// All of it, the map handed over as it forms ([`Answer::Partial`], then [`Answer::Data`]).
    #[default]
    Whole,
    /// The map's coarse first look ([`Answer::Partial`] with `rows_done` 0).
    Coarse,
    /// The statistics and the plane's marks ([`Answer::Stats`]).
    Stats,
    /// The masks of the map's rows `[start, end)` ([`Answer::Tile`]; a map that
    /// [`TiledMap`] makes).
    Tile([usize; 2]),
    /// The map finished from the masks of all its rows ([`Answer::Map`]).
    Finish(Vec<u8>),
}

/// A robot as it travels to the worker.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
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
    /// The statistics ([`Part::Stats`]).
    Stats {
        /// Area or volume, bounds and reach.
        stats: Box<WorkspaceStats>,
        /// Fig. 2.30's marks, where they apply.
        plane_marks: Option<PlaneMarks>,
    },
    /// A tile's masks ([`Part::Tile`]).
    Tile {
        /// Its rows, `[start, end)`.
        rows: [usize; 2],
        /// Their masks, row-major.
        masks: Vec<u8>,
    },
    /// The finished map ([`Part::Finish`]).
    Map(Box<WorkspaceMap>),
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
        Ok(Self {
            model,
            task,
            part: Part::Whole,
        })
    }

    /// The same request for part `part`.
    pub fn for_part(&self, part: Part) -> Self {
        Self {
            part,
            ..self.clone()
        }
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

/// Computes the answer to `request`, handing `forming` the map as it forms (a whole figure).
pub fn run_forming(request: &Request, forming: &mut dyn MapForming) -> Answer {
    let answer = request.model.robot().and_then(|robot| {
        let task = &request.task;
        let failed = |e: crate::workspace::WorkspaceError| e.to_string();
        let map_request = match &task.content {
            ContentRequest::Map(m) => Some(m),
            _ => None,
        };
        let no_map = || "this figure has no map".to_string();
        Ok(match &request.part {
            Part::Whole => Answer::Data(Box::new(
                compute_figure_data_forming(&robot, task, &|_| {}, forming).map_err(failed)?,
            )),
            Part::Coarse => Answer::Partial {
                map: Box::new(coarse_map(&robot, map_request.ok_or_else(no_map)?).map_err(failed)?),
                rows_done: 0,
            },
            Part::Stats => {
                let (stats, plane_marks) = figure_stats(&robot, task).map_err(failed)?;
                Answer::Stats {
                    stats: Box::new(stats),
                    plane_marks,
                }
            }
            Part::Tile([a, b]) => Answer::Tile {
                rows: [*a, *b],
                masks: tiled(request, &robot)?.rows(*a..*b).map_err(failed)?,
            },
            Part::Finish(masks) => Answer::Map(Box::new(
                tiled(request, &robot)?
                    .finish(masks.clone())
                    .map_err(failed)?,
            )),
        })
    });
    answer.unwrap_or_else(Answer::Error)
}

/// The tiled map of a request, prepared once per worker: kept for the next tile of the same
/// figure (a top view's preparation solves the side view at every radius).
fn tiled(request: &Request, robot: &Robot) -> Result<Arc<TiledMap>, String> {
    type Key = (Model, FigureRequest);
    static LAST: Mutex<Option<(Key, Arc<TiledMap>)>> = Mutex::new(None);
    let ContentRequest::Map(req) = &request.task.content else {
        return Err("this figure has no map".into());
    };
    let key = (request.model.clone(), request.task.clone());
    let mut last = LAST.lock().map_err(|e| e.to_string())?;
    if let Some((k, map)) = last.as_ref()
        && *k == key
    {
        return Ok(map.clone());
    }
    let map = TiledMap::new(robot, req)
        .map_err(|e| e.to_string())?
        .ok_or("this map is not made in tiles")?;
    let map = Arc::new(map);
    *last = Some((key, map.clone()));
    Ok(map)
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
