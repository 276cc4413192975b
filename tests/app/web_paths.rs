//! The web build's ways of doing what the desktop does, run natively (the browser itself is
//! tested by `web/test.sh`): the workspace job in slices with its statistics and map computed by
//! an offload worker (here a synchronous stand-in that runs the worker's own function) gives the
//! desktop's figure (to anti-aliased edges); the worker's answers, after the trip through a model file
//! and JSON, equal the direct computation. Needs a graphics adapter (fails without one).

use armlab::app::workspace_job::{JobFigure, OVERLAY_SAMPLES, WorkspaceJob};
use armlab::figure::workspace::WsView;
use armlab::kinematics::models::built_in;
use armlab::offload::{Answer, Offload, Part, Request, Spread, SpreadStep, answer, answer_forming};
use armlab::render::Gpu;
use armlab::workspace::{
    Content, ContentRequest, FigureRequest, MapRequest, MapValues, MapView, StatsOptions,
    TrackedPoint, compute_map, map_statistics,
};
use std::cell::RefCell;
use std::rc::Rc;

/// What a pool of in-place workers was asked and answered.
#[derive(Default)]
struct Counts {
    requests: usize,
    partials: usize,
    parts: Vec<String>,
}

/// A worker, run in place: each request answered over the next polls, as `worker.js` would:
/// every partial map (the figure as it forms), then the answer.
struct InPlace {
    pending: std::collections::VecDeque<String>,
    counts: Rc<RefCell<Counts>>,
}

impl Offload for InPlace {
    fn submit(&mut self, request: String) -> bool {
        let mut partials = Vec::new();
        let last = answer_forming(&request, &mut || true, &mut |p| partials.push(p));
        let mut c = self.counts.borrow_mut();
        c.requests += 1;
        c.partials += partials.len();
        let part = serde_json::from_str::<Request>(&request).unwrap().part;
        c.parts.push(format!("{part:?}").chars().take(12).collect());
        self.pending = partials.into_iter().chain([last]).collect();
        true
    }
    fn poll(&mut self) -> Option<String> {
        self.pending.pop_front()
    }
}

/// A pool of `n` in-place workers and what they are asked.
fn pool(n: usize) -> (Vec<Box<dyn Offload>>, Rc<RefCell<Counts>>) {
    let counts = Rc::new(RefCell::new(Counts::default()));
    let pool = (0..n)
        .map(|_| {
            Box::new(InPlace {
                pending: Default::default(),
                counts: counts.clone(),
            }) as Box<dyn Offload>
        })
        .collect();
    (pool, counts)
}

fn json(v: &impl serde::Serialize) -> serde_json::Value {
    serde_json::to_value(v).unwrap()
}

/// Equal, numbers to 1e-12 relative (sums over cells may be added in another order).
fn assert_close(a: &serde_json::Value, b: &serde_json::Value, at: &str) {
    use serde_json::Value as V;
    match (a, b) {
        (V::Number(x), V::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            assert!(
                (x - y).abs() <= 1e-12 * x.abs().max(y.abs()).max(1.0),
                "{at}: {x} vs {y}"
            );
        }
        (V::Array(x), V::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{at}");
            for (k, (p, q)) in x.iter().zip(y).enumerate() {
                assert_close(p, q, &format!("{at}[{k}]"));
            }
        }
        (V::Object(x), V::Object(y)) => {
            assert_eq!(x.len(), y.len(), "{at}");
            for (k, p) in x {
                assert_close(p, &y[k], &format!("{at}.{k}"));
            }
        }
        _ => assert_eq!(a, b, "{at}"),
    }
}

#[test]
fn the_sliced_job_with_a_worker_makes_the_desktops_figure() {
    let gpu = Gpu::new_headless().unwrap_or_else(|e| panic!("{e}"));
    for (name, workers) in [
        ("planar2", 1),
        ("puma560", 1),
        ("planar2", 3),
        ("puma560", 3),
    ] {
        let robot = built_in(name).unwrap();
        let view = if name == "planar2" {
            WsView::Plane
        } else {
            WsView::Top
        };
        let figure =
            JobFigure::Workspace(WorkspaceJob::options_for(&robot, view, [1200, 900], None));
        let title = robot.name.to_lowercase();
        let threaded = WorkspaceJob::start(
            robot.clone(),
            name.to_string(),
            title.clone(),
            figure.clone(),
        );
        threaded.wait();
        let sliced = WorkspaceJob::start_sliced(robot, name.to_string(), title, figure);
        let (mut workers, counts) = pool(workers);
        let (mut frames, mut previews) = (0, 0);
        while sliced.progress().is_some() {
            // A clock that runs 0.6 s per frame between frames (each picture of the figure as
            // it forms is due) and not within one (the overlay's chunks stop only when done).
            let at = frames as f64 * 0.6;
            sliced.step(Some(&gpu), &mut workers, &|| at);
            previews += usize::from(sliced.take_preview().is_some());
            frames += 1;
            std::thread::sleep(std::time::Duration::from_millis(2));
            assert!(
                frames < 10_000,
                "{name}: the sliced job never finishes (progress {:?})",
                sliced.progress()
            );
        }
        assert!(sliced.error().is_none(), "{name}: {:?}", sliced.error());
        assert!(
            sliced.figure_error().is_none(),
            "{name}: {:?}",
            sliced.figure_error()
        );
        let counts = counts.borrow();
        if workers.len() == 1 || name == "planar2" {
            assert_eq!(
                counts.requests, 1,
                "{name}: the statistics and the map go to one worker in one request"
            );
            assert!(counts.partials >= 1, "{name}: no partial map");
        } else {
            // The coarse look, the statistics, three tiles per worker (of 64-row multiples),
            // the finish.
            let parts = &counts.parts;
            assert_eq!(parts[..2], ["Coarse", "Stats"], "{name}: {parts:?}");
            let tiles = parts.iter().filter(|p| p.starts_with("Tile")).count();
            assert!(tiles >= 3, "{name}: {parts:?}");
            assert_eq!(parts.len(), tiles + 3, "{name}: {parts:?}");
            assert!(
                parts.last().unwrap().starts_with("Finish"),
                "{name}: {parts:?}"
            );
        }
        assert_eq!(sliced.dots().map(<[_]>::len), Some(OVERLAY_SAMPLES));
        // The figure formed on the page: the coarse look and, for the tiled map, tiles.
        assert!(previews >= 1, "{name}: the page painted no partial map");
        assert_eq!(sliced.previews() as usize, previews, "{name}");
        let (a, b) = (threaded.figure().unwrap(), sliced.figure().unwrap());
        assert_eq!(a.dimensions(), b.dimensions());
        // The same results painted: planned once, computed once, painted once, as the desktop
        // does it, so the pixels agree (the results themselves are compared exactly in the next
        // test). The allowance of 0.5 % of the pixels is for anti-aliased edges of glyphs, should
        // two devices rasterize them differently.
        let worst = a
            .as_raw()
            .iter()
            .zip(b.as_raw())
            .map(|(p, q)| p.abs_diff(*q))
            .max();
        let differ = a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count();
        if differ * 200 > a.pixels().len() {
            let dir = std::env::temp_dir();
            a.save(dir.join(format!("web_paths_{name}_threaded.png")))
                .unwrap();
            b.save(dir.join(format!("web_paths_{name}_sliced.png")))
                .unwrap();
            panic!(
                "{name}: the figures differ in {differ} pixels, by up to {worst:?} (both in {})",
                dir.display()
            );
        }
        assert!(frames >= 2, "{name}: {frames} frames");
    }
}

#[test]
fn the_workers_answers_equal_the_direct_computation() {
    for name in [
        "puma560",
        "anthropomorphic_spherical_wrist",
        "humanoid",
        "planar3",
    ] {
        let robot = built_in(name).unwrap();
        let fallback = StatsOptions {
            samples: 20_000,
            ..StatsOptions::default()
        };
        let point = TrackedPoint::WristCentre;
        let req = MapRequest {
            view: MapView::Top,
            point,
            values: MapValues::Classes,
            cells: [48, 36],
            bounds: Some([-2.0, 2.0, -1.5, 1.5]),
            samples: 20_000,
            seed: 3,
            end_effector: 0,
        };
        let task = FigureRequest {
            point,
            fallback: fallback.clone(),
            content: ContentRequest::Map(req.clone()),
        };
        // Edited (a new name): the robot travels as a model file, where it has one.
        let mut edited = robot.clone();
        edited.name = format!("{name} (edited)");
        let spec = if Request::new(&edited, name, task.clone()).is_ok() {
            "edited"
        } else {
            name
        };
        let sent = if spec == name { &robot } else { &edited };
        let request = serde_json::to_string(&Request::new(sent, spec, task).unwrap()).unwrap();
        match serde_json::from_str::<Answer>(&answer(&request)).unwrap() {
            Answer::Data(d) => {
                let direct = map_statistics(&robot, point, &fallback).unwrap();
                assert_close(&json(&d.stats), &json(&direct), name);
                assert_eq!(
                    d.content,
                    Content::Map(compute_map(&robot, &req).unwrap()),
                    "{name}"
                );
            }
            other => panic!("{name}: {other:?}"),
        }
    }
    // A request the worker cannot read is an answer, not a crash.
    assert!(matches!(
        serde_json::from_str::<Answer>(&answer("{not json")).unwrap(),
        Answer::Error(e) if e.contains("bad request")
    ));
}

/// Changing the model cancels the running job at once: its thread stops within the chunk of
/// samples it is on, so the next model's job does not share the CPU with it (the Stanford arm's
/// flange figure, the 64-direction approach scan, takes seconds when left to run: its top view
/// at 1600 x 1200 several in this build).
#[test]
fn a_cancelled_job_stops_computing_at_once() {
    let robot = armlab::kinematics::models::built_in("stanford").unwrap();
    let figure = JobFigure::Workspace(WorkspaceJob::options_for(
        &robot,
        armlab::figure::workspace::WsView::Top,
        [1600, 1200],
        None,
    ));
    let job = WorkspaceJob::start(robot, "stanford".into(), "Stanford".into(), figure);
    std::thread::sleep(std::time::Duration::from_millis(300));
    assert!(job.computing(), "the job should still be computing");
    let t = std::time::Instant::now();
    job.cancel();
    while job.computing() {
        assert!(
            t.elapsed().as_secs_f64() < 5.0,
            "the cancelled job's thread still runs after 5 s"
        );
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    assert!(job.is_cancelled());
    println!(
        "stopped {:.0} ms after the cancel",
        t.elapsed().as_secs_f64() * 1e3
    );
}

/// The desktop's job shows the figure as it forms (the coarse look, then tiles of the approach
/// scan) and ends with the one-shot figure, pixel for pixel.
#[test]
fn the_desktop_job_shows_the_figure_forming_and_ends_with_the_one_shot_figure() {
    let robot = built_in("stanford").unwrap();
    let opts = WorkspaceJob::options_for(&robot, WsView::Top, [1200, 900], None);
    let job = WorkspaceJob::start(
        robot.clone(),
        "stanford".into(),
        "stanford".into(),
        JobFigure::Workspace(opts.clone()),
    );
    let t = std::time::Instant::now();
    let (mut previews, mut first) = (Vec::new(), None);
    while job.progress().is_some() {
        if let Some(img) = job.take_preview() {
            first.get_or_insert(t.elapsed());
            previews.push(img);
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let formed_in = t.elapsed();
    assert!(job.error().is_none(), "{:?}", job.error());
    let t = std::time::Instant::now();
    let mut figs = armlab::figure::figures::Figures::new().unwrap_or_else(|e| panic!("{e}"));
    let one_shot =
        armlab::headless::workspace_figure(&mut figs, &robot, "stanford", &opts, &|_| {})
            .unwrap()
            .image;
    // The job also draws the overlay's 100,000 samples first.
    println!(
        "Stanford's top view: the job's first picture after {:.2} s, {} pictures, the finished \
         figure after {:.2} s; the one-shot figure alone {:.2} s",
        first.unwrap_or_default().as_secs_f64(),
        previews.len(),
        formed_in.as_secs_f64(),
        t.elapsed().as_secs_f64()
    );
    let formed = job.figure().expect("a figure");
    if formed != &one_shot {
        let dir = std::env::temp_dir();
        formed.save(dir.join("forming_formed.png")).unwrap();
        one_shot.save(dir.join("forming_one_shot.png")).unwrap();
        for (k, p) in previews.iter().enumerate() {
            p.save(dir.join(format!("forming_preview_{k}.png")))
                .unwrap();
        }
        let differ = formed
            .pixels()
            .zip(one_shot.pixels())
            .filter(|(p, q)| p != q);
        panic!(
            "the formed figure differs from the one-shot figure in {} pixels (both in {})",
            differ.count(),
            dir.display()
        );
    }
    assert!(
        previews.len() >= 2,
        "{} pictures while it formed (the coarse look and at least one tile)",
        previews.len()
    );
    assert!(
        previews
            .iter()
            .all(|p| p.dimensions() == one_shot.dimensions())
    );
    assert!(
        previews[0] != one_shot,
        "the first picture is the coarse look"
    );
}

/// A figure spread over a pool (the coarse look, the statistics, tiles answered in reverse
/// order, the finish), its parts travelling as JSON, ends with the one-shot data exactly; the
/// partial maps on the way hold the decided tiles' final cells.
#[test]
fn a_figure_spread_over_a_pool_ends_with_the_one_shot_data() {
    for (name, view, point) in [
        ("stanford", MapView::Top, TrackedPoint::Flange),
        (
            "anthropomorphic_spherical_wrist",
            MapView::Top,
            TrackedPoint::Flange,
        ),
        ("puma560", MapView::Side, TrackedPoint::WristCentre),
    ] {
        let robot = built_in(name).unwrap();
        let map = MapRequest {
            view,
            point,
            cells: [300, 260],
            bounds: Some([-1.4, 1.4, -1.2, 1.2]),
            samples: 20_000,
            ..MapRequest::default()
        };
        let task = FigureRequest {
            point,
            fallback: StatsOptions::for_figure(false, 20_000, 1, 0),
            content: ContentRequest::Map(map),
        };
        let one_shot = armlab::workspace::compute_figure_data(&robot, &task, &|_| {}).unwrap();
        let request = Request::new(&robot, name, task).unwrap();
        assert!(
            Spread::new(&robot, &request, 1).is_none(),
            "one worker: whole"
        );
        let mut spread = Spread::new(&robot, &request, 2).expect("a tiled map");
        let mut parts = Vec::new();
        while let Some(r) = spread.next_part() {
            parts.push(r);
        }
        // The coarse look and the statistics first, then the tiles (the finish waits).
        assert_eq!(parts[0].part, Part::Coarse);
        assert_eq!(parts[1].part, Part::Stats);
        let tiles = parts.len() - 2;
        assert!(tiles >= 5, "{name}: {tiles} tiles for two workers");
        let reply = |r: &Request| -> Answer {
            serde_json::from_str(&answer(&serde_json::to_string(r).unwrap())).unwrap()
        };
        let Content::Map(last) = &one_shot.content else {
            panic!()
        };
        let mut order: Vec<&Request> = parts.iter().collect();
        order[2..].reverse();
        let mut done = None;
        for r in order {
            match spread.take(reply(r)).unwrap() {
                SpreadStep::Partial(m, rows) => {
                    assert_eq!(m.masks.len(), last.masks.len());
                    if let Part::Tile([a, b]) = r.part {
                        let w = last.width;
                        assert_eq!(m.masks[a * w..b * w], last.masks[a * w..b * w], "{name}");
                        assert!(rows >= b - a);
                    }
                }
                SpreadStep::Done(_) => panic!("{name}: done before the finish"),
                SpreadStep::Working => {}
            }
        }
        let finish = spread
            .next_part()
            .expect("the finish once every tile is in");
        assert!(matches!(finish.part, Part::Finish(_)), "{name}");
        if let SpreadStep::Done(d) = spread.take(reply(&finish)).unwrap() {
            done = Some(d);
        }
        let done = done.expect("the data after the finish");
        assert!(
            *done == one_shot,
            "{name}: the spread data differ from the one-shot data"
        );
    }
}
