//! What a workspace figure is drawn from (`workspace::figure_data`): one request computes the
//! statistics and the body the figure asked for, equal to the separate computations; Fig. 2.30's
//! marks (A-H) on the two-link arm with limits; the built-in arm of Figs 2.29-2.30 is the model
//! file `assets/robots/example_2_6.toml`; a figure that forms tile by tile ends with the one-shot
//! data.

use armlab::kinematics::models::built_in;
use armlab::model_file::load_model;
use armlab::workspace::map::padded;
use armlab::workspace::{
    Content, ContentRequest, FigureRequest, MapForming, MapRequest, MapView, SampleOptions,
    Section, StatsOptions, TILE_ROWS, TrackedPoint, WorkspaceMap, compute_figure_data,
    compute_figure_data_forming, compute_map, joint_rectangle, map_extent, map_statistics,
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

/// Records what a forming computation hands over.
#[derive(Default)]
struct Recorder {
    partials: Vec<(WorkspaceMap, usize)>,
}

impl MapForming for Recorder {
    fn wants(&mut self) -> bool {
        true
    }
    fn partial(&mut self, map: &WorkspaceMap, rows_done: usize) {
        self.partials.push((map.clone(), rows_done));
    }
}

/// A figure that forms (a coarse first look, then tiles) ends with the one-shot data, exactly;
/// each partial map's decided rows are already the final cells, the rows below them come from a
/// coarse look that mostly agrees with the final map, and a sampled map's partials only grow.
#[test]
fn a_forming_figure_ends_with_the_one_shot_data() {
    let cases = [
        ("stanford", MapView::Top, TrackedPoint::Flange, true),
        (
            "anthropomorphic_spherical_wrist",
            MapView::Top,
            TrackedPoint::Flange,
            true,
        ),
        ("puma560", MapView::Side, TrackedPoint::WristCentre, true),
        ("planar4", MapView::Plane, TrackedPoint::Flange, false),
        ("planar2", MapView::Plane, TrackedPoint::Flange, false),
    ];
    for (name, view, point, tiled) in cases {
        let robot = built_in(name).unwrap();
        let planar = view == MapView::Plane;
        let map = MapRequest {
            view,
            point,
            cells: [240, 200],
            bounds: Some(padded(&map_extent(&robot, view, point, 0).unwrap(), 0.06)),
            samples: 20_000,
            ..MapRequest::default()
        };
        let req = FigureRequest {
            point,
            fallback: StatsOptions::for_figure(planar, 20_000, 1, 0),
            content: ContentRequest::Map(map.clone()),
        };
        let one_shot = compute_figure_data(&robot, &req, &|_| {}).unwrap();
        let mut rec = Recorder::default();
        let formed = compute_figure_data_forming(&robot, &req, &|_| {}, &mut rec).unwrap();
        assert_eq!(one_shot.stats, formed.stats, "{name}: stats");
        if let (Content::Map(a), Content::Map(b)) = (&one_shot.content, &formed.content) {
            let d = a.masks.iter().zip(&b.masks).filter(|(x, y)| x != y).count();
            assert_eq!(d, 0, "{name}: masks differ in {d} cells");
            assert_eq!(a.edges, b.edges, "{name}: edges");
            assert_eq!(a.curves, b.curves, "{name}: curves");
        }
        let again = compute_figure_data(&robot, &req, &|_| {}).unwrap();
        assert!(
            again == one_shot,
            "{name}: the one-shot is not deterministic"
        );
        assert!(one_shot == formed, "{name}: the formed data differ");
        let Content::Map(last) = &formed.content else {
            panic!("{name}: no map")
        };
        let (w, h) = (last.width, last.height);
        let (coarse, rows) = &rec.partials[0];
        assert_eq!(*rows, 0, "{name}: the coarse look comes first");
        let agree = coarse.masks.iter().zip(&last.masks).filter(|(a, b)| a == b);
        let agree = agree.count() as f64 / (w * h) as f64;
        assert!(agree > 0.9, "{name}: the coarse look agrees on {agree}");
        if tiled {
            // 200 rows: tiles end at 64, 128 and 192 (the last one is the final map).
            let done: Vec<usize> = rec.partials.iter().map(|p| p.1).collect();
            assert_eq!(done, [0, TILE_ROWS, 2 * TILE_ROWS, 3 * TILE_ROWS], "{name}");
        }
        for (p, rows) in &rec.partials {
            assert_eq!((p.width, p.height, p.bounds), (w, h, last.bounds), "{name}");
            if *rows > 0 && *rows < h {
                let k = rows * w;
                assert_eq!(p.masks[..k], last.masks[..k], "{name}: rows above {rows}");
            }
            if *rows == h {
                let grew = p.masks.iter().zip(&last.masks).all(|(a, b)| a & !b == 0);
                assert!(
                    grew,
                    "{name}: a sampled map's partial is not within the final one"
                );
            }
        }
        if name == "planar4" {
            assert!(rec.partials.len() >= 3, "{name}: the rim refined in tiles");
        }
    }
}

/// The side view's masks, decided tile by tile, are the exact point test at every cell centre
/// (the centres computed here).
#[test]
fn the_tiled_side_view_is_the_point_test_at_every_cell_centre() {
    let robot = built_in("puma560").unwrap();
    let section = Section::new(&robot, TrackedPoint::WristCentre).unwrap();
    let bounds = [-0.1, 1.0, -0.8, 1.2];
    let (w, h) = (150, 140);
    let map = compute_map(
        &robot,
        &MapRequest {
            view: MapView::Side,
            point: TrackedPoint::WristCentre,
            cells: [w, h],
            bounds: Some(bounds),
            ..MapRequest::default()
        },
    )
    .unwrap();
    let mut reached = 0;
    for j in 0..h {
        for i in 0..w {
            let x = bounds[0] + (i as f64 + 0.5) / w as f64 * (bounds[1] - bounds[0]);
            let y = bounds[3] - (j as f64 + 0.5) / h as f64 * (bounds[3] - bounds[2]);
            let want = if x < 0.0 { 0 } else { section.side_mask(x, y) };
            assert_eq!(map.masks[j * w + i], want, "cell ({i}, {j})");
            reached += usize::from(want != 0);
        }
    }
    assert!(reached > w * h / 4, "{reached} cells reached");
}
