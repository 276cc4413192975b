//! The pose a model opens at (in the app, the screenshots): its "ready" configuration when that
//! shows the arm well, otherwise the best of a fixed set of candidates, with the reason.
//!
//! A pose shows the arm well when it is away from every singularity (no condition of
//! [`SingularityAnalyzer::classify`], at or near) and, for an arm with a closed form, when every
//! posture of its tool pose (Sect. 2.12) lies inside the joint limits, so that a class can step
//! through all of them. Where no candidate has every posture inside the limits, the one with the
//! most is taken and the note says so.

use super::ik::closed_form::ClosedForm;
use super::ik::{IkStatus, Target};
use super::robot::Robot;
use super::singularity::SingularityAnalyzer;

/// How many candidates are tried after the named configurations (deterministic).
const CANDIDATES: usize = 400;

/// The pose a model opens at.
#[derive(Debug, Clone, PartialEq)]
pub struct OpeningPose {
    /// Joint values (rad or m), inside the limits.
    pub q: Vec<f64>,
    /// Why it is not "ready" (or why not every posture can be shown), in one sentence; `None`
    /// when "ready" (or zero) is used as it is.
    pub note: Option<String>,
}

/// How well a pose shows the arm; larger is better (compared field by field, in order).
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd)]
struct Score {
    /// Away from every singularity.
    regular: bool,
    /// Every closed-form posture inside the limits (true without a closed form).
    all_postures: bool,
    /// Postures inside the limits.
    postures_in: usize,
    /// Minus the distance (rad or m, summed) from "ready": the familiar pose, moved as little as
    /// it takes.
    closeness: f64,
}

/// Scores poses of one robot against its "ready" pose.
struct Scorer<'a> {
    robot: &'a Robot,
    analyzer: SingularityAnalyzer,
    closed: Option<ClosedForm>,
    ready: &'a [f64],
    /// The end-effectors that must be away from singularities: every arm's tool (a tree's
    /// arms each open regular, not only the default one: Baxter's left arm opened near one).
    tools: Vec<usize>,
}

impl Scorer<'_> {
    /// The score of `q` and the number of postures of its tool pose; `None` where it cannot be
    /// analysed (or its pose is out of reach of the closed form).
    fn score(&self, q: &[f64]) -> Option<(Score, usize)> {
        let robot = self.robot;
        let mut regular = true;
        for &ee in &self.tools {
            regular &= self.analyzer.classify(robot, q, ee).ok()?.is_none();
        }
        let closeness = -q
            .iter()
            .zip(self.ready)
            .map(|(a, b)| (a - b).abs())
            .sum::<f64>();
        let (in_limits, total) = match &self.closed {
            Some(cf) => {
                let pose = robot.fk_ee(q, 0).ok()?;
                let r = cf.solve(robot, &Target::Pose(pose)).ok()?;
                if matches!(r.status, IkStatus::Unreachable { .. }) {
                    return None;
                }
                let inside = r.solutions.iter().filter(|s| s.within_limits).count();
                (inside, r.solutions.len())
            }
            None => (0, 0),
        };
        let s = Score {
            regular,
            all_postures: in_limits == total,
            postures_in: in_limits,
            closeness,
        };
        Some((s, total))
    }
}

/// The pose `robot` opens at: "ready" (or zero) if it scores as well as any candidate can
/// (regular, every posture inside the limits), else the best candidate.
pub fn opening_pose(robot: &Robot) -> OpeningPose {
    let n = robot.dof();
    let limits = robot.limits();
    let mut ready = robot.ready_or_zero();
    clamp(&mut ready, &limits);
    if n == 0 || robot.end_effectors().is_empty() {
        return OpeningPose {
            q: ready,
            note: None,
        };
    }
    let scorer = Scorer {
        robot,
        analyzer: SingularityAnalyzer::new(robot),
        closed: if robot.end_effectors().len() == 1 {
            ClosedForm::detect(robot).ok()
        } else {
            None
        },
        ready: &ready,
        tools: {
            let tools = super::end_effectors::catalog(robot).tools();
            if tools.is_empty() { vec![0] } else { tools }
        },
    };
    let ready_score = scorer.score(&ready);
    if let Some((s, _)) = ready_score
        && s.regular
        && s.all_postures
    {
        return OpeningPose {
            q: ready,
            note: None,
        };
    }
    let best = candidates(robot, &ready, &limits)
        .into_iter()
        .filter_map(|q| scorer.score(&q).map(|(s, total)| (s, total, q)))
        .max_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal));
    let Some((best_score, total, q)) = best else {
        return OpeningPose {
            q: ready,
            note: Some("no candidate pose could be scored; opened at \"ready\"".into()),
        };
    };
    OpeningPose {
        q,
        note: Some(note(ready_score, best_score, total)),
    }
}

/// Clamps `q` into `limits`.
fn clamp(q: &mut [f64], limits: &[[f64; 2]]) {
    for (v, [lo, hi]) in q.iter_mut().zip(limits) {
        *v = v.clamp(*lo, *hi);
    }
}

/// The named configurations, then [`CANDIDATES`] poses spread around "ready" (deterministic).
fn candidates(robot: &Robot, ready: &[f64], limits: &[[f64; 2]]) -> Vec<Vec<f64>> {
    let n = robot.dof();
    let mut out: Vec<Vec<f64>> = robot
        .configurations
        .iter()
        .filter(|c| c.q.len() == n)
        .map(|c| c.q.clone())
        .collect();
    let mut rng = 7u64;
    let ranges = robot.sampling_ranges();
    for _ in 0..CANDIDATES {
        let mut q: Vec<f64> = ready
            .iter()
            .zip(&ranges)
            .map(|(&r, [lo, hi])| {
                let u = unit(&mut rng) - 0.5;
                // Around "ready", at most a third of the range away: the familiar pose, moved off
                // its singularity.
                r + u * (hi - lo) / 1.5
            })
            .collect();
        clamp(&mut q, limits);
        out.push(q);
    }
    out
}

/// Why the pose is not "ready", and what it could not achieve.
fn note(ready: Option<(Score, usize)>, best: Score, total: usize) -> String {
    let why_not_ready = match ready {
        Some((s, _)) if !s.regular => "\"ready\" is at or near a singularity".to_string(),
        Some((s, t)) => format!(
            "at \"ready\" only {} of the {t} postures are inside the joint limits",
            s.postures_in
        ),
        None => "\"ready\" could not be analysed".to_string(),
    };
    let mut note = format!("opened near \"ready\": {why_not_ready}");
    if !best.all_postures {
        note.push_str(&format!(
            "; no pose tried has every posture inside the limits (this one has {} of {total})",
            best.postures_in
        ));
    }
    note
}

/// A uniform number in [0, 1) from a SplitMix64 state (deterministic candidates).
fn unit(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}
