//! Issue 48: `--scene` on `reach`, `self-motion`, `workspace` and `render`, run as a user runs
//! them. The postures and stretches they call free or colliding are checked with another
//! command, `armlab collisions` (the configurations they give), and `armlab fk` (that those
//! configurations reach the point); the existing JSON keys stay.

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

fn armlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(args)
        .env("WGPU_BACKEND", "vulkan")
        .output()
        .expect("run armlab")
}

fn json(o: &Output) -> Value {
    assert!(
        o.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("JSON on stdout")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("armlab-cell-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A table (top at z = 0.43 m, x from 0.6 to 1.6 m) and a floor at z = -0.7 m.
const CELL: &str = "[[obstacle]]\nname = \"table\"\nshape = \"box\"\nsize = [1.0, 1.2, 0.06]\n\
                    xyz = [1.1, 0.0, 0.4]\n\n[[obstacle]]\nname = \"floor\"\nshape = \"plane\"\n\
                    xyz = [0.0, 0.0, -0.7]\n";

/// What `armlab collisions` says of each configuration in the cell.
fn in_collision(dir: &std::path::Path, scene: &str, model: &str, qs: &[Vec<f64>]) -> Vec<bool> {
    let rows: Vec<String> = qs
        .iter()
        .map(|q| {
            q.iter()
                .map(|v| format!("{v:.17}"))
                .collect::<Vec<_>>()
                .join(",")
        })
        .collect();
    let input = dir.join("qs.txt");
    std::fs::write(&input, rows.join("\n")).unwrap();
    let v = json(&armlab(&[
        "collisions",
        model,
        "--input",
        input.to_str().unwrap(),
        "--scene",
        scene,
        "--format",
        "json",
    ]));
    v.as_array()
        .expect("one report per configuration")
        .iter()
        .map(|r| r["in_collision"].as_bool().expect("in_collision"))
        .collect()
}

/// A JSON array of strings.
fn strings(v: &Value) -> Vec<&str> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_str().expect("a string"))
        .collect()
}

/// A JSON array of numbers.
fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

/// `armlab fk` puts `model`'s tool at `p` (world, m) at `q`.
fn reaches(model: &str, q: &[f64], p: [f64; 3]) {
    let row: Vec<String> = q.iter().map(|v| format!("{v:.17}")).collect();
    let fk = json(&armlab(&[
        "fk",
        model,
        "--q",
        &row.join(","),
        "--format",
        "json",
    ]));
    let t = &fk[0]["T"];
    for (k, want) in p.iter().enumerate() {
        let got = t[k][3].as_f64().expect("T");
        assert!((got - want).abs() < 1e-9, "{q:?} reaches {t}, not {p:?}");
    }
}

#[test]
fn reach_lists_the_collision_free_postures_and_what_the_others_hit() {
    let dir = scratch("reach");
    let scene = dir.join("cell.toml");
    std::fs::write(&scene, CELL).unwrap();
    let scene = scene.to_str().unwrap();
    let points = dir.join("points.txt");
    // Under the table top, and far above everything.
    std::fs::write(&points, "1.0,0,0.2\n0.2,0.3,1.5\n").unwrap();
    let v = json(&armlab(&[
        "reach",
        "anthropomorphic3r",
        "--point",
        "flange",
        "--input",
        points.to_str().unwrap(),
        "--scene",
        scene,
        "--format",
        "json",
    ]));
    let rows = v.as_array().expect("one answer per point");
    let mut colliding = Vec::new();
    for (row, p) in rows.iter().zip([[1.0, 0.0, 0.2], [0.2, 0.3, 1.5]]) {
        for key in ["point", "reachable", "postures", "distance"] {
            assert!(row.get(key).is_some(), "{key} kept");
        }
        let (postures, free) = (
            strings(&row["postures"]),
            strings(&row["collision_free_postures"]),
        );
        let hit = row["colliding_postures"].as_array().unwrap();
        assert_eq!(free.len() + hit.len(), postures.len(), "{row}");
        assert_eq!(
            row["reachable_collision_free"],
            Value::Bool(!free.is_empty())
        );
        for h in hit {
            assert!(postures.contains(&h["posture"].as_str().unwrap()));
            assert!(!h["pairs"].as_array().unwrap().is_empty(), "{h}");
            let q = numbers(&h["q"]);
            reaches("anthropomorphic3r", &q, p);
            colliding.push(q);
        }
    }
    // Under the table some posture collides; far above, none does.
    assert!(!rows[0]["colliding_postures"].as_array().unwrap().is_empty());
    assert!(rows[1]["colliding_postures"].as_array().unwrap().is_empty());
    let checked = in_collision(&dir, scene, "anthropomorphic3r", &colliding);
    assert!(
        checked.iter().all(|c| *c),
        "`armlab collisions` says {checked:?}"
    );
}

#[test]
fn self_motion_json_keeps_its_keys_and_its_stretches_hit_what_collisions_says() {
    let dir = scratch("self-motion");
    let scene = dir.join("cell.toml");
    std::fs::write(
        &scene,
        "[[obstacle]]\nname = \"table\"\nshape = \"box\"\nsize = [0.6, 0.8, 0.04]\n\
         xyz = [0.55, 0.0, 0.1]\n",
    )
    .unwrap();
    let scene = scene.to_str().unwrap();
    let pose = "1,0,0,0.55,0,-1,0,0.1,0,0,-1,0.35,0,0,0,1";
    let v = json(&armlab(&[
        "self-motion",
        "lwr4",
        "--pose",
        pose,
        "--samples",
        "180",
        "--scene",
        scene,
        "--format",
        "json",
    ]));
    for key in ["parameter", "samples", "feasible", "manifolds", "singular"] {
        assert!(v.get(key).is_some(), "{key} kept");
    }
    let free = v["collision_free"]
        .as_object()
        .expect("collision_free per branch");
    let colliding = v["colliding"].as_object().expect("colliding per branch");
    let within = |list: &Value, t: f64| {
        list.as_array().unwrap().iter().any(|iv| {
            let iv = iv.as_array().unwrap();
            iv[0].as_f64().unwrap() <= t && t <= iv[1].as_f64().unwrap()
        })
    };
    let in_stretch = |list: &Value, t: f64| {
        list.as_array()
            .unwrap()
            .iter()
            .any(|s| s["from"].as_f64().unwrap() <= t && t <= s["to"].as_f64().unwrap())
    };
    let (mut qs, mut expect) = (Vec::new(), Vec::new());
    for sample in v["samples"].as_array().unwrap() {
        let t = sample["value"].as_f64().unwrap();
        for b in sample["branches"].as_array().unwrap() {
            let name = b["name"].as_str().unwrap();
            let q = numbers(&b["q"]);
            if within(&free[name], t) {
                qs.push(q);
                expect.push(false);
            } else if in_stretch(&colliding[name], t) {
                qs.push(q);
                expect.push(true);
            }
        }
    }
    assert!(
        expect.contains(&true) && expect.contains(&false),
        "{expect:?}"
    );
    assert_eq!(in_collision(&dir, scene, "lwr4", &qs), expect);
    for stretches in colliding.values() {
        for s in stretches.as_array().unwrap() {
            assert_eq!(s["b"], "table", "{s}");
        }
    }
    // The text names the pair.
    let text = armlab(&["self-motion", "lwr4", "--pose", pose, "--scene", scene]);
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(
        text.contains("collision-free arm angle") && text.contains("hits table"),
        "{text}"
    );
}

#[test]
fn workspace_and_render_draw_the_cell() {
    let dir = scratch("figures");
    let scene = dir.join("cell.toml");
    std::fs::write(&scene, CELL).unwrap();
    let scene = scene.to_str().unwrap();
    let png = dir.join("side.png");
    let v = json(&armlab(&[
        "workspace",
        "anthropomorphic3r",
        "--view",
        "side",
        "--scene",
        scene,
        "--size",
        "640x480",
        "--out",
        png.to_str().unwrap(),
        "--format",
        "json",
    ]));
    assert_eq!(v["scene"], scene);
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    let three_d = armlab(&[
        "workspace",
        "anthropomorphic3r",
        "--view",
        "3d",
        "--scene",
        scene,
        "--out",
        png.to_str().unwrap(),
    ]);
    assert_eq!(three_d.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&three_d.stderr).contains("--scene"));
    let render = dir.join("render.png");
    let o = armlab(&[
        "render",
        "anthropomorphic3r",
        "--scene",
        scene,
        "--size",
        "640x480",
        "--out",
        render.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::metadata(&render).unwrap().len() > 1000);
    // A scene naming a link the robot does not have: one line naming the file and obstacle.
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "[[obstacle]]\nname = \"tool\"\nshape = \"sphere\"\nsize = [0.1]\nxyz = [0, 0, 0]\n\
         frame = \"no_such_link\"\n",
    )
    .unwrap();
    let o = armlab(&[
        "reach",
        "anthropomorphic3r",
        "--input",
        "-",
        "--scene",
        bad.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("bad.toml") && err.contains("no_such_link") && !err.contains("panicked"));
}
