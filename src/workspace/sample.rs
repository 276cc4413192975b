//! Monte Carlo sampling of the reachable workspace (Sect. 2.10.1): joint vectors drawn uniformly
//! in the joint-limit box `q_im <= q_i <= q_iM`, mapped by direct kinematics `p_e = p_e(q)`.

use super::posture::PostureClassifier;
use super::rng::{Xoshiro256pp, uniform_q};
use super::{Aabb, Progress, WorkspaceError, check_ee, planar_frame};
use crate::kinematics::{Pose, Robot};
use nalgebra::{Matrix6xX, Rotation3};
use rayon::prelude::*;

/// Samples per chunk. Chunk k draws from its own stream seeded by `(seed, k)`, so the samples
/// depend on the seed and this constant, never on the number of threads.
pub const SAMPLE_CHUNK: usize = 4096;

/// What [`sample`] computes.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SampleOptions {
    /// Number of joint vectors.
    pub samples: usize,
    /// Seed of the generator (same seed, same samples).
    pub seed: u64,
    /// End-effector index.
    pub end_effector: usize,
    /// Compute the posture class of every sample ([`PostureClassifier`]).
    pub classes: bool,
    /// Compute the manipulability of every sample (one Jacobian and a small determinant each).
    pub manipulability: bool,
    /// Keep the joint vectors (`dof` values per sample).
    pub keep_joints: bool,
}

impl Default for SampleOptions {
    /// 100 000 samples, seed 1, end-effector 0, classes on, manipulability and joints off.
    fn default() -> Self {
        Self {
            samples: 100_000,
            seed: 1,
            end_effector: 0,
            classes: true,
            manipulability: false,
            keep_joints: false,
        }
    }
}

/// The result of [`sample`].
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct Samples {
    /// End-effector positions `p_e` in the world frame (m), one per sample.
    pub positions: Vec<[f64; 3]>,
    /// Posture class of each sample (index into `class_names`, or
    /// [`super::UNCLASSIFIED`]), when asked.
    pub classes: Option<Vec<u8>>,
    /// Names of the classes (always filled, `["all"]` for arms without postures).
    pub class_names: Vec<String>,
    /// Manipulability of each sample, when asked: `sqrt(det(J J^T))` (product of the singular
    /// values) of the task Jacobian, the x-y rows of the base frame for a planar arm (m^2 for
    /// two revolute columns), the three position rows for other arms with fewer than six joints,
    /// the full 6 x n geometric Jacobian otherwise; `sqrt(det(J^T J))` when J has fewer columns
    /// than rows.
    pub manipulability: Option<Vec<f32>>,
    /// Joint vectors, `dof` consecutive values per sample (rad or m), when asked.
    pub joints: Option<Vec<f64>>,
    /// Number of joints per sample in `joints`.
    pub dof: usize,
    /// The seed used.
    pub seed: u64,
    /// The end-effector index.
    pub end_effector: usize,
}

impl Samples {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// True when there are no samples.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// Joint vector of sample `i`, if the joints were kept.
    pub fn joint_vector(&self, i: usize) -> Option<&[f64]> {
        self.joints
            .as_ref()
            .map(|j| &j[i * self.dof..(i + 1) * self.dof])
    }

    /// Bounding box of the positions (world frame, m).
    pub fn bounds(&self) -> Aabb {
        let mut b = Aabb::EMPTY;
        for p in &self.positions {
            b.extend(*p);
        }
        b
    }

    /// Smallest and largest distance (m) of the positions from `origin` (world frame).
    pub fn reach_range(&self, origin: [f64; 3]) -> [f64; 2] {
        self.positions
            .iter()
            .fold([f64::INFINITY, 0.0], |[lo, hi], p| {
                let d = ((p[0] - origin[0]).powi(2)
                    + (p[1] - origin[1]).powi(2)
                    + (p[2] - origin[2]).powi(2))
                .sqrt();
                [lo.min(d), hi.max(d)]
            })
    }
}

/// The rows of the Jacobian whose manipulability is reported.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Task {
    /// x, y rows in the base frame (`base_from_world` rotation).
    Plane(Rotation3<f64>),
    /// The three position rows (world).
    Position,
    /// All six rows.
    Full,
}

impl Task {
    pub(crate) fn of(robot: &Robot, ee: usize) -> Task {
        if planar_frame(robot, ee).is_some() {
            Task::Plane(robot.base.rotation.inverse())
        } else if robot.dof() >= 6 {
            Task::Full
        } else {
            Task::Position
        }
    }

    /// `sqrt(det(J_t J_t^T))`, or `sqrt(det(J_t^T J_t))` when J_t has fewer columns than rows.
    /// Allocation-free.
    pub(crate) fn manipulability(self, jac: &Matrix6xX<f64>) -> f64 {
        let n = jac.ncols();
        let mut rows = [[0.0f64; 6]; 6];
        let mut cols = [[0.0f64; 6]; 6];
        let m = match self {
            Task::Plane(_) => 2,
            Task::Position => 3,
            Task::Full => 6,
        };
        let row = |c: usize| -> [f64; 6] {
            let v = jac.column(c);
            match self {
                Task::Plane(r) => {
                    let w = r * nalgebra::Vector3::new(v[0], v[1], v[2]);
                    [w.x, w.y, 0.0, 0.0, 0.0, 0.0]
                }
                Task::Position => [v[0], v[1], v[2], 0.0, 0.0, 0.0],
                Task::Full => [v[0], v[1], v[2], v[3], v[4], v[5]],
            }
        };
        if n >= m {
            // Gram matrix J J^T (m x m), any number of columns.
            for c in 0..n {
                let v = row(c);
                for i in 0..m {
                    for j in 0..m {
                        rows[i][j] += v[i] * v[j];
                    }
                }
            }
            det(&mut rows, m).max(0.0).sqrt()
        } else {
            for (c, col) in cols.iter_mut().enumerate().take(n) {
                *col = row(c);
            }
            for i in 0..n {
                for j in 0..n {
                    rows[i][j] = (0..m).map(|k| cols[i][k] * cols[j][k]).sum();
                }
            }
            det(&mut rows, n).max(0.0).sqrt()
        }
    }
}

/// Determinant of the top-left k x k block by Gaussian elimination with partial pivoting.
fn det(a: &mut [[f64; 6]; 6], k: usize) -> f64 {
    let mut d = 1.0;
    for c in 0..k {
        let p = (c..k)
            .max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))
            .unwrap_or(c);
        if a[p][c] == 0.0 {
            return 0.0;
        }
        if p != c {
            a.swap(p, c);
            d = -d;
        }
        d *= a[c][c];
        let pivot = a[c];
        for row in a.iter_mut().take(k).skip(c + 1) {
            let f = row[c] / pivot[c];
            for (x, p) in row[c..k].iter_mut().zip(&pivot[c..k]) {
                *x -= f * p;
            }
        }
    }
    d
}

struct Chunk<'a> {
    index: usize,
    pos: &'a mut [[f64; 3]],
    cls: Option<&'a mut [u8]>,
    man: Option<&'a mut [f32]>,
    q: Option<&'a mut [f64]>,
}

/// Cuts the output buffers into [`SAMPLE_CHUNK`]-sample chunks (`dof` values per sample of
/// `joints`).
fn split_chunks<'a>(
    positions: &'a mut [[f64; 3]],
    classes: Option<&'a mut [u8]>,
    manip: Option<&'a mut [f32]>,
    joints: Option<&'a mut [f64]>,
    dof: usize,
) -> Vec<Chunk<'a>> {
    let mut cls_it = classes.map(|c| c.chunks_mut(SAMPLE_CHUNK));
    let mut man_it = manip.map(|c| c.chunks_mut(SAMPLE_CHUNK));
    let mut q_it = joints.map(|c| c.chunks_mut(SAMPLE_CHUNK * dof.max(1)));
    positions
        .chunks_mut(SAMPLE_CHUNK)
        .enumerate()
        .map(|(index, pos)| Chunk {
            index,
            pos,
            cls: cls_it.as_mut().and_then(Iterator::next),
            man: man_it.as_mut().and_then(Iterator::next),
            q: q_it.as_mut().and_then(Iterator::next),
        })
        .collect()
}

/// What every chunk of [`sample`] shares.
struct ChunkSampler<'a> {
    robot: &'a Robot,
    ee: usize,
    seed: u64,
    classifier: &'a PostureClassifier,
    /// The classifier needs the whole pose, not only the position.
    needs_pose: bool,
    task: Task,
    limits: &'a [[f64; 2]],
}

impl ChunkSampler<'_> {
    /// Draws chunk `c`'s joint vectors from its own stream and fills its outputs.
    fn fill(&self, mut c: Chunk) -> Result<(), WorkspaceError> {
        let (robot, ee) = (self.robot, self.ee);
        let dof = robot.dof();
        let mut rng = Xoshiro256pp::stream(self.seed, c.index as u64);
        let mut q = vec![0.0; dof];
        let mut frames = c
            .man
            .is_some()
            .then(|| vec![Pose::identity(); robot.joints().len()]);
        let mut jac = Matrix6xX::zeros(dof);
        for i in 0..c.pos.len() {
            uniform_q(&mut rng, self.limits, &mut q);
            if let Some(cls) = c.cls.as_deref_mut().filter(|_| self.needs_pose) {
                let t = robot.fk_ee(&q, ee)?;
                let p = t.translation.vector;
                c.pos[i] = [p.x, p.y, p.z];
                cls[i] = self.classifier.classify(&q, &t);
            } else {
                // q is drawn inside the (finite) limits and ee was checked above.
                c.pos[i] = robot.fk_ee_position_prechecked(&q, ee);
                if let Some(cls) = c.cls.as_deref_mut() {
                    cls[i] = self.classifier.classify(&q, &Pose::identity());
                }
            }
            if let (Some(man), Some(frames)) = (c.man.as_deref_mut(), frames.as_mut()) {
                robot.jacobian_into(&q, ee, frames, &mut jac)?;
                man[i] = self.task.manipulability(&jac) as f32;
            }
            if let Some(qs) = c.q.as_deref_mut() {
                qs[i * dof..(i + 1) * dof].copy_from_slice(&q);
            }
        }
        Ok(())
    }
}

/// Samples the reachable workspace: `opts.samples` joint vectors drawn uniformly in the
/// joint-limit box and their end-effector positions (world frame, m), in parallel on rayon's
/// current pool.
///
/// The result depends only on the robot, `opts` and [`SAMPLE_CHUNK`], not on the number of threads.
/// `progress` is called from the workers after every chunk with the number of samples finished so
/// far (calls from different threads may arrive out of order). The loop over samples allocates
/// nothing (direct kinematics by [`Robot::fk_ee`]); the manipulability costs one
/// [`Robot::jacobian_into`] per sample.
///
/// # Examples
///
/// Two thousand samples of the two-link planar arm (a1 = a2 = 1 m, joints within [-pi, pi]):
/// every position lies within a1 + a2 of the base, and the same seed gives the same samples.
///
/// ```
/// use armlab::kinematics::models::built_in;
/// use armlab::workspace::{SampleOptions, sample};
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let arm = built_in("planar2").expect("a built-in model");
/// let opts = SampleOptions { samples: 2000, manipulability: true, ..SampleOptions::default() };
/// let s = sample(&arm, &opts, &|_done| {})?;
/// assert_eq!(s.len(), 2000);
/// let [_, max] = s.reach_range([0.0, 0.0, 0.0]);
/// assert!(max <= 2.0 + 1e-12 && max > 1.9);
/// assert_eq!(s.class_names, ["elbow down", "elbow up"]);
/// // Manipulability of the x-y rows: a1 a2 |sin q2| <= 1 m^2.
/// assert!(s.manipulability.as_ref().expect("asked for").iter().all(|&m| m <= 1.0 + 1e-6));
/// assert_eq!(sample(&arm, &opts, &|_| {})?.positions, s.positions);
/// # Ok(())
/// # }
/// ```
pub fn sample(
    robot: &Robot,
    opts: &SampleOptions,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Samples, WorkspaceError> {
    let ee = opts.end_effector;
    check_ee(robot, ee)?;
    let n = opts.samples;
    let dof = robot.dof();
    let classifier = PostureClassifier::for_end_effector(robot, ee);
    let limits = robot.sampling_ranges();
    let sampler = ChunkSampler {
        robot,
        ee,
        seed: opts.seed,
        classifier: &classifier,
        // Only closed-form posture rules need the whole pose; otherwise the position suffices.
        needs_pose: classifier.needs_pose(),
        task: Task::of(robot, ee),
        limits: &limits,
    };
    let mut positions = vec![[0.0; 3]; n];
    let mut classes = opts.classes.then(|| vec![0u8; n]);
    let mut manip = opts.manipulability.then(|| vec![0f32; n]);
    let mut joints = opts.keep_joints.then(|| vec![0f64; n * dof]);
    let chunks = split_chunks(
        &mut positions,
        classes.as_deref_mut(),
        manip.as_deref_mut(),
        joints.as_deref_mut(),
        dof,
    );
    let progress = Progress::new(progress);
    chunks.into_par_iter().try_for_each(|c| {
        let len = c.pos.len();
        sampler.fill(c)?;
        progress.add(len);
        Ok::<(), WorkspaceError>(())
    })?;
    Ok(Samples {
        positions,
        classes,
        class_names: classifier.class_names().to_vec(),
        manipulability: manip,
        joints,
        dof,
        seed: opts.seed,
        end_effector: ee,
    })
}
