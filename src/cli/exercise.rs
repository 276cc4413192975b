//! `armlab exercise new`, `check` and `grade`: sheets with figures and answer keys, grading by
//! equivalence ([`crate::exercise`]), and a class's folder of answers graded at once.

use super::CliError;
use super::figures::{Size, framing_camera};
use crate::camera::Preset;
use crate::exercise::{
    Answer, ClassGrades, Grade, Key, KeyAnswer, Kind, Sheet, StudentGrade, generate, grade,
    grade_dh, item_count,
};
use crate::figure::Theme;
use crate::figure::figures::{Figures, Scene3d};
use crate::headless::write_png;
use crate::scene::{ArmStyle, Dot, Label, arm_scene, frame_triad, point32};
use clap::{Subcommand, ValueEnum};
use std::io::Write;
use std::path::{Path, PathBuf};

/// `armlab exercise ...`.
#[derive(Debug, clap::Args)]
pub struct ExerciseArgs {
    /// What to do.
    #[command(subcommand)]
    pub action: ExerciseAction,
}

/// The exercise subcommands.
#[derive(Debug, Subcommand)]
pub enum ExerciseAction {
    /// Write sheets (question in Markdown and a figure) and, separately, their answer keys.
    New(NewArgs),
    /// Grade an answer against a key (or a DH table against a model with --against).
    Check(CheckArgs),
    /// Grade a class: every key of KEYS_DIR against the answer of the same stem in ANSWERS_DIR
    /// (`keys/student-07.json` and `answers/student-07.toml`); a CSV with one row per student
    /// and a summary of the mistakes made.
    Grade(GradeArgs),
}

/// The kinds on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum KindArg {
    /// Write the DH table of the arm drawn with its base and tool frames only.
    DhTable,
    /// T at a given q.
    Fk,
    /// Every solution of a pose, with its posture.
    Ik,
    /// Which points a two-link arm reaches, with how many postures; its workspace area.
    Workspace,
    /// n, m and r for a stated task.
    Redundancy,
    /// Which DH parameters a stated measurement setup cannot identify.
    Identifiability,
    /// The Euler angles (ZYZ, ZXZ or RPY) of a given rotation matrix.
    Euler,
    /// The matrix of a described sequence of rotations about current or fixed axes.
    Compose,
    /// The angle and axis of a given rotation matrix.
    AxisAngle,
    /// The unit quaternion of a given rotation matrix.
    Quaternion,
}

impl From<KindArg> for Kind {
    fn from(k: KindArg) -> Self {
        match k {
            KindArg::DhTable => Kind::DhTable,
            KindArg::Fk => Kind::Fk,
            KindArg::Ik => Kind::Ik,
            KindArg::Workspace => Kind::Workspace,
            KindArg::Redundancy => Kind::Redundancy,
            KindArg::Identifiability => Kind::Identifiability,
            KindArg::Euler => Kind::Euler,
            KindArg::Compose => Kind::Compose,
            KindArg::AxisAngle => Kind::AxisAngle,
            KindArg::Quaternion => Kind::Quaternion,
        }
    }
}

/// Arguments of `armlab exercise new`.
#[derive(Debug, clap::Args)]
pub struct NewArgs {
    /// The kind of exercise (or --kind KIND).
    #[arg(value_enum, required_unless_present = "kind_flag")]
    pub kind: Option<KindArg>,
    /// The kind of exercise, as a flag (instead of the first argument).
    #[arg(long = "kind", value_enum, id = "kind_flag", conflicts_with = "kind")]
    pub kind_flag: Option<KindArg>,
    /// The arm of every sheet (built-in name or model file); not for the orientation kinds
    /// (euler, compose, axis-angle, quaternion), which draw no arm.
    #[arg(long, conflicts_with = "random")]
    pub robot: Option<String>,
    /// A different textbook arm per sheet, with its lengths varied.
    #[arg(long)]
    pub random: bool,
    /// Seed: the same seed gives the same sheets.
    #[arg(long)]
    pub seed: u64,
    /// Number of students: one sheet each, all different.
    #[arg(long, visible_alias = "students", default_value_t = 1)]
    pub class: usize,
    /// Folder to write each student's `student-NN/sheet.md`, `student-NN/figure.png` and
    /// `student-NN/sheet.json` (the sheet the app opens in exam mode: no answer in it), and
    /// the teacher's `keys/student-NN.json`.
    #[arg(long)]
    pub out: PathBuf,
    /// Figure size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "960x720")]
    pub size: Size,
}

/// Arguments of `armlab exercise check`.
#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    /// KEY ANSWER, or only ANSWER with --against.
    #[arg(num_args = 1..=2, required = true)]
    pub files: Vec<PathBuf>,
    /// Grade a DH-table answer against this model (built-in name or file) instead of a key.
    #[arg(long)]
    pub against: Option<String>,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub format: super::Format,
}

/// Arguments of `armlab exercise grade`.
#[derive(Debug, clap::Args)]
pub struct GradeArgs {
    /// The keys' folder (`armlab exercise new`'s `keys/`).
    pub keys_dir: PathBuf,
    /// The answers' folder: one file per student, named as the student's key (any extension).
    pub answers_dir: PathBuf,
    /// Where to write the grades (CSV: student, answer, score, max, error, mistakes, items).
    #[arg(long)]
    pub out: PathBuf,
    /// The summary's format (text, or JSON with every student's items).
    #[arg(long, value_enum, default_value_t)]
    pub format: super::Format,
}

/// Runs `armlab exercise`.
pub(super) fn run(args: &ExerciseArgs, out: &mut dyn Write) -> Result<(), CliError> {
    match &args.action {
        ExerciseAction::New(a) => new(a, out),
        ExerciseAction::Check(a) => check(a, out),
        ExerciseAction::Grade(a) => grade_class(a, out),
    }
}

fn io_error(path: &Path, e: impl std::fmt::Display) -> CliError {
    CliError::Export(format!("{}: {e}", path.display()))
}

/// The kind asked for (first argument or --kind) and the arm of every sheet (`None`: drawn per
/// sheet, or none at all for the workspace and orientation kinds).
fn kind_and_robot(args: &NewArgs) -> Result<(Kind, Option<crate::kinematics::Robot>), CliError> {
    let kind: Kind = args
        .kind
        .or(args.kind_flag)
        .ok_or(CliError::Usage("give the kind of exercise"))?
        .into();
    let robot = match (&args.robot, args.random) {
        (Some(_), _) if kind.is_orientation() => {
            return Err(CliError::Usage(
                "an orientation exercise draws no arm: leave out --robot",
            ));
        }
        (Some(spec), _) => Some(super::load_model(spec)?),
        (None, true) => None,
        (None, false) if kind == Kind::Workspace || kind.is_orientation() => None,
        (None, false) => {
            return Err(CliError::Usage("give --robot MODEL or --random"));
        }
    };
    Ok((kind, robot))
}

/// `armlab exercise new`.
fn new(args: &NewArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (kind, robot) = kind_and_robot(args)?;
    if args.class == 0 {
        return Err(CliError::Usage("--class must be at least 1"));
    }
    let keys = args.out.join("keys");
    std::fs::create_dir_all(&keys).map_err(|e| io_error(&keys, e))?;
    let mut figures = Figures::new()?;
    for student in 1..=args.class {
        let sheet = generate(kind, robot.as_ref(), args.seed, student).map_err(|e| {
            CliError::BadTarget {
                source_name: "exercise new".into(),
                reason: e.to_string(),
            }
        })?;
        let dir = args.out.join(format!("student-{student:02}"));
        std::fs::create_dir_all(&dir).map_err(|e| io_error(&dir, e))?;
        let md = dir.join("sheet.md");
        // A compose sheet has no figure: its final frame is the answer.
        let drawn = kind != Kind::Compose;
        let text = format!(
            "{}\n{}Sheet {student} of {} (seed {}).\n",
            sheet.markdown,
            if drawn {
                "![figure](figure.png)\n\n"
            } else {
                ""
            },
            args.class,
            args.seed
        );
        std::fs::write(&md, text).map_err(|e| io_error(&md, e))?;
        let sheet_path = dir.join("sheet.json");
        let sheet_file =
            crate::exercise::SheetFile::of(&sheet).map_err(|e| CliError::BadTarget {
                source_name: "exercise new".into(),
                reason: e.to_string(),
            })?;
        let json = serde_json::to_string_pretty(&sheet_file).map_err(std::io::Error::from)?;
        std::fs::write(&sheet_path, json + "\n").map_err(|e| io_error(&sheet_path, e))?;
        let png = dir.join("figure.png");
        if drawn {
            let img = figure(&mut figures, &sheet, args.size.0)?;
            write_png(&img, &png)?;
        }
        let key_path = keys.join(format!("student-{student:02}.json"));
        let json = serde_json::to_string_pretty(&sheet.key).map_err(std::io::Error::from)?;
        std::fs::write(&key_path, json + "\n").map_err(|e| io_error(&key_path, e))?;
        let figure_name = if drawn {
            format!(", {}", png.display())
        } else {
            String::new()
        };
        writeln!(
            out,
            "wrote {}, {}{figure_name} and {} ({})",
            md.display(),
            sheet_path.display(),
            key_path.display(),
            sheet
                .robot
                .as_ref()
                .map_or(kind.name(), |r| r.name.as_str())
        )?;
    }
    Ok(())
}

/// The sheet's figure: the arm, with every DH frame or (dh-table) only the base and tool
/// frames; the ik target's frame; the workspace's points, numbered.
fn figure(
    figures: &mut Figures,
    sheet: &Sheet,
    size: [u32; 2],
) -> Result<image::RgbaImage, CliError> {
    let Some(robot) = &sheet.robot else {
        return frame_figure(figures, sheet, size);
    };
    let style = ArmStyle {
        frames: sheet.frames,
        frame_labels: sheet.frames,
        ..ArmStyle::default()
    };
    let mut scene = arm_scene(robot, &sheet.q, &style)?;
    let len = 0.18 * robot.characteristic_length().max(0.1);
    let n = robot.dof();
    if !sheet.frames {
        frame_triad(&mut scene, &robot.base, "0", len);
        frame_triad(&mut scene, &robot.fk(&sheet.q)?, &n.to_string(), len);
    }
    if let Some(t) = &sheet.target {
        frame_triad(&mut scene, t, "t", len);
    }
    let mut points = crate::scene::arm_points(robot, &sheet.q)?;
    for (i, p) in sheet.points.iter().enumerate() {
        let v = nalgebra::Vector3::new(p[0], p[1], p[2]);
        scene.dots.push(Dot {
            p: point32(&v).into(),
            color: [0.8, 0.1, 0.1, 1.0],
            size_px: 10.0,
        });
        scene.labels.push(Label {
            p: point32(&v).into(),
            text: (i + 1).to_string(),
            color: [0.8, 0.1, 0.1, 1.0],
            movable: true,
        });
        points.push(point32(&v));
    }
    let preset = if sheet.points.is_empty() {
        Preset::Iso
    } else {
        Preset::Top
    };
    let camera = framing_camera(preset, &points, size, false);
    let fig = Scene3d {
        title: format!(
            "Exercise {}, sheet {}",
            sheet.key.kind.name(),
            sheet.key.student
        ),
        subtitle: format!("{} joints", robot.dof()),
        scene: &scene,
        camera,
        legend: Vec::new(),
        caption: String::new(),
    };
    Ok(figures.scene(size, Theme::Light, &fig)?)
}

/// An orientation sheet's figure: the reference frame and the given frame (a rotation about
/// the origin), seen from the usual corner.
fn frame_figure(
    figures: &mut Figures,
    sheet: &Sheet,
    size: [u32; 2],
) -> Result<image::RgbaImage, CliError> {
    let mut scene = crate::scene::Scene::default();
    frame_triad(&mut scene, &crate::kinematics::Pose::identity(), "0", 1.0);
    if let Some(t) = &sheet.target {
        frame_triad(&mut scene, t, "", 0.7);
    }
    let corners = [-1.0, 1.0].map(|s| nalgebra::Vector3::new(s, s, s));
    let points: Vec<_> = corners.iter().map(point32).collect();
    let camera = framing_camera(Preset::Iso, &points, size, false);
    let fig = Scene3d {
        title: format!(
            "Exercise {}, sheet {}",
            sheet.key.kind.name(),
            sheet.key.student
        ),
        subtitle: "the reference frame (x0 y0 z0) and the given frame (x y z)".into(),
        scene: &scene,
        camera,
        legend: Vec::new(),
        caption: String::new(),
    };
    Ok(figures.scene(size, Theme::Light, &fig)?)
}

/// Reads an answer: a model file for dh-table, rows of numbers otherwise (`#` comments; a
/// first line `# deg` makes ik rows degrees), an orientation's own lines for those kinds.
fn read_answer(key: &Key, path: &Path) -> Result<Answer, CliError> {
    if matches!(key.answer, KeyAnswer::DhTable) {
        return Ok(Answer::Model(Box::new(super::load_model(
            &path.to_string_lossy(),
        )?)));
    }
    let text = std::fs::read_to_string(path).map_err(|e| io_error(path, e))?;
    if key.kind.is_orientation() {
        let name = path.display().to_string();
        let parsed = crate::exercise::orientation::parse_answer(key.kind, &text, &name);
        return parsed
            .map(Answer::Orientation)
            .map_err(|e| CliError::BadTarget {
                source_name: name,
                reason: e.to_string(),
            });
    }
    if matches!(key.answer, KeyAnswer::Identifiability { .. }) {
        return Ok(Answer::Words(crate::exercise::parse_words(&text)));
    }
    let rows = crate::exercise::parse_rows(&text, &path.display().to_string()).map_err(|e| {
        CliError::BadTarget {
            source_name: path.display().to_string(),
            reason: e.to_string(),
        }
    })?;
    Ok(Answer::Rows(rows))
}

/// `armlab exercise check`.
fn check(args: &CheckArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let grade_result = match (&args.against, args.files.as_slice()) {
        (Some(model), [answer]) => {
            let reference =
                crate::exercise::sheet_arm(&super::load_model(model)?, None).map_err(|e| {
                    CliError::BadTarget {
                        source_name: model.clone(),
                        reason: e.to_string(),
                    }
                })?;
            let answer = super::load_model(&answer.to_string_lossy())?;
            grade_dh(&reference, &answer, crate::exercise::Tolerance::default())
        }
        (None, [key_path, answer]) => {
            let text = std::fs::read_to_string(key_path).map_err(|e| io_error(key_path, e))?;
            let key: Key = serde_json::from_str(&text).map_err(|e| CliError::BadTarget {
                source_name: key_path.display().to_string(),
                reason: format!("not an armlab exercise key: {e}"),
            })?;
            let answer = read_answer(&key, answer)?;
            grade(&key, &answer).map_err(|e| CliError::BadTarget {
                source_name: args.files[1].display().to_string(),
                reason: e.to_string(),
            })?
        }
        (Some(_), _) => return Err(CliError::Usage("with --against give only the ANSWER file")),
        (None, _) => {
            return Err(CliError::Usage(
                "give KEY ANSWER (or --against MODEL ANSWER)",
            ));
        }
    };
    report(&grade_result, args.format, out)
}

fn report(g: &Grade, format: super::Format, out: &mut dyn Write) -> Result<(), CliError> {
    match format {
        super::Format::Json => {
            serde_json::to_writer_pretty(&mut *out, g).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        super::Format::Text => {
            writeln!(out, "score {} of {}", g.score, g.max)?;
            for i in &g.items {
                let mark = if i.correct { "ok   " } else { "WRONG" };
                if i.feedback.starts_with(&format!("{}:", i.item)) {
                    writeln!(out, "  {mark} {}", i.feedback)?;
                } else {
                    writeln!(out, "  {mark} {}: {}", i.item, i.feedback)?;
                }
            }
        }
    }
    Ok(())
}

/// The files of `dir` (not folders, not hidden), by stem; two files of one stem are an error.
fn files_by_stem(dir: &Path) -> Result<std::collections::BTreeMap<String, PathBuf>, CliError> {
    let mut found = std::collections::BTreeMap::new();
    let entries = std::fs::read_dir(dir).map_err(|e| io_error(dir, e))?;
    for entry in entries {
        let path = entry.map_err(|e| io_error(dir, e))?.path();
        let Some(stem) = path.file_stem().and_then(|s| s.to_str()) else {
            continue;
        };
        if !path.is_file() || stem.starts_with('.') {
            continue;
        }
        if let Some(other) = found.insert(stem.to_string(), path.clone()) {
            return Err(CliError::BadTarget {
                source_name: dir.display().to_string(),
                reason: format!(
                    "two files for {stem}: {} and {}; keep one",
                    other.display(),
                    path.display()
                ),
            });
        }
    }
    Ok(found)
}

/// Reads a key file.
fn read_key(path: &Path) -> Result<Key, CliError> {
    let text = std::fs::read_to_string(path).map_err(|e| io_error(path, e))?;
    serde_json::from_str(&text).map_err(|e| CliError::BadTarget {
        source_name: path.display().to_string(),
        reason: format!("not an armlab exercise key: {e}"),
    })
}

/// One student's line: the answer graded, or score 0 with why it could not be.
fn grade_student(stem: &str, key: &Key, answer: Option<&PathBuf>) -> StudentGrade {
    let zero = |error: String| {
        let g = Grade {
            score: 0,
            max: item_count(key),
            items: Vec::new(),
        };
        (g, error)
    };
    let Some(path) = answer else {
        let (grade, error) = zero("no answer".into());
        return StudentGrade {
            student: stem.to_string(),
            answer: None,
            grade,
            error: Some(error),
        };
    };
    let graded = read_answer(key, path).and_then(|a| {
        grade(key, &a).map_err(|e| CliError::BadTarget {
            source_name: path.display().to_string(),
            reason: e.to_string(),
        })
    });
    let (grade, error) = match graded {
        Ok(g) => (g, None),
        Err(e) => {
            let (g, e) = zero(e.to_string());
            (g, Some(e))
        }
    };
    StudentGrade {
        student: stem.to_string(),
        answer: path.file_name().map(|n| n.to_string_lossy().into_owned()),
        grade,
        error,
    }
}

/// `armlab exercise grade`.
fn grade_class(args: &GradeArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let keys = files_by_stem(&args.keys_dir)?;
    let keys: Vec<(String, PathBuf)> = keys
        .into_iter()
        .filter(|(_, p)| p.extension().is_some_and(|e| e == "json"))
        .collect();
    if keys.is_empty() {
        return Err(CliError::BadTarget {
            source_name: args.keys_dir.display().to_string(),
            reason: "no keys (*.json) here".into(),
        });
    }
    let mut answers = files_by_stem(&args.answers_dir)?;
    let mut students = Vec::new();
    for (stem, key_path) in &keys {
        let key = read_key(key_path)?;
        let answer = answers.remove(stem);
        students.push(grade_student(stem, &key, answer.as_ref()));
    }
    let unmatched = answers.values().map(|p| p.display().to_string()).collect();
    let class = ClassGrades::new(students, unmatched);
    std::fs::write(&args.out, class.csv()).map_err(|e| io_error(&args.out, e))?;
    match args.format {
        super::Format::Json => {
            serde_json::to_writer_pretty(&mut *out, &class).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        super::Format::Text => summary(&class, &args.out, out)?,
    }
    Ok(())
}

/// The class summary in words: how many answers, the mean score, each named mistake with how
/// many made it, what could not be graded.
fn summary(class: &ClassGrades, csv: &Path, out: &mut dyn Write) -> Result<(), CliError> {
    let n = class.students.len();
    let graded = class.students.iter().filter(|s| s.error.is_none()).count();
    let (score, max) = class
        .students
        .iter()
        .fold((0, 0), |(s, m), g| (s + g.grade.score, m + g.grade.max));
    writeln!(
        out,
        "graded {graded} of {n} students; {score} of {max} items right in all; wrote {}",
        csv.display()
    )?;
    if class.mistakes.is_empty() {
        writeln!(out, "no mistakes")?;
    } else {
        writeln!(out, "mistakes (students who made each):")?;
        for (m, count) in &class.mistakes {
            writeln!(out, "  {count:>3}  {m}")?;
        }
    }
    for s in class.students.iter().filter(|s| s.error.is_some()) {
        writeln!(
            out,
            "not graded: {}: {}",
            s.student,
            s.error.as_deref().unwrap_or_default()
        )?;
    }
    for a in &class.unmatched_answers {
        writeln!(out, "no key for the answer {a}")?;
    }
    Ok(())
}
