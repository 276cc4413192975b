//! `armlab reachability` run as a user runs it: the issue's flags, the .npz's arrays read here
//! from the zip with the `.npy` headers parsed by hand (dtype, shape, C order), the samples
//! checked against the Puma's closed form called by the test, bad input refused before any
//! work with no file written, `--map` reading a map back, and Ctrl+C stopping cleanly.

use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn armlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(args)
        .output()
        .expect("run armlab")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("armlab-reach-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// One `.npy` array: its dtype, shape and raw little-endian bytes.
struct Npy {
    dtype: String,
    shape: Vec<usize>,
    data: Vec<u8>,
}

/// Every array of an .npz, the `.npy` format (version 1 or 2) parsed here.
fn read_npz(path: &Path) -> BTreeMap<String, Npy> {
    let file = std::fs::File::open(path).expect("the map file");
    let mut zip = zip::ZipArchive::new(file).expect("a zip archive");
    let mut out = BTreeMap::new();
    for k in 0..zip.len() {
        let mut entry = zip.by_index(k).expect("an entry");
        let name = entry.name().strip_suffix(".npy").expect(".npy").to_string();
        let mut bytes = Vec::new();
        entry.read_to_end(&mut bytes).expect("read");
        assert_eq!(&bytes[..6], b"\x93NUMPY", "{name}");
        let (len, start) = match bytes[6] {
            1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
            _ => (
                u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
                12,
            ),
        };
        let header = std::str::from_utf8(&bytes[start..start + len]).expect("ASCII header");
        assert!(
            header.contains("'fortran_order': False"),
            "{name}: {header}"
        );
        let field = |key: &str| -> String {
            let at = header.find(key).expect(key) + key.len();
            header[at..].trim_start_matches([':', ' ']).to_string()
        };
        let dtype = field("'descr'");
        let dtype = dtype[1..].split('\'').next().expect("dtype").to_string();
        let shape_text = field("'shape'");
        let inner = &shape_text[1..shape_text.find(')').expect(")")];
        let shape = inner
            .split(',')
            .filter(|s| !s.trim().is_empty())
            .map(|s| s.trim().parse().expect("a dimension"))
            .collect();
        out.insert(
            name,
            Npy {
                dtype,
                shape,
                data: bytes[start + len..].to_vec(),
            },
        );
    }
    out
}

fn f64s(a: &Npy) -> Vec<f64> {
    assert_eq!(a.dtype, "<f8");
    a.data
        .chunks(8)
        .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
        .collect()
}

fn text(a: &Npy) -> String {
    assert!(a.dtype.starts_with("<U"), "{}", a.dtype);
    a.data
        .chunks(4)
        .map(|c| char::from_u32(u32::from_le_bytes(c.try_into().expect("4 bytes"))).expect("char"))
        .take_while(|&c| c != '\0')
        .collect()
}

#[test]
fn the_map_file_holds_the_issues_arrays_and_they_agree_with_the_closed_form() {
    let dir = scratch("puma");
    let out = dir.join("map.npz");
    let o = armlab(&[
        "reachability",
        "puma560",
        "--voxel",
        "0.2",
        "--directions",
        "20",
        "--rolls",
        "2",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let a = read_npz(&out);
    for key in [
        "reachable",
        "postures",
        "posture_names",
        "index",
        "origin",
        "voxel",
        "directions",
        "rolls",
        "end_effector",
        "model",
        "version",
    ] {
        assert!(a.contains_key(key), "no {key}: {:?}", a.keys());
    }
    let shape = a["reachable"].shape.clone();
    assert_eq!(shape.len(), 5);
    assert_eq!(&shape[3..], &[20, 2]);
    assert_eq!(a["reachable"].dtype, "|b1");
    assert_eq!(a["postures"].dtype, "<u2");
    assert_eq!(a["postures"].shape, shape);
    assert_eq!(a["index"].shape, shape[..3].to_vec());
    assert_eq!(a["directions"].shape, vec![20, 3]);
    assert_eq!(a["rolls"].shape, vec![2]);
    assert_eq!(text(&a["model"]), "Puma 560");
    assert_eq!(text(&a["version"]), env!("CARGO_PKG_VERSION"));
    assert_eq!(f64s(&a["voxel"]), vec![0.2]);
    let names = &a["posture_names"];
    assert_eq!(names.shape, vec![8]);

    // Samples checked against the closed form called here, at the pose rebuilt from the
    // origin, the voxel and the issue's formulas.
    let puma = armlab::kinematics::models::built_in("puma560").expect("puma");
    let cf = armlab::kinematics::ik::closed_form::ClosedForm::detect(&puma).expect("a closed form");
    let origin = f64s(&a["origin"]);
    let dirs = f64s(&a["directions"]);
    let reachable = &a["reachable"].data;
    let postures: Vec<u16> = a["postures"]
        .data
        .chunks(2)
        .map(|c| u16::from_le_bytes([c[0], c[1]]))
        .collect();
    let index = f64s(&a["index"]);
    let [nx, ny, nz] = [shape[0], shape[1], shape[2]];
    let limits = puma.limits();
    let mut reached = 0;
    for s in (0..reachable.len()).step_by(7) {
        let (v, d, r) = (s / 40, s / 2 % 20, s % 2);
        let (i, j, k) = (v / (ny * nz), v / nz % ny, v % nz);
        assert!(i < nx);
        let c = [
            origin[0] + 0.2 * i as f64,
            origin[1] + 0.2 * j as f64,
            origin[2] + 0.2 * k as f64,
        ];
        let rot = armlab::reachability::sample_rotation(
            [dirs[3 * d], dirs[3 * d + 1], dirs[3 * d + 2]],
            std::f64::consts::PI * r as f64,
        );
        let pose = armlab::kinematics::Pose::from_parts(
            nalgebra::Translation3::new(c[0], c[1], c[2]),
            rot,
        );
        let mut raw = armlab::kinematics::ik::closed_form::RawSolutions::default();
        let mut any = false;
        if cf.solve_raw(&pose, &mut raw).is_ok() {
            for (q, _) in raw.iter(6) {
                // Within the limits after whole turns.
                any |= q.iter().zip(&limits).all(|(&x, &[lo, hi])| {
                    (-2..=2).any(|t| {
                        let y = x + std::f64::consts::TAU * t as f64;
                        y >= lo - 1e-12 && y <= hi + 1e-12
                    })
                });
            }
        }
        assert_eq!(reachable[s] == 1, any, "sample {s}");
        assert_eq!(postures[s] != 0, any, "sample {s}");
        reached += any as usize;
    }
    assert!(reached > 100, "{reached}");
    for (v, &x) in index.iter().enumerate() {
        let n = reachable[v * 40..(v + 1) * 40]
            .iter()
            .filter(|&&b| b == 1)
            .count();
        assert!((x - n as f64 / 40.0).abs() < 1e-15);
    }

    // --map reads it back: the same summary, in JSON.
    let again = armlab(&[
        "reachability",
        "puma560",
        "--map",
        out.to_str().expect("utf-8"),
        "--format",
        "json",
    ]);
    assert!(
        again.status.success(),
        "{}",
        String::from_utf8_lossy(&again.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&again.stdout).expect("JSON");
    let total_reached = reachable.iter().filter(|&&b| b == 1).count();
    assert_eq!(v["reached"], total_reached);
    assert_eq!(v["samples"], reachable.len());
    assert_eq!(v["model"], "Puma 560");
    assert_eq!(v["postures"].as_array().expect("postures").len(), 8);
}

#[test]
fn bad_input_is_refused_before_any_work_and_writes_nothing() {
    let dir = scratch("bad");
    let out = dir.join("map.npz");
    let path = out.to_str().expect("utf-8");
    for (args, needle) in [
        (vec!["--voxel", "0"], "voxel"),
        (vec!["--voxel=-0.1"], "voxel"),
        (vec!["--directions", "0"], "directions"),
        (vec!["--rolls", "0"], "rolls"),
        (vec!["--voxel", "0.004"], "over the limit"),
    ] {
        let mut all = vec!["reachability", "puma560"];
        all.extend(args);
        all.extend(["--out", path]);
        let started = std::time::Instant::now();
        let o = armlab(&all);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{all:?}: {err}");
        assert!(err.contains(needle), "{needle:?} not in {err}");
        assert!(!err.contains("panicked"));
        assert!(!out.exists(), "{all:?} wrote a file");
        assert!(started.elapsed().as_secs() < 20, "{all:?} worked first");
    }
    let o = armlab(&["reachability", "puma560"]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("--out"));
    // An output folder that does not exist: said before the map is computed.
    let missing = dir.join("no/such/folder/map.npz");
    let started = std::time::Instant::now();
    let o = armlab(&[
        "reachability",
        "puma560",
        "--out",
        missing.to_str().expect("utf-8"),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("does not exist"), "{err}");
    assert!(
        started.elapsed().as_secs() < 10,
        "the map was computed first"
    );
    // A file that is no .npz, and a missing one.
    let junk = dir.join("junk.npz");
    std::fs::write(&junk, "hello").expect("write");
    let o = armlab(&[
        "reachability",
        "puma560",
        "--map",
        junk.to_str().expect("utf-8"),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("not a NumPy .npz archive") && err.contains("junk.npz"),
        "{err}"
    );
    let o = armlab(&[
        "reachability",
        "puma560",
        "--map",
        dir.join("none.npz").to_str().expect("utf-8"),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("none.npz"));
}

#[test]
fn ctrl_c_stops_a_map_cleanly_and_writes_nothing() {
    let dir = scratch("interrupt");
    let out = dir.join("map.npz");
    let child = Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args([
            "reachability",
            "puma560",
            "--directions",
            "400",
            "--rolls",
            "16",
            "--out",
        ])
        .arg(&out)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    std::thread::sleep(std::time::Duration::from_millis(2500));
    let pid = child.id().to_string();
    let sent = Command::new("kill")
        .args(["-INT", &pid])
        .status()
        .expect("kill");
    assert!(sent.success());
    let started = std::time::Instant::now();
    let o = child.wait_with_output().expect("wait");
    assert!(started.elapsed().as_secs() < 30, "did not stop");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("no file written"), "{err}");
    assert!(err.contains("stopped after"), "{err}");
    assert!(!err.contains("panicked"));
    assert!(!out.exists());
}

#[test]
fn figures_are_written_beside_the_map() {
    let dir = scratch("figures");
    let (npz, png, svg) = (
        dir.join("m.npz"),
        dir.join("down.png"),
        dir.join("post.svg"),
    );
    let o = Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args([
            "reachability",
            "puma560",
            "--voxel",
            "0.2",
            "--directions",
            "20",
            "--rolls",
            "2",
        ])
        .arg("--out")
        .arg(&npz)
        .arg("--figure")
        .arg(&png)
        .arg("--figure")
        .arg(&svg)
        .args([
            "--figure-kind",
            "direction",
            "--figure-kind",
            "postures",
            "--view",
            "top",
        ])
        .output()
        .expect("run armlab");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("down.png") && stdout.contains("post.svg"),
        "{stdout}"
    );
    let img = image::open(&png).expect("a PNG").to_rgba8();
    assert_eq!(img.dimensions(), (1200, 900));
    let svg = std::fs::read_to_string(&svg).expect("an SVG");
    assert!(svg.contains("shoulder right, elbow up, wrist no flip"));
    // Without --out, a figure alone is enough; from --map, the same figure again.
    let again = dir.join("again.png");
    let o = Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(["reachability", "puma560", "--map"])
        .arg(&npz)
        .arg("--figure")
        .arg(&again)
        .args(["--figure-kind", "direction", "--view", "top"])
        .output()
        .expect("run armlab");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let a = image::open(&again).expect("a PNG").to_rgba8();
    assert!(
        a.as_raw() == img.as_raw(),
        "the map read back draws another figure"
    );
    // Bad flags are refused before any work, naming what is wrong.
    let o = Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(["reachability", "puma560", "--out"])
        .arg(&npz)
        .args(["--figure", "a.jpg"])
        .output()
        .expect("run armlab");
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains(".png, .svg or .pdf"));
}
