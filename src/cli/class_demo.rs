//! `armlab class demo`: a class rehearsed alone. A class server on this computer, the
//! teacher's app joined to it, and simulated students ([`crate::app::class::rehearsal`]) who
//! follow the arm and answer the questions asked, right or with the mistakes students make, so
//! that the tally fills as in a room. Real students may join too, with the printed link. With
//! `--screenshot` (the teacher's window once every student answered) or `--student-screenshot`
//! (a student's window with the question), nothing opens: the windows are rendered offscreen,
//! as the guide's pictures are.

use super::CliError;
use super::figures::Size;
use super::input::parse_row;
use crate::app::action::Action;
use crate::app::class::ClassAction;
use crate::app::class::rehearsal::{Pace, Rehearsal};
use crate::app::screenshot::OffscreenWindow;
use crate::app::shell::AppUi;
use crate::app::state::AppState;
use crate::app::{AppError, class};
use crate::class::protocol::{QuestionRequest, Role};
use crate::class_server::{self, ServerHandle, ServerOptions};
use crate::exercise::Kind;
use crate::kinematics::models::DEFAULT_MODEL;
use clap::ValueEnum;
use std::io::Write;
use std::net::{IpAddr, Ipv4Addr};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// How long the offscreen class may take to be ready for its picture.
const PICTURE_TIMEOUT: Duration = Duration::from_secs(60);

/// Arguments of `armlab class demo`.
#[derive(Debug, clap::Args)]
pub struct DemoArgs {
    /// Built-in name or path to a .toml / .urdf model (default: the anthropomorphic arm with
    /// spherical wrist).
    pub model: Option<String>,
    /// How many simulated students join.
    #[arg(long, default_value_t = 12, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=200))]
    pub students: u16,
    /// A question to ask at once (the app's Class window asks any later).
    #[arg(long, value_enum, value_name = "QUESTION")]
    pub ask: Option<AskArg>,
    /// Joint vector (rad, m) the teacher's arm starts at (the IK target on its tool).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
    /// Draws which simulated students err, and how; also the sheet of the exercise --ask asks
    /// (the same seed, the same sheet: a rehearsal or a picture made again shows the same arm).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Render the teacher's window, once every simulated student answered --ask (default
    /// dh-table), to this PNG and exit.
    #[arg(long, value_name = "FILE.png")]
    pub screenshot: Option<PathBuf>,
    /// Render a student's window, the question open in it, to this PNG and exit.
    #[arg(long, value_name = "FILE.png")]
    pub student_screenshot: Option<PathBuf>,
    /// Window size of the pictures, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x800")]
    pub size: Size,
    /// The SQLite file the class is kept in (default: a temporary file, removed at the end).
    #[arg(long, value_name = "FILE.sqlite")]
    pub data: Option<PathBuf>,
    /// The port (0: any free one; the links name it).
    #[arg(long, default_value_t = 0, value_name = "N")]
    pub port: u16,
}

/// The questions `--ask` asks: those the simulated students answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum AskArg {
    /// "Which posture is this?" (the IK solutions' postures at the arm's tool pose).
    Posture,
    /// The arm's DH table.
    DhTable,
    /// T at a given q.
    Fk,
    /// The Euler angles of a given rotation matrix.
    Euler,
    /// The unit quaternion of a given rotation matrix.
    Quaternion,
}

impl AskArg {
    /// The question the teacher's app asks.
    fn request(self, app: &AppUi) -> Result<QuestionRequest, String> {
        let kind = match self {
            AskArg::Posture => return class::poll_request(app),
            AskArg::DhTable => Kind::DhTable,
            AskArg::Fk => Kind::Fk,
            AskArg::Euler => Kind::Euler,
            AskArg::Quaternion => Kind::Quaternion,
        };
        Ok(class::exercise_request(kind, true))
    }
}

/// Runs `armlab class demo`.
pub fn run(args: &DemoArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let spec = args.model.as_deref().unwrap_or(DEFAULT_MODEL);
    let mut state = AppState::new(super::load_model(spec)?, spec);
    if let Some(text) = &args.q {
        let q = parse_row(text, "--q", state.robot().dof(), "joint values")?;
        let input = |e: String| CliError::App(AppError::Input(e));
        state.set_q(&q).map_err(|e| input(e.to_string()))?;
        let tool = state
            .robot()
            .fk(state.q())
            .map_err(|e| input(e.to_string()))?;
        state
            .set_target(0, tool)
            .map_err(|e| input(e.to_string()))?;
        state.clear_trails();
    }
    let temporary = args.data.is_none();
    let data = args.data.clone().unwrap_or_else(temporary_data);
    let server = class_server::start(ServerOptions {
        bind: IpAddr::V4(Ipv4Addr::LOCALHOST),
        port: args.port,
        data: data.clone(),
        web: None,
        show_names: true,
        new_session: true,
    })?;
    let pictures = args.screenshot.is_some() || args.student_screenshot.is_some();
    let pace = if pictures {
        Pace::AtOnce
    } else {
        Pace::Spread(Duration::from_secs(10))
    };
    let ws = format!("ws://{}/ws", server.addr);
    let n = usize::from(args.students);
    let room = Rehearsal::start(&ws, &server.code, n, args.seed, pace);
    let ran = if pictures {
        pictures_of(args, state, &server, &room, out)
    } else {
        live(args, spec, state, &server, out)
    };
    drop(room);
    let stopped = server.stop();
    if temporary {
        for suffix in ["", "-wal", "-shm"] {
            let _ = std::fs::remove_file(format!("{}{suffix}", data.display()));
        }
    }
    ran?;
    stopped?;
    Ok(())
}

/// A data file of its own in the temporary folder.
fn temporary_data() -> PathBuf {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    std::env::temp_dir().join(format!(
        "armlab-class-demo-{}-{nanos}.sqlite",
        std::process::id()
    ))
}

/// The teacher's app in a window, joined to the class; returns when it closes.
fn live(
    args: &DemoArgs,
    spec: &str,
    state: AppState,
    server: &ServerHandle,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    writeln!(out, "teacher: {}", server.teacher_url)?;
    writeln!(out, "students: {}", server.student_url)?;
    writeln!(
        out,
        "{} simulated students join; they answer polls and the {} exercises (others go \
         unanswered); real students may join with the link above",
        args.students,
        class::rehearsal::ANSWERED_KINDS.map(Kind::name).join(", ")
    )?;
    out.flush()?;
    if args.ask.is_some() {
        writeln!(
            out,
            "(--ask is for the pictures: in the window, the Class window asks)"
        )?;
    }
    let opts = crate::app::RunOptions {
        q: Some(state.q().to_vec()),
        model_given: true,
        class_teacher: Some(server.teacher_url.clone()),
        ..Default::default()
    };
    crate::app::run_with(spec, &opts).map_err(CliError::App)?;
    Ok(())
}

/// The pictures: the teacher's app (and a student's) laid out offscreen frame after frame
/// while the class runs, rendered when ready.
fn pictures_of(
    args: &DemoArgs,
    state: AppState,
    server: &ServerHandle,
    room: &Rehearsal,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let gpu = crate::render::Gpu::new_headless().map_err(crate::figure::FigureError::from)?;
    let n = usize::from(args.students);
    let ask = args.ask.unwrap_or(AskArg::DhTable);
    let mut teacher = AppUi::new(state);
    teacher.apply(Action::Class(ClassAction::JoinTeacher(
        server.teacher_url.clone(),
    )));
    teacher.class.window = true;
    // the arm framed from the start: the students follow this camera
    teacher.tabs.view3d.fit(&teacher.state);
    let mut teacher_window = OffscreenWindow::new(&gpu, args.size.0);
    let mut student = args
        .student_screenshot
        .as_ref()
        .map(|_| (student_app(server), OffscreenWindow::new(&gpu, args.size.0)));
    let joined = n + usize::from(student.is_some());
    let start = Instant::now();
    let mut asked = false;
    let mut waiting = "the students joining";
    loop {
        teacher_window.frame(&mut teacher).map_err(CliError::App)?;
        if let Some((app, window)) = &mut student {
            window.frame(app).map_err(CliError::App)?;
        }
        let c = &teacher.class;
        if let Some(e) = room.errors().first() {
            return Err(demo_error(format!(
                "the server refused a simulated student: {e}"
            )));
        }
        if !asked && c.role() == Some(Role::Teacher) && c.roster.joined >= joined {
            ask_now(&mut teacher, ask, args.seed)?;
            asked = true;
            waiting = "every simulated student's answer";
        } else if asked && ready(&teacher, student.as_ref().map(|s| &s.0), n) {
            break;
        }
        if start.elapsed() > PICTURE_TIMEOUT {
            return Err(not_ready(
                waiting,
                room,
                &teacher,
                student.as_ref().map(|s| &s.0),
            ));
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    // A frame more, so that the last tally's window is sized.
    teacher_window.frame(&mut teacher).map_err(CliError::App)?;
    if let Some(path) = &args.screenshot {
        let image = teacher_window
            .render(teacher, false)
            .map_err(CliError::App)?;
        write_picture(&image, path, out)?;
    }
    if let (Some(path), Some((mut app, mut window))) = (&args.student_screenshot, student) {
        window.frame(&mut app).map_err(CliError::App)?;
        let image = window.render(app, true).map_err(CliError::App)?;
        write_picture(&image, path, out)?;
    }
    Ok(())
}

/// A student of our own, in the app, joining (a built-in robot until the teacher's arrives).
fn student_app(server: &ServerHandle) -> AppUi {
    let mut app = AppUi::new(AppState::from_spec("planar2").expect("a built-in robot"));
    app.apply(Action::Class(ClassAction::JoinStudent {
        ws: format!("ws://{}/ws", server.addr),
        code: server.code.clone(),
        name: "Sam".into(),
        resume: None,
    }));
    app
}

/// The teacher's app asks `ask` (an exercise's sheet drawn from `seed`), its Class window's
/// kind box showing the kind asked as if chosen there.
fn ask_now(teacher: &mut AppUi, ask: AskArg, seed: u64) -> Result<(), CliError> {
    let mut request = ask.request(teacher).map_err(demo_error)?;
    if let crate::class::protocol::QuestionKind::Exercise(kind) = request.kind {
        teacher.class.form.kind = kind;
        request.seed = Some(seed);
    }
    teacher.apply(Action::Class(ClassAction::Ask(request)));
    Ok(())
}

/// Why the pictures could not be taken in time: what was awaited, and where things stood.
fn not_ready(
    waiting: &str,
    room: &Rehearsal,
    teacher: &AppUi,
    student: Option<&AppUi>,
) -> CliError {
    demo_error(format!(
        "waited {PICTURE_TIMEOUT:?} for {waiting} ({} answered; the tally counts {}; {})",
        room.answered(),
        teacher.class.tally.as_ref().map_or(0, |t| t.answered),
        student.map_or(String::new(), |s| format!(
            "the student's robot {}, question {}",
            s.state.robot().name,
            s.class.question.is_some()
        ))
    ))
}

/// The teacher's tally counts `n` answers, and the student (if any) has the question.
fn ready(teacher: &AppUi, student: Option<&AppUi>, n: usize) -> bool {
    let tallied = teacher
        .class
        .tally
        .as_ref()
        .is_some_and(|t| t.answered >= n);
    // the student's app has the question, and shows the teacher's arm (not the one it opened
    // with) or, for an exercise, the question's sheet in the Exercise tab
    let student_has_it = student.is_none_or(|s| {
        s.class.question.is_some()
            && (s.class.student_answering() || s.state.robot().name == teacher.state.robot().name)
    });
    tallied && student_has_it
}

fn demo_error(message: String) -> CliError {
    CliError::App(AppError::Input(format!("class demo: {message}")))
}

/// Writes `image` to `path` and says so.
fn write_picture(
    image: &image::RgbaImage,
    path: &std::path::Path,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    crate::headless::write_png(image, path)?;
    writeln!(
        out,
        "wrote {} ({}x{})",
        path.display(),
        image.width(),
        image.height()
    )?;
    Ok(())
}
