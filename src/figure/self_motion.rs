//! The self-motion figure: every joint against the redundancy parameter for every branch, the
//! joint limits as dashed lines, the feasible stretches of each branch as bars under the curves.

use super::figures::Figures;
use super::palette::CLASS_COLORS;
use super::plot2d::{Area, Curve, Plot2d};
use super::{FigureError, Theme};
use crate::kinematics::Robot;
use crate::redundancy::sampler::SelfMotionSamples;
use egui::Color32;

/// Joint colours (colour-blind safe), by joint index (the animations' rate plot uses them too).
pub(crate) const JOINT_COLORS: [[u8; 3]; 7] = [
    [0, 114, 178],
    [213, 94, 0],
    [0, 158, 115],
    [204, 121, 167],
    [230, 159, 0],
    [86, 180, 233],
    [120, 120, 120],
];

/// The figure (1200 x 800, light theme) of a sampled self-motion: its samples (parameter value,
/// solutions), the feasible intervals of each branch (rad) and the branch names.
pub fn figure(
    figs: &mut Figures,
    robot: &Robot,
    motion: &SelfMotionSamples,
) -> Result<image::RgbaImage, FigureError> {
    figs.plot([1200, 800], Theme::Light, &plot_of(robot, motion), None)
}

/// The figure's plot: curves, limit lines and feasible bars.
fn plot_of(robot: &Robot, motion: &SelfMotionSamples) -> Plot2d {
    let SelfMotionSamples {
        parameter,
        samples,
        feasible,
        names,
        ..
    } = motion;
    let mut plot = Plot2d {
        title: format!("Self-motion of the {}", robot.name.to_lowercase()),
        subtitle: format!(
            "hand fixed; solid and dashed lines alternate by branch; bars: feasible {parameter} \
             inside the joint limits"
        ),
        x_label: format!("{parameter} [deg] (the free parameter)"),
        y_label: "joint angle [deg]".into(),
        bounds: [-180.0, 180.0, -200.0, 200.0],
        ..Plot2d::default()
    };
    let dof = robot.dof().min(JOINT_COLORS.len());
    for (b, name) in names.iter().enumerate() {
        // One branch: each joint's entry names it. Several: the joints once (their colours are
        // the same in every branch) and each branch by its feasible bar, so that the legend of
        // an SRS arm's eight branches is 15 entries, not 63 that run off the figure.
        let legend = match (names.len(), b) {
            (1, _) => Legend::JointAndBranch,
            (_, 0) => Legend::Joint,
            _ => Legend::None,
        };
        add_branch(&mut plot, b, name, samples, dof, legend);
        add_feasible_bars(&mut plot, b, name, &feasible[b]);
    }
    add_limit_lines(&mut plot, robot, dof);
    plot
}

/// How a branch's curves appear in the legend.
#[derive(Clone, Copy, PartialEq)]
enum Legend {
    /// "q1 (elbow up)".
    JointAndBranch,
    /// "q1".
    Joint,
    /// Not at all.
    None,
}

/// Branch `b`'s joint curves (the first `dof` joints), broken where a branch has no solution or
/// an angle wraps; solid for even branches, dashed for odd ones.
fn add_branch(
    plot: &mut Plot2d,
    b: usize,
    name: &str,
    samples: &[(f64, Vec<crate::redundancy::BranchSolution>)],
    dof: usize,
    legend: Legend,
) {
    for (j, c) in JOINT_COLORS.iter().copied().enumerate().take(dof) {
        let mut run: Vec<[f64; 2]> = Vec::new();
        let mut labelled = legend == Legend::None;
        let mut flush = |run: &mut Vec<[f64; 2]>| {
            if run.len() > 1 {
                plot.curves.push(Curve {
                    name: (!labelled).then(|| match legend {
                        Legend::JointAndBranch => format!("q{} ({name})", j + 1),
                        _ => format!("q{}", j + 1),
                    }),
                    points: std::mem::take(run),
                    color: Color32::from_rgb(c[0], c[1], c[2]),
                    width: 1.8,
                    dashed: b % 2 == 1,
                    ..Curve::default()
                });
                labelled = true;
            }
            run.clear();
        };
        for (phi, sols) in samples {
            match sols.iter().find(|s| s.name == name) {
                Some(s) => {
                    let p = [phi.to_degrees(), s.q[j].to_degrees()];
                    if run.last().is_some_and(|l| (l[1] - p[1]).abs() > 180.0) {
                        flush(&mut run);
                    }
                    run.push(p);
                }
                None => flush(&mut run),
            }
        }
        flush(&mut run);
    }
}

/// Branch `b`'s feasible intervals (rad) as bars in its posture colour under the curves.
fn add_feasible_bars(plot: &mut Plot2d, b: usize, name: &str, intervals: &[[f64; 2]]) {
    let c = CLASS_COLORS[b % CLASS_COLORS.len()];
    for iv in intervals {
        let y = -196.0 + 3.0 * b as f64;
        plot.areas.push(Area {
            name: format!("{name} feasible"),
            points: vec![
                [iv[0].to_degrees(), y],
                [iv[1].to_degrees(), y],
                [iv[1].to_degrees(), y + 2.0],
                [iv[0].to_degrees(), y + 2.0],
            ],
            fill: Color32::from_rgb(c[0], c[1], c[2]),
        });
    }
}

/// The finite joint limits of the first `dof` joints as dashed lines in the joints' colours.
fn add_limit_lines(plot: &mut Plot2d, robot: &Robot, dof: usize) {
    for (j, l) in robot.limits().iter().enumerate().take(dof) {
        let c = JOINT_COLORS[j];
        for v in l.iter().filter(|v| v.is_finite() && v.abs() < 3.5) {
            plot.curves.push(Curve {
                name: None,
                points: vec![[-180.0, v.to_degrees()], [180.0, v.to_degrees()]],
                color: Color32::from_rgba_unmultiplied(c[0], c[1], c[2], 140),
                width: 1.0,
                dashed: true,
                ..Curve::default()
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The legend entries of a plot: named curves and distinct area names.
    fn legend(plot: &Plot2d) -> Vec<String> {
        let mut names: Vec<String> = plot.curves.iter().filter_map(|c| c.name.clone()).collect();
        for a in &plot.areas {
            if !names.contains(&a.name) {
                names.push(a.name.clone());
            }
        }
        names
    }

    #[test]
    fn the_legend_of_eight_branches_fits_and_one_branch_names_its_joints() {
        let dlr = crate::kinematics::models::built_in("dlr").expect("built-in");
        let q = [0.3, 0.5, -0.2, 1.1, 0.4, -0.6, 0.2];
        let pose = dlr.fk(&q).expect("fk");
        let mut m = crate::redundancy::sampler::sample_self_motion_locked(&dlr, 0, &pose, 36, None)
            .expect("an exact self-motion");
        assert_eq!(m.names.len(), 8);
        let all = legend(&plot_of(&dlr, &m));
        // Seven joints and eight branches' bars (63 entries before, off the figure's edge).
        assert_eq!(all.len(), 15, "{all:?}");
        assert!(all.contains(&"q1".to_string()));
        let first = m.names[0].clone();
        m.keep_branch(&first).expect("a branch");
        let one = legend(&plot_of(&dlr, &m));
        assert!(one.contains(&format!("q1 ({first})")), "{one:?}");
    }
}
