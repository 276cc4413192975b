//! Which singularity an arm is at, named from its geometry (`kinematics::singularity`): the
//! wrist, elbow and shoulder singularities of the anthropomorphic arm with spherical wrist and the
//! Puma 560, the aligned links of a planar arm, and a plain loss of rank for other arms.

use armlab::kinematics::Robot;
use armlab::kinematics::models::{anthropomorphic_spherical_wrist, planar2, puma560};
use armlab::kinematics::singularity::{Proximity, SingularityAnalyzer, SingularityKind, classify};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

#[test]
fn singularities_are_named_by_kind() {
    let kinds = |r: &Robot, q: &[f64]| classify(r, q, 0).unwrap().map(|x| x.kinds());
    // Anthropomorphic arm with spherical wrist (a2 = d4 = 0.5 m).
    let r = anthropomorphic_spherical_wrist();
    let q = |t3: f64, t5: f64| [0.0, FRAC_PI_4, t3, 0.0, t5, 0.0];
    assert_eq!(kinds(&r, &q(FRAC_PI_4, FRAC_PI_4)), None);
    assert_eq!(
        kinds(&r, &q(FRAC_PI_4, 0.0)),
        Some(vec![SingularityKind::Wrist])
    );
    let near = classify(&r, &q(FRAC_PI_4, 0.005), 0).unwrap().unwrap();
    assert_eq!(near.proximity, Proximity::Near);
    assert!(
        near.message().starts_with("near a wrist singularity"),
        "{}",
        near.message()
    );
    // theta3 = pi/2: stretched; theta3 = pi with theta2 = pi/4: wrist centre on axis 1.
    assert_eq!(
        kinds(&r, &q(FRAC_PI_2, 0.7)),
        Some(vec![SingularityKind::Elbow])
    );
    let at = classify(&r, &q(FRAC_PI_2, 0.7), 0).unwrap().unwrap();
    assert!(
        at.message().starts_with("at an elbow singularity"),
        "{}",
        at.message()
    );
    assert_eq!(at.proximity, Proximity::At);
    assert_eq!(
        kinds(&r, &q(PI, 0.7)),
        Some(vec![SingularityKind::Shoulder])
    );
    let both = kinds(&r, &q(FRAC_PI_2, 0.0)).unwrap();
    assert!(both.contains(&SingularityKind::Wrist) && both.contains(&SingularityKind::Elbow));

    // Puma 560: "ready" has the wrist singular (theta5 = 0); stretched arm with the a3 offset;
    // the wrist centre on the shoulder-offset plane.
    let r = puma560();
    let rk = kinds(&r, r.config("ready").unwrap()).unwrap();
    assert!(rk.contains(&SingularityKind::Wrist), "{rk:?}");
    assert_eq!(kinds(&r, &[0.3, 0.4, -2.0, 0.1, 0.5, 0.0]), None);
    let elbow = (0.0203f64).atan2(0.4318); // theta3 where axes 2, 3 and W are in one plane
    let rk = kinds(&r, &[0.3, 0.4, -FRAC_PI_2 + elbow, 0.1, 0.5, 0.0]).unwrap();
    assert_eq!(rk, vec![SingularityKind::Elbow]);
    let a = SingularityAnalyzer::new(&r);
    assert_eq!(a.task_rank(0), 6);

    // Two-link planar arm: links aligned, stretched or folded.
    let r = planar2();
    assert_eq!(
        kinds(&r, &[0.3, 0.0]),
        Some(vec![SingularityKind::PlanarElbow])
    );
    assert_eq!(
        kinds(&r, &[0.3, PI]),
        Some(vec![SingularityKind::PlanarElbow])
    );
    assert_eq!(kinds(&r, &[0.3, 1.0]), None);
    assert_eq!(SingularityAnalyzer::new(&r).task_rank(0), 2);

    // Other arms: by rank only.
    let r = armlab::kinematics::models::dlr();
    let rep = classify(&r, &[0.0; 7], 0).unwrap().unwrap();
    assert!(matches!(
        rep.kinds()[0],
        SingularityKind::RankDeficient { rank, of: 6 } if rank < 6
    ));
    assert!(
        rep.message().contains("rank-deficient (rank"),
        "{}",
        rep.message()
    );
}

/// Issue 46, item 9: near (not at) a singularity no named kind explains, the words do not say
/// "rank 6 of 6 ... singularity" (which contradicts itself): they say what the hand does.
#[test]
fn an_unnamed_near_singularity_says_what_the_hand_does() {
    let r = armlab::kinematics::models::dlr();
    let mut seen = 0;
    for k in 1..=60 {
        let t = 0.002 * k as f64;
        let q = [0.0, t, 0.0, 0.5 * t, 0.0, t, 0.0];
        let Some(rep) = classify(&r, &q, 0).unwrap() else {
            continue;
        };
        let full = rep
            .kinds()
            .iter()
            .all(|k| matches!(k, SingularityKind::RankDeficient { rank, of } if rank >= of));
        let msg = rep.message();
        if full {
            seen += 1;
            assert!(!msg.contains("rank 6 of 6"), "{msg}");
            assert!(msg.contains("barely moves"), "{msg}");
            assert!(msg.contains("a singular configuration:"), "{msg}");
        }
    }
    assert!(seen > 0, "no near, full-rank report along the path");
}
