//! What a workspace figure is drawn from (`workspace::figure_data`): one request computes the
//! statistics and the body the figure asked for, equal to the separate computations; Fig. 2.30's
//! marks (A-H) on the two-link arm with limits; the built-in arm of Figs 2.29-2.30 is the model
//! file `assets/robots/example_2_6.toml`.

use armlab::kinematics::models::built_in;
use armlab::model_file::load_model;
use armlab::workspace::{
    Content, ContentRequest, FigureRequest, MapRequest, MapView, SampleOptions, StatsOptions,
    TrackedPoint, compute_figure_data, compute_map, joint_rectangle, map_statistics,
};

#[test]
fn one_request_gives_what_the_separate_computations_give() {
    let robot = built_in("planar2_fig2_30").unwrap();
    let fallback = StatsOptions::for_figure(true, 10_000, 1, 0);
    let map = MapRequest {
        view: MapView::Plane,
        cells: [120, 90],
        bounds: Some([-2.2, 2.2, -2.2, 2.2]),
        ..MapRequest::default()
    };
    let req = FigureRequest {
        point: TrackedPoint::Flange,
        fallback: fallback.clone(),
        content: ContentRequest::Map(map.clone()),
    };
    let data = compute_figure_data(&robot, &req, &|_| {}).unwrap();
    assert_eq!(
        data.stats,
        map_statistics(&robot, TrackedPoint::Flange, &fallback).unwrap()
    );
    assert_eq!(
        data.content,
        Content::Map(compute_map(&robot, &map).unwrap())
    );
    // Fig. 2.30's letters, H where FD cuts BC at (1, 1) m.
    let marks = data
        .plane_marks
        .expect("the two-link arm with limits has Fig. 2.30's marks");
    let letters: Vec<&str> = marks.labels.iter().map(|(l, _)| l.as_str()).collect();
    assert_eq!(letters, ["A", "B", "C", "D", "E", "F", "H"]);
    let h = marks.labels.last().unwrap().1;
    assert!(
        (h[0] - 1.0).abs() < 1e-12 && (h[1] - 1.0).abs() < 1e-12,
        "{h:?}"
    );
    assert!(!marks.singular.is_empty());

    // The joint-space rectangle and a point cloud, the same way.
    let rect = FigureRequest {
        content: ContentRequest::JointRectangle,
        ..req.clone()
    };
    let data = compute_figure_data(&robot, &rect, &|_| {}).unwrap();
    assert_eq!(
        data.content,
        Content::JointRectangle(joint_rectangle(&robot).unwrap())
    );
    assert!(data.plane_marks.is_none());
    let cloud = FigureRequest {
        content: ContentRequest::Cloud(SampleOptions {
            samples: 1000,
            ..SampleOptions::default()
        }),
        ..req
    };
    match compute_figure_data(&robot, &cloud, &|_| {})
        .unwrap()
        .content
    {
        Content::Cloud(c) => assert_eq!(c.positions.len(), 1000),
        other => panic!("{other:?}"),
    }
}

#[test]
fn the_fig_2_30_arm_is_the_example_2_6_model_file() {
    let builtin = built_in("planar2_fig2_30").unwrap();
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/robots/example_2_6.toml"
    );
    let file = load_model(path).unwrap();
    assert_eq!(builtin.limits(), file.limits());
    for q in [[0.0, 0.0], [0.3, -1.2], [-1.5, 1.5], [1.1, 0.4]] {
        let (a, b) = (builtin.fk(&q).unwrap(), file.fk(&q).unwrap());
        assert!(
            (a.to_homogeneous() - b.to_homogeneous()).norm() < 1e-15,
            "{q:?}"
        );
    }
    assert_eq!(builtin.config("ready"), file.config("ready"));
    assert_eq!(builtin.config("figure"), file.config("figure"));
}
