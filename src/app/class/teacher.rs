//! The teacher's side: the app's setup as the class's state (the robot by name or as a model
//! file sent once, q, the rest as a lesson step), sent when it changes and at most
//! [`super::STATE_RATE_HZ`] times a second; the "which posture is this?" poll; a server started
//! in the app.

use super::ClassClient;
use crate::app::lesson::{Seen, current_step};
use crate::app::shell::AppUi;
use crate::app::state::AppState;
use crate::class::protocol::{
    ClassState, ClientMessage, LessonAt, QuestionKind, QuestionRequest, RobotRef,
};

/// What the teacher's app last sent, and the robot as the server knows it.
#[derive(Debug, Default)]
pub(super) struct TeacherSide {
    /// The state last sent, and when (s, egui time).
    sent: Option<(ClassState, f64)>,
    /// The robot for the model generation it was made at: a built-in's name, or a model file
    /// sent and the id the server gave it (`None` while the reply is awaited).
    robot: Option<(u64, Option<RobotRef>)>,
    /// The name of the model file sent, awaiting its id.
    pending: Option<String>,
}

impl TeacherSide {
    /// After a reconnection everything is sent again (the model too: the server may be new).
    pub(super) fn reconnected(&mut self) {
        *self = Self::default();
    }

    /// The server stored the model file sent: its id.
    pub(super) fn model_stored(&mut self, id: String, name: String) {
        if self.pending.take().is_some()
            && let Some((_, slot @ None)) = &mut self.robot
        {
            *slot = Some(RobotRef::Model { id, name });
        }
    }
}

impl ClassClient {
    /// Sends the app's setup if it changed since the last state and the last was sent at
    /// least 1 / [`super::STATE_RATE_HZ`] s ago (else a frame is asked for when it may be).
    pub(super) fn send_state(&mut self, ctx: &egui::Context, app: &AppUi) {
        let Some(robot) = self.robot_ref(&app.state) else {
            return;
        };
        let state = class_state(app, robot);
        let now = ctx.input(|i| i.time);
        let wait = match &self.teacher.sent {
            Some((last, _)) if *last == state => return,
            Some((_, at)) => 1.0 / super::STATE_RATE_HZ - (now - at),
            None => 0.0,
        };
        if wait > 0.0 {
            ctx.request_repaint_after(std::time::Duration::from_secs_f64(wait));
            return;
        }
        self.send(&ClientMessage::State {
            state: state.clone(),
        });
        self.teacher.sent = Some((state, now));
    }

    /// The robot as the state names it: a built-in (unedited) by name; any other model as a
    /// model file, sent once per model generation (`None` until the server's id came back).
    fn robot_ref(&mut self, state: &AppState) -> Option<RobotRef> {
        let generation = state.generation();
        if let Some((g, robot)) = &self.teacher.robot
            && *g == generation
        {
            return robot.clone();
        }
        let spec = state.spec();
        if crate::kinematics::models::built_in(spec).is_some() && !state.is_edited() {
            let robot = RobotRef::Builtin(spec.to_string());
            self.teacher.robot = Some((generation, Some(robot.clone())));
            return Some(robot);
        }
        match model_file(state) {
            Ok((name, text)) => {
                self.teacher.robot = Some((generation, None));
                self.teacher.pending = Some(name.clone());
                self.send(&ClientMessage::Model { name, text });
            }
            Err(e) => {
                self.teacher.robot = Some((generation, None));
                let m = format!("class: the students cannot be sent this model: {e}");
                self.note(crate::app::state::Level::Error, m);
            }
        }
        None
    }
}

/// The robot as a model file for the students: TOML where it is one DH table, else URDF; named
/// after the robot.
fn model_file(state: &AppState) -> Result<(String, String), String> {
    let stem: String = state
        .robot()
        .name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .take(60)
        .collect();
    let toml = format!("{stem}.toml");
    match state.model_text(&toml) {
        Ok(text) => Ok((toml, text)),
        Err(_) => {
            let urdf = format!("{stem}.urdf");
            state.model_text(&urdf).map(|text| (urdf, text))
        }
    }
}

/// What the teacher's app shows, as the class's state: the robot, q, the setup as a lesson
/// step (without q, which [`ClassState::q`] holds; the Workspace tab's figure only while that
/// tab is shown, so that following students compute no figure they do not see), the lesson
/// being played and its caption.
pub(super) fn class_state(app: &AppUi, robot: RobotRef) -> ClassState {
    let seen = Seen::of(&app.tabs, app.tab, &app.ik.construction);
    let playing = app.lesson.as_ref().filter(|p| !p.lesson.steps.is_empty());
    let caption = playing.map_or("", |p| {
        p.lesson.steps[p.step.min(p.lesson.steps.len() - 1)]
            .caption
            .as_str()
    });
    let mut view = current_step(&app.state, app.ee(), &seen, caption);
    view.q = None;
    if app.tab != crate::app::tabs::WORKSPACE {
        view.figure = None;
    }
    ClassState {
        robot,
        q: app.state.q().to_vec(),
        view,
        lesson: playing.map(|p| LessonAt {
            title: p.lesson.title.clone(),
            step: p.step + 1,
            steps: p.lesson.steps.len(),
        }),
    }
}

/// "Which posture is this?": a poll whose choices are the postures of the current target's
/// solutions, as the IK panel lists them (each once), the right one the posture the arm is in.
/// An error where the target has fewer than two postures.
pub fn poll_request(app: &AppUi) -> Result<QuestionRequest, String> {
    let (state, ee) = (&app.state, app.ee());
    let mut choices: Vec<String> = Vec::new();
    let mut correct = None;
    for g in state.ghosts(ee) {
        let Some(p) = g.posture.posture() else {
            continue;
        };
        let name = p.to_string();
        let at_q = g.q.len() == state.q().len()
            && g.q.iter().zip(state.q()).all(|(a, b)| (a - b).abs() < 1e-6);
        let index = match choices.iter().position(|c| *c == name) {
            Some(i) => i,
            None => {
                choices.push(name);
                choices.len() - 1
            }
        };
        if at_q && correct.is_none() {
            correct = Some(index);
        }
    }
    choices.truncate(crate::class::protocol::MAX_CHOICES);
    if choices.len() < 2 {
        return Err(format!(
            "the target has {} posture(s): a poll needs two to choose from (move the target \
             where the arm has several solutions)",
            choices.len()
        ));
    }
    Ok(QuestionRequest {
        kind: QuestionKind::Poll,
        prompt: Some("Which posture is this?".into()),
        correct: correct.filter(|c| *c < choices.len()),
        choices,
        robot: None,
        seed: None,
        feedback: false,
    })
}

/// An exercise question of `kind` (on the session's robot, the seed drawn by the server).
pub fn exercise_request(kind: crate::exercise::Kind, feedback: bool) -> QuestionRequest {
    QuestionRequest {
        kind: QuestionKind::Exercise(kind),
        prompt: None,
        choices: Vec::new(),
        correct: None,
        robot: None,
        seed: None,
        feedback,
    }
}

/// Starts a class server in the app's process: on port
/// [`crate::class_server::DEFAULT_PORT`] (a free one if it is taken), on every network when
/// `reachable`, the class kept in `class.sqlite` in the app's data folder (else
/// `armlab-class.sqlite` in the current folder), the web build from `web/dist` where it is.
#[cfg(all(feature = "app", not(target_arch = "wasm32")))]
pub(super) fn start_server(
    reachable: bool,
) -> Result<crate::class_server::ServerHandle, crate::class_server::ServerError> {
    use crate::class_server::{DEFAULT_PORT, ServerError, ServerOptions, start};
    use std::net::{IpAddr, Ipv4Addr};
    let data = eframe::storage_dir(crate::app::APP_ID)
        .filter(|dir| std::fs::create_dir_all(dir).is_ok())
        .map_or_else(
            || std::path::PathBuf::from(crate::class_server::DEFAULT_DATA),
            |dir| dir.join("class.sqlite"),
        );
    let options = ServerOptions {
        bind: if reachable {
            IpAddr::V4(Ipv4Addr::UNSPECIFIED)
        } else {
            IpAddr::V4(Ipv4Addr::LOCALHOST)
        },
        port: DEFAULT_PORT,
        data,
        ..ServerOptions::default()
    };
    match start(options.clone()) {
        Err(ServerError::Bind { .. }) => start(ServerOptions { port: 0, ..options }),
        started => started,
    }
}
