//! `armlab collisions` and the collision fields of `armlab ik`, run as a user runs them: the
//! issue's JSON keys, obstacles placed by hand around points the test's own `fk` call puts on a
//! link (must collide) or far from the arm (must not, with the clearance measured by hand), the
//! allowed-collision matrix on the UR5 and Panda corpus files against their URDF joints read
//! here, SRDF and model-file round trips, and bad scene files (a clear line naming the file, the
//! line and the obstacle, exit code 2, never a panic).

use serde_json::Value;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn armlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(args)
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

/// Exit code 2, nothing on stdout, one line on stderr holding every needle, no panic.
fn bad(o: &Output, needles: &[&str]) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(
        o.stdout.is_empty(),
        "partial output: {}",
        String::from_utf8_lossy(&o.stdout)
    );
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "one line expected: {err}"
    );
    for n in needles {
        assert!(err.contains(n), "{n:?} not in {err:?}");
    }
    assert!(!err.contains("panicked"));
}

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("armlab-coll-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

/// The keys of a JSON object.
fn keys(v: &Value) -> BTreeSet<&str> {
    v.as_object()
        .unwrap_or_else(|| panic!("not an object: {v}"))
        .keys()
        .map(String::as_str)
        .collect()
}

/// Every joint frame's origin (world, m) at `q` (radians), from `armlab fk --frames`.
fn frame_origins(model: &str, q: &str) -> Vec<[f64; 3]> {
    let v = json(&armlab(&[
        "fk", model, "--q", q, "--frames", "--format", "json",
    ]));
    v[0]["frames"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| {
            let t = &f["T"];
            std::array::from_fn(|i| t[i][3].as_f64().unwrap())
        })
        .collect()
}

/// A box obstacle as a scene file's table.
fn box_table(name: &str, size: [f64; 3], xyz: [f64; 3]) -> String {
    format!(
        "[[obstacle]]\nname = \"{name}\"\nshape = \"box\"\nsize = [{}, {}, {}]\nxyz = [{}, {}, {}]\n",
        size[0], size[1], size[2], xyz[0], xyz[1], xyz[2]
    )
}

const ISSUE_KEYS: [&str; 4] = ["in_collision", "pairs", "clearance_m", "closest"];

#[test]
fn one_configuration_answers_with_exactly_the_issues_keys() {
    let v = json(&armlab(&[
        "collisions",
        "puma560",
        "--q",
        "0,0,0,0,0,0",
        "--format",
        "json",
    ]));
    assert_eq!(keys(&v), BTreeSet::from(ISSUE_KEYS));
    assert_eq!(v["in_collision"], false);
    assert_eq!(v["pairs"], Value::Array(Vec::new()));
    assert!(v["clearance_m"].as_f64().unwrap() > 0.0);
    assert_eq!(keys(&v["closest"]), BTreeSet::from(["a", "b"]));
    // Degrees for revolute joints, as the other commands take them: the same answer.
    let deg = json(&armlab(&[
        "collisions",
        "puma560",
        "--q-deg",
        "0,0,0,0,0,0",
        "--format",
        "json",
    ]));
    assert_eq!(deg, v);
}

#[test]
fn a_box_around_a_point_on_a_link_collides_and_one_far_away_does_not() {
    let dir = scratch("probe");
    let q = "0.3,-0.8,1.9,0.2,0.5,0.1";
    // The elbow's frame origin: the stick figure's links run through every frame origin.
    let p = frame_origins("puma560", q)[2];
    let half = 0.04;
    let near = write(&dir, "near.toml", &box_table("probe", [2.0 * half; 3], p));
    let v = json(&armlab(&[
        "collisions",
        "puma560",
        "--q",
        q,
        "--scene",
        &near,
        "--format",
        "json",
    ]));
    assert_eq!(keys(&v), BTreeSet::from(ISSUE_KEYS));
    assert_eq!(v["in_collision"], true, "{v}");
    assert_eq!(v["clearance_m"], 0.0);
    let pairs = v["pairs"].as_array().unwrap();
    let probe: Vec<&Value> = pairs.iter().filter(|c| c["b"] == "probe").collect();
    assert!(!probe.is_empty(), "{v}");
    for c in pairs {
        let k = keys(c);
        assert!(k.is_superset(&BTreeSet::from(["a", "b", "depth_m"])), "{c}");
        assert!(
            k.is_subset(&BTreeSet::from(["a", "b", "depth_m", "at"])),
            "{c}"
        );
        assert!(c["depth_m"].as_f64().unwrap() > 0.0);
    }
    // A link through the box's centre: to separate them, the box must move by more than its
    // half-width (its inscribed ball holds a point of the link).
    let deepest = probe
        .iter()
        .map(|c| c["depth_m"].as_f64().unwrap())
        .fold(0.0, f64::max);
    assert!(deepest >= half, "depth {deepest} < {half}: {v}");
    // The text names the pair.
    let text =
        String::from_utf8(armlab(&["collisions", "puma560", "--q", q, "--scene", &near]).stdout)
            .unwrap();
    assert!(text.contains("hits probe"), "{text}");

    // A slab 1 m above the highest frame origin, the arm's own pairs all disabled by an SRDF
    // written here: the clearance is the slab's height over the arm's top, which lies between
    // the highest frame origin (on the arm) and a few link radii above it.
    let origins = frame_origins("puma560", q);
    let top = origins.iter().map(|o| o[2]).fold(f64::MIN, f64::max);
    let bottom = top + 1.0;
    let slab = write(
        &dir,
        "far.toml",
        &box_table("slab", [20.0, 20.0, 0.1], [0.0, 0.0, bottom + 0.05]),
    );
    let links = ["base", "link1", "link2", "link3", "link4", "link5", "link6"];
    let mut srdf = String::from("<robot name=\"puma\">\n");
    for (i, a) in links.iter().enumerate() {
        for b in &links[i + 1..] {
            srdf += &format!("<disable_collisions link1=\"{a}\" link2=\"{b}\" reason=\"User\"/>\n");
        }
    }
    srdf += "</robot>\n";
    let srdf = write(&dir, "all.srdf", &srdf);
    let v = json(&armlab(&[
        "collisions",
        "puma560",
        "--q",
        q,
        "--scene",
        &slab,
        "--srdf",
        &srdf,
        "--format",
        "json",
    ]));
    assert_eq!(v["in_collision"], false, "{v}");
    assert_eq!(v["closest"]["b"], "slab");
    let clearance = v["clearance_m"].as_f64().unwrap();
    assert!(clearance <= 1.0 + 1e-9, "{clearance}");
    assert!(clearance >= 1.0 - 0.1, "{clearance}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn input_answers_every_row_in_order() {
    let dir = scratch("input");
    let q_hit = "0.3,-0.8,1.9,0.2,0.5,0.1";
    let p = frame_origins("puma560", q_hit)[2];
    let scene = write(&dir, "cell.toml", &box_table("probe", [0.08; 3], p));
    // The second row turns the whole arm half a turn about the base: the elbow is then on the
    // other side of the base, about 2 |p_xy| from the box.
    let far = "3.4415926535897931,-0.8,1.9,0.2,0.5,0.1";
    assert!(p[0].hypot(p[1]) > 0.3, "{p:?}");
    let rows = write(&dir, "q.txt", &format!("# two rows\n{q_hit}\n\n{far}\n"));
    let v = json(&armlab(&[
        "collisions",
        "puma560",
        "--input",
        &rows,
        "--scene",
        &scene,
        "--format",
        "json",
    ]));
    let list = v.as_array().expect("a list for --input");
    assert_eq!(list.len(), 2);
    for r in list {
        assert_eq!(keys(r), BTreeSet::from(ISSUE_KEYS));
    }
    assert_eq!(list[0]["in_collision"], true);
    assert!(
        !list[1]["pairs"]
            .as_array()
            .unwrap()
            .iter()
            .any(|c| c["b"] == "probe"),
        "{}",
        list[1]
    );
    // Text: a line saying what is checked, then one line per row.
    let text = String::from_utf8(
        armlab(&["collisions", "puma560", "--input", &rows, "--scene", &scene]).stdout,
    )
    .unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 3, "{text}");
    assert!(
        lines[1].starts_with("q = [0.3, -0.8, 1.9, 0.2, 0.5, 0.1] (rad): ")
            && lines[1].contains("hits probe"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The `(parent, child)` link pairs of a URDF's joints, read here from the XML.
fn urdf_joint_pairs(path: &str) -> Vec<(String, String)> {
    let text = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    doc.descendants()
        .filter(|n| n.has_tag_name("joint") && n.parent().is_some_and(|p| p.has_tag_name("robot")))
        .map(|j| {
            let link = |tag: &str| {
                j.children()
                    .find(|c| c.has_tag_name(tag))
                    .and_then(|c| c.attribute("link"))
                    .unwrap()
                    .to_string()
            };
            (link("parent"), link("child"))
        })
        .collect()
}

/// A pair's key, names in order.
fn pair_key(a: &str, b: &str) -> (String, String) {
    if a <= b {
        (a.into(), b.into())
    } else {
        (b.into(), a.into())
    }
}

#[test]
fn the_matrix_of_the_corpus_arms_disables_every_joints_links_and_counts_right() {
    for file in ["ur5_robot.urdf", "panda.urdf"] {
        let model = format!("tests/data/urdf_corpus/{file}");
        let o = armlab(&[
            "collisions",
            &model,
            "--matrix",
            "--samples",
            "2000",
            "--format",
            "json",
        ]);
        let v = json(&o);
        // The meshes of the corpus are not in the repository: said on stderr, naming the links.
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("warning") && err.contains("link"), "{err}");
        assert_eq!(v["samples"], 2000);
        let pairs = v["pairs"].as_array().unwrap();
        let by_key: BTreeMap<(String, String), &Value> = pairs
            .iter()
            .map(|p| {
                (
                    pair_key(p["a"].as_str().unwrap(), p["b"].as_str().unwrap()),
                    p,
                )
            })
            .collect();
        assert_eq!(by_key.len(), pairs.len(), "a pair listed twice");
        let joints = urdf_joint_pairs(&model);
        assert!(joints.len() >= 6);
        for (parent, child) in &joints {
            let p = by_key
                .get(&pair_key(parent, child))
                .unwrap_or_else(|| panic!("{file}: no pair {parent} {child}"));
            assert_eq!(p["reason"], "Adjacent", "{file}: {p}");
        }
        let mut disabled = 0;
        for p in pairs {
            let k = keys(p);
            assert_eq!(
                k,
                BTreeSet::from(["a", "b", "reason", "collided", "samples", "why"]),
                "{p}"
            );
            let (n, of) = (
                p["collided"].as_u64().unwrap(),
                p["samples"].as_u64().unwrap(),
            );
            match p["reason"].as_str().unwrap() {
                "Adjacent" => assert_eq!(of, 0),
                "Never" => assert_eq!((n, of), (0, 2000), "{p}"),
                "Always" => assert!(n as f64 >= 0.95 * 2000.0, "{p}"),
                "Checked" => assert!(n > 0 && n < 2000, "{p}"),
                "Default" => assert!(of == 2000, "{p}"),
                other => panic!("{file}: reason {other}"),
            }
            if p["reason"] != "Checked" {
                disabled += 1;
            }
            assert!(!p["why"].as_str().unwrap().is_empty());
        }
        assert_eq!(v["disabled"], disabled);
        assert_eq!(v["checked"], pairs.len() - disabled);
        // In words: every pair on its own line.
        let text = String::from_utf8(
            armlab(&["collisions", &model, "--matrix", "--samples", "2000"]).stdout,
        )
        .unwrap();
        for p in pairs {
            let (a, b) = (p["a"].as_str().unwrap(), p["b"].as_str().unwrap());
            assert!(
                text.lines()
                    .any(|l| l.split_whitespace().take(2).eq([a, b])),
                "{file}: no line for {a} {b}"
            );
        }
    }
}

/// The disabled pairs of a matrix printed as JSON, with their reasons.
fn disabled_pairs(v: &Value) -> BTreeMap<(String, String), String> {
    v["pairs"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["reason"] != "Checked")
        .map(|p| {
            (
                pair_key(p["a"].as_str().unwrap(), p["b"].as_str().unwrap()),
                p["reason"].as_str().unwrap().to_string(),
            )
        })
        .collect()
}

#[test]
fn an_srdf_written_reads_back_to_the_same_pairs() {
    let dir = scratch("srdf");
    let model = "tests/data/urdf_corpus/ur5_robot.urdf";
    let srdf = dir.join("ur5.srdf").display().to_string();
    let sampled = json(&armlab(&[
        "collisions",
        model,
        "--matrix",
        "--samples",
        "1000",
        "--write-srdf",
        &srdf,
        "--format",
        "json",
    ]));
    let want = disabled_pairs(&sampled);
    // The file holds one element per disabled pair, read here with an XML parser.
    let text = std::fs::read_to_string(&srdf).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let in_file: BTreeMap<(String, String), String> = doc
        .descendants()
        .filter(|n| n.has_tag_name("disable_collisions"))
        .map(|n| {
            (
                pair_key(n.attribute("link1").unwrap(), n.attribute("link2").unwrap()),
                n.attribute("reason").unwrap().to_string(),
            )
        })
        .collect();
    assert_eq!(in_file, want);
    // Read back: the same pairs disabled, for the same reasons; every other pair checked.
    let read = json(&armlab(&[
        "collisions",
        model,
        "--srdf",
        &srdf,
        "--format",
        "json",
    ]));
    assert_eq!(read["source"], "srdf");
    assert_eq!(disabled_pairs(&read), want);
    assert_eq!(
        read["pairs"].as_array().unwrap().len(),
        sampled["pairs"].as_array().unwrap().len()
    );
    // And the checks use it: a configuration's checked pairs are the matrix's checked ones.
    let text = String::from_utf8(
        armlab(&["collisions", model, "--srdf", &srdf, "--q", "0,-1,1,0,1,0"]).stdout,
    )
    .unwrap();
    let checked = read["checked"].as_u64().unwrap();
    assert!(
        text.contains(&format!("; {checked} pairs of bodies checked")),
        "{checked}: {text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_matrix_stored_in_a_model_file_reads_back_to_the_same_pairs() {
    let dir = scratch("model");
    let out = dir.join("puma.toml").display().to_string();
    let sampled = json(&armlab(&[
        "collisions",
        "puma560",
        "--matrix",
        "--samples",
        "500",
        "--save-model",
        &out,
        "--format",
        "json",
    ]));
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(
        text.matches("[[disable_collisions]]").count(),
        sampled["disabled"].as_u64().unwrap() as usize
    );
    let stored = json(&armlab(&[
        "collisions",
        &out,
        "--write-srdf",
        &dir.join("p.srdf").display().to_string(),
        "--format",
        "json",
    ]));
    assert_eq!(stored["source"], "model");
    assert_eq!(disabled_pairs(&stored), disabled_pairs(&sampled));
    // The model is the same robot: the same forward kinematics.
    let q = "0.3,-0.8,1.9,0.2,0.5,0.1";
    for (a, b) in frame_origins(&out, q)
        .iter()
        .zip(frame_origins("puma560", q))
    {
        assert!((0..3).all(|i| (a[i] - b[i]).abs() < 1e-12), "{a:?} {b:?}");
    }
    // A URDF cannot be written as a TOML model file: refused before sampling, with the way out.
    let o = armlab(&[
        "collisions",
        "tests/data/urdf_corpus/ur5_robot.urdf",
        "--matrix",
        "--save-model",
        &dir.join("ur5.toml").display().to_string(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--write-srdf"));
    assert!(!dir.join("ur5.toml").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn ik_solutions_say_what_they_hit() {
    let dir = scratch("ik");
    let q = "0.3,-0.8,1.9,0.2,0.5,0.1";
    let t = json(&armlab(&["fk", "puma560", "--q", q, "--format", "json"]));
    let pose: Vec<String> = t[0]["T"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.to_string()))
        .collect();
    let pose = pose.join(",");
    // Without a scene: every solution still says whether the arm hits itself.
    let v = json(&armlab(&[
        "ik", "puma560", "--pose", &pose, "--all", "--format", "json",
    ]));
    let sols = v[0]["solutions"].as_array().unwrap();
    assert_eq!(sols.len(), 8);
    let want = BTreeSet::from([
        "q",
        "posture",
        "posture_parts",
        "within_limits",
        "position_error",
        "orientation_error",
        "free_joints",
        "collision",
        "clearance_m",
    ]);
    for s in sols {
        assert_eq!(keys(s), want, "{s}");
        assert!(s["collision"].is_null() || s["collision"].is_array());
    }
    // A box around the elbow of one solution: that solution hits it.
    let hit: Vec<String> = sols[0]["q"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.to_string())
        .collect();
    let p = frame_origins("puma560", &hit.join(","))[2];
    let scene = write(&dir, "cell.toml", &box_table("probe", [0.08; 3], p));
    let v = json(&armlab(&[
        "ik", "puma560", "--pose", &pose, "--all", "--scene", &scene, "--format", "json",
    ]));
    let first = &v[0]["solutions"][0];
    assert_eq!(first["q"], sols[0]["q"]);
    let contacts = first["collision"].as_array().expect("a list of contacts");
    assert!(contacts.iter().any(|c| c["b"] == "probe"), "{first}");
    assert_eq!(first["clearance_m"], 0.0);
    for c in contacts {
        assert!(keys(c).is_superset(&BTreeSet::from(["a", "b", "depth_m"])));
    }
    // The text says it under the solution.
    let text = String::from_utf8(
        armlab(&["ik", "puma560", "--pose", &pose, "--all", "--scene", &scene]).stdout,
    )
    .unwrap();
    assert_eq!(text.matches("    collision: ").count(), 8, "{text}");
    assert!(text.contains("hits probe"), "{text}");
    // A bad scene stops ik before anything is printed.
    let bad_scene = write(
        &dir,
        "bad.toml",
        "[[obstacle]]\nname = \"slab\"\nshape = \"box\"\nsize = [1, 0, 1]\n",
    );
    bad(
        &armlab(&["ik", "puma560", "--pose", &pose, "--scene", &bad_scene]),
        &["bad.toml:1", "\"slab\"", "degenerate"],
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_scenes_name_the_file_the_line_and_the_obstacle() {
    let dir = scratch("bad");
    std::fs::write(dir.join("empty.stl"), "").unwrap();
    let preamble =
        "# a cell\n\n[[obstacle]]\nname = \"floor\"\nshape = \"plane\"\nxyz = [0, 0, -1]\n";
    let cases: [(&str, &str, &str, &[&str]); 5] = [
        (
            "degenerate.toml",
            "slab",
            "shape = \"box\"\nsize = [1.0, 0.0, 0.5]\n",
            &["degenerate"],
        ),
        (
            "missing.toml",
            "fixture",
            "shape = \"mesh\"\nmesh = \"no_such_file.stl\"\n",
            &["no_such_file.stl"],
        ),
        (
            "empty.toml",
            "fixture",
            "shape = \"mesh\"\nmesh = \"empty.stl\"\n",
            &["empty.stl"],
        ),
        (
            "nan.toml",
            "ball",
            "shape = \"sphere\"\nsize = [0.1]\nxyz = [nan, 0, 0]\n",
            &["xyz", "not finite"],
        ),
        (
            "frame.toml",
            "gripper",
            "shape = \"sphere\"\nsize = [0.05]\nframe = \"link9\"\n",
            &["link9"],
        ),
    ];
    for (file, name, body, needles) in cases {
        let path = write(
            &dir,
            file,
            &format!("{preamble}[[obstacle]]\nname = \"{name}\"\n{body}"),
        );
        let named = format!("\"{name}\"");
        let mut all = vec![file, ":7:", named.as_str()];
        all.extend_from_slice(needles);
        for format in ["text", "json"] {
            bad(
                &armlab(&[
                    "collisions",
                    "puma560",
                    "--q",
                    "0,0,0,0,0,0",
                    "--scene",
                    &path,
                    "--format",
                    format,
                ]),
                &all,
            );
        }
    }
    // A scene file that is not there, and flags that do not go together.
    bad(
        &armlab(&[
            "collisions",
            "puma560",
            "--q",
            "0,0,0,0,0,0",
            "--scene",
            "/no/such/cell.toml",
        ]),
        &["cell.toml"],
    );
    bad(&armlab(&["collisions", "puma560"]), &["--q", "--matrix"]);
    bad(
        &armlab(&[
            "collisions",
            "puma560",
            "--q",
            "0,0,0,0,0,0",
            "--samples",
            "10",
        ]),
        &["--matrix"],
    );
    bad(
        &armlab(&["collisions", "puma560", "--matrix", "--samples", "0"]),
        &["--samples"],
    );
    bad(
        &armlab(&["collisions", "puma560", "--q", "0,0,0"]),
        &["--q"],
    );
    let _ = std::fs::remove_dir_all(&dir);
}
