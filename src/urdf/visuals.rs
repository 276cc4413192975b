//! A URDF's `<visual>` elements into [`Visual`]s: boxes, cylinders (capsules drawn as
//! cylinders), spheres, and mesh files (STL, OBJ and COLLADA through the `mesh-loader` crate),
//! with their origin, scale and material colour. Mesh paths: `package://PKG/rest` is looked up
//! as `DIR/PKG/rest` for every DIR of the package search list (armlab's `--package-path`, then
//! `ROS_PACKAGE_PATH`) and of the URDF's own folder and its ancestors (also as `DIR/rest` when
//! DIR is itself named PKG); `file://` paths are absolute; other paths are relative to the
//! URDF's folder. A file used by several links is read once and shared. A mesh that cannot be
//! found or read is a warning naming the file, and its link is drawn with the joint's body; the
//! robot still loads. Meshes over [`MAX_TRIANGLES`] are decimated by vertex clustering.

use crate::kinematics::pose::{Pose, rot_x, rot_y, rot_z};
use crate::kinematics::visual::{Visual, VisualGeometry};
use crate::mesh::{COARSE_TRIANGLES, TriMesh};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

/// Triangles a mesh may keep; larger ones are decimated (the software rasterizer pays per
/// triangle; a real arm's link meshes have a few thousand).
pub const MAX_TRIANGLES: usize = 20_000;
/// Most bytes read from one mesh file: 64 MiB (larger files are refused with a warning).
pub const MAX_MESH_BYTES: u64 = 64 << 20;

/// The package search list set by `--package-path` (before `ROS_PACKAGE_PATH`).
fn package_paths() -> &'static Mutex<Vec<PathBuf>> {
    static PATHS: OnceLock<Mutex<Vec<PathBuf>>> = OnceLock::new();
    PATHS.get_or_init(|| Mutex::new(Vec::new()))
}

/// Sets the folders searched for `package://` meshes before `ROS_PACKAGE_PATH`.
pub fn set_package_paths(paths: Vec<PathBuf>) {
    if let Ok(mut p) = package_paths().lock() {
        *p = paths;
    }
}

/// Where a mesh file name points, or the places tried.
fn resolve(filename: &str, urdf: &Path) -> Result<PathBuf, String> {
    let dir = urdf.parent().unwrap_or(Path::new("."));
    if let Some(rest) = filename.strip_prefix("file://") {
        return Ok(PathBuf::from(rest));
    }
    let Some(rest) = filename.strip_prefix("package://") else {
        return Ok(dir.join(filename));
    };
    let (pkg, rel) = rest.split_once('/').unwrap_or((rest, ""));
    let mut dirs: Vec<PathBuf> = package_paths()
        .lock()
        .map(|p| p.clone())
        .unwrap_or_default();
    if let Some(ros) = std::env::var_os("ROS_PACKAGE_PATH") {
        dirs.extend(std::env::split_paths(&ros));
    }
    dirs.extend(dir.ancestors().map(Path::to_path_buf));
    let mut tried = Vec::new();
    for d in &dirs {
        let mut candidates = vec![d.join(pkg).join(rel)];
        if d.file_name().is_some_and(|n| n == pkg) {
            candidates.push(d.join(rel));
        }
        for c in candidates {
            if c.is_file() {
                return Ok(c);
            }
            tried.push(c.display().to_string());
        }
    }
    Err(format!(
        "package \"{pkg}\" not found (tried {}; add its parent folder with --package-path or \
         ROS_PACKAGE_PATH)",
        tried.first().map_or("nothing".into(), |t| format!(
            "{t} and {} more",
            tried.len() - 1
        ))
    ))
}

/// Reads a mesh file, or a file a mesh references (an OBJ's material library): a regular file
/// of at most [`MAX_MESH_BYTES`].
fn read_capped(path: &Path) -> std::io::Result<Vec<u8>> {
    crate::input::read_bytes(path, MAX_MESH_BYTES, "a mesh")
}

/// A mesh file read once: the triangles, and what to say about the file (its COLLADA up axis).
type LoadedMesh = Result<(Arc<TriMesh>, Option<String>), String>;

/// One mesh file as a single triangle mesh (every sub-mesh merged), decimated if large, with a
/// note when it is COLLADA with an `<up_axis>` other than Z_UP.
fn read_mesh(path: &Path) -> LoadedMesh {
    let bytes = read_capped(path).map_err(|e| e.to_string())?;
    let mesh = parse_mesh(&bytes, path)?;
    Ok((Arc::new(mesh), collada_up_axis_note(&bytes)))
}

/// A COLLADA file's `<up_axis>` when it is not Z_UP, as a warning: armlab ignores it, as RViz
/// does (ros-visualization/rviz#1045), since robot meshes are drawn in their link frames
/// whatever their exporter wrote; `<unit meter="...">` is applied (mesh-loader scales the scene).
fn collada_up_axis_note(bytes: &[u8]) -> Option<String> {
    let head = &bytes[..bytes.len().min(64 * 1024)];
    let text = std::str::from_utf8(head).ok()?;
    let start = text.find("<up_axis>")? + "<up_axis>".len();
    let end = start + text[start..].find("</up_axis>")?;
    let axis = text[start..end].trim();
    (axis != "Z_UP").then(|| {
        format!("<up_axis>{axis}</up_axis> is ignored (as RViz does): the mesh is drawn as its vertices are, Z up")
    })
}

/// A mesh file's bytes (STL, OBJ or COLLADA, told by `path`'s extension or the bytes) as one
/// triangle mesh, every sub-mesh merged, decimated to [`MAX_TRIANGLES`]; files it references
/// are read from beside `path`, capped like the mesh itself. Errors say why in words.
pub fn parse_mesh(bytes: &[u8], path: &Path) -> Result<TriMesh, String> {
    // mesh-loader 0.1.13 panics (`todo!()`) on some COLLADA files it cannot handle (found by
    // fuzzing); such a file is a warning like any unreadable mesh, not a crash.
    let loaded = std::panic::catch_unwind(|| {
        mesh_loader::Loader::default().load_from_slice_with_reader(bytes, path, read_capped)
    })
    .map_err(
        |_| "the mesh loader cannot read this file (it stopped on a feature it does not support)",
    )?;
    let scene = loaded.map_err(|e| e.to_string())?;
    let mut mesh = TriMesh::default();
    for m in &scene.meshes {
        let base = mesh.positions.len() as u32;
        mesh.positions.extend(m.vertices.iter().copied());
        mesh.triangles
            .extend(m.faces.iter().map(|f| f.map(|v| v + base)));
    }
    if mesh.triangles.is_empty() {
        return Err("no triangles in the file".into());
    }
    let n = mesh.positions.len() as u32;
    if mesh.triangles.iter().flatten().any(|&v| v >= n)
        || mesh.positions.iter().flatten().any(|v| !v.is_finite())
    {
        return Err("an index out of range or a non-finite vertex".into());
    }
    Ok(mesh.decimated(MAX_TRIANGLES))
}

/// The origin of a visual.
fn origin(o: &urdf_rs::Pose) -> Option<Pose> {
    let (xyz, rpy) = (o.xyz.0, o.rpy.0);
    xyz.iter().chain(&rpy).all(|v| v.is_finite()).then(|| {
        Pose::translation(xyz[0], xyz[1], xyz[2]) * rot_z(rpy[2]) * rot_y(rpy[1]) * rot_x(rpy[0])
    })
}

/// The colour of a visual's material: its own `<color>`, or the named top-level material's.
fn color(m: Option<&urdf_rs::Material>, named: &HashMap<String, [f32; 4]>) -> Option<[f32; 4]> {
    let m = m?;
    let c = match &m.color {
        Some(c) => Some(c.rgba.0.map(|v| v.clamp(0.0, 1.0) as f32)),
        None => named.get(m.name.as_str()).copied(),
    }?;
    c.iter().all(|v| v.is_finite()).then_some(c)
}

/// A mesh visual: the file found, read (once per file) and scaled, with its coarse copy.
fn mesh_geometry(
    filename: &str,
    scale: Option<&urdf_rs::Vec3>,
    urdf_path: &Path,
    cache: &mut HashMap<PathBuf, LoadedMesh>,
) -> Result<(VisualGeometry, Option<String>), String> {
    let path = resolve(filename, urdf_path)?;
    let (mesh, note) = cache
        .entry(path.clone())
        .or_insert_with(|| read_mesh(&path))
        .clone()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let mesh = scaled(&mesh, scale.map_or([1.0; 3], |s| s.0));
    let coarse = Arc::new(mesh.decimated(COARSE_TRIANGLES));
    Ok((VisualGeometry::Mesh { mesh, coarse }, note))
}

/// The top-level materials by name; a name defined twice with different colours is a warning
/// naming it, and the first definition is used (as the URDF parser of ROS does).
fn named_materials(urdf: &urdf_rs::Robot, warnings: &mut Vec<String>) -> HashMap<String, [f32; 4]> {
    let mut named: HashMap<String, [f32; 4]> = HashMap::new();
    for m in &urdf.materials {
        let Some(c) = &m.color else { continue };
        let rgba = c.rgba.0.map(|v| v as f32);
        match named.get(&m.name) {
            Some(first) if *first != rgba => warnings.push(format!(
                "material \"{}\" is defined twice (rgba {first:?}, then {rgba:?}): the first is used",
                m.name
            )),
            Some(_) => {}
            None => {
                named.insert(m.name.clone(), rgba);
            }
        }
    }
    named
}

/// Which of a link's elements to read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Elements {
    /// `<visual>`: what is drawn.
    Visual,
    /// `<collision>`: what collision checks use.
    Collision,
}

impl Elements {
    /// The element's name in messages.
    fn word(self) -> &'static str {
        match self {
            Elements::Visual => "visual",
            Elements::Collision => "collision",
        }
    }
}

/// One element of a link as the reader sees it: origin, geometry and material.
type Element<'a> = (
    &'a urdf_rs::Pose,
    &'a urdf_rs::Geometry,
    Option<&'a urdf_rs::Material>,
);

/// The elements of one kind of a link.
fn elements_of(link: &urdf_rs::Link, which: Elements) -> Vec<Element<'_>> {
    match which {
        Elements::Visual => link
            .visual
            .iter()
            .map(|v| (&v.origin, &v.geometry, v.material.as_ref()))
            .collect(),
        Elements::Collision => link
            .collision
            .iter()
            .map(|c| (&c.origin, &c.geometry, None))
            .collect(),
    }
}

/// Reads every link's visuals; `joint_of` maps a link to the joint whose child it is (`None`
/// for the root link). Returns the visuals and the warnings.
pub(super) fn read(
    urdf: &urdf_rs::Robot,
    urdf_path: &Path,
    joint_of: impl Fn(&str) -> Option<usize>,
) -> (Vec<Visual>, Vec<String>) {
    read_elements(urdf, urdf_path, &joint_of, Elements::Visual)
}

/// Every link's collision geometry: its `<collision>` elements, or, for a link that has none,
/// its `visuals` (read already by [`read`]), with one warning naming those links.
pub(super) fn collisions(
    urdf: &urdf_rs::Robot,
    urdf_path: &Path,
    joint_of: impl Fn(&str) -> Option<usize>,
    visuals: &[Visual],
) -> (Vec<Visual>, Vec<String>) {
    let (mut out, mut warnings) = read_elements(urdf, urdf_path, &joint_of, Elements::Collision);
    let mut borrowed = Vec::new();
    for link in urdf.links.iter().filter(|l| l.collision.is_empty()) {
        let joint = joint_of(&link.name);
        let theirs: Vec<&Visual> = visuals.iter().filter(|v| v.joint == joint).collect();
        if theirs.is_empty() {
            continue;
        }
        borrowed.push(format!("\"{}\"", link.name));
        out.extend(theirs.into_iter().map(|v| Visual {
            color: None,
            ..v.clone()
        }));
    }
    if !borrowed.is_empty() {
        let more = borrowed.len().saturating_sub(6);
        borrowed.truncate(6);
        let more = if more > 0 {
            format!(" and {more} more")
        } else {
            String::new()
        };
        warnings.push(format!(
            "links {}{more} have no <collision>: their <visual> is used for collisions",
            borrowed.join(", ")
        ));
    }
    (out, warnings)
}

/// Reads every link's `<visual>` or `<collision>` elements (see [`read`]); a mesh that cannot
/// be read is left out with a warning naming the link and the file.
// Over 80 lines: one pass over the links, whose per-element match (primitives, meshes with
// their cache, notes and missing list) shares that state; split, it would pass six arguments.
pub(super) fn read_elements(
    urdf: &urdf_rs::Robot,
    urdf_path: &Path,
    joint_of: &impl Fn(&str) -> Option<usize>,
    which: Elements,
) -> (Vec<Visual>, Vec<String>) {
    let mut warnings = Vec::new();
    let named = named_materials(urdf, &mut warnings);
    if which == Elements::Collision {
        // The materials were already judged with the visuals.
        warnings.clear();
    }
    let mut cache: HashMap<PathBuf, LoadedMesh> = HashMap::new();
    let mut noted: Vec<PathBuf> = Vec::new();
    let mut missing: Vec<MissingMesh> = Vec::new();
    let mut visuals = Vec::new();
    for link in &urdf.links {
        let joint = joint_of(&link.name);
        for (v_origin, v_geometry, v_material) in elements_of(link, which) {
            let Some(origin) = origin(v_origin) else {
                warnings.push(format!(
                    "link \"{}\": a {} origin is not finite; skipped",
                    link.name,
                    which.word()
                ));
                continue;
            };
            let geometry = match v_geometry {
                urdf_rs::Geometry::Box { size } => VisualGeometry::Box(size.0),
                urdf_rs::Geometry::Cylinder { radius, length }
                | urdf_rs::Geometry::Capsule { radius, length } => VisualGeometry::Cylinder {
                    radius: *radius,
                    length: *length,
                },
                urdf_rs::Geometry::Sphere { radius } => VisualGeometry::Sphere(*radius),
                urdf_rs::Geometry::Mesh { filename, scale } => {
                    match mesh_geometry(filename, scale.as_ref(), urdf_path, &mut cache) {
                        Ok((g, note)) => {
                            // Said once per file, naming the first link that uses it.
                            let path = resolve(filename, urdf_path).unwrap_or_default();
                            if let Some(note) = note
                                && !noted.contains(&path)
                            {
                                warnings.push(format!(
                                    "link \"{}\": mesh \"{filename}\": {note}",
                                    link.name
                                ));
                                noted.push(path);
                            }
                            g
                        }
                        Err(e) => {
                            missing.push(MissingMesh {
                                link: link.name.clone(),
                                filename: filename.clone(),
                                why: e,
                                which,
                            });
                            continue;
                        }
                    }
                }
            };
            if !sizes_ok(&geometry) {
                warnings.push(format!(
                    "link \"{}\": a {} has a bad size; skipped",
                    link.name,
                    which.word()
                ));
                continue;
            }
            visuals.push(Visual {
                joint,
                origin,
                geometry,
                color: color(v_material, &named),
            });
        }
    }
    warnings.extend(missing_mesh_warnings(missing));
    (visuals, warnings)
}

/// Whether a primitive's sizes are finite and not negative (meshes always are).
fn sizes_ok(geometry: &VisualGeometry) -> bool {
    match geometry {
        VisualGeometry::Box(s) => s.iter().all(|v| v.is_finite() && *v >= 0.0),
        VisualGeometry::Cylinder { radius, length } => {
            radius.is_finite() && length.is_finite() && *radius >= 0.0 && *length >= 0.0
        }
        VisualGeometry::Sphere(r) => r.is_finite() && *r >= 0.0,
        VisualGeometry::Mesh { .. } => true,
    }
}

/// A mesh that was not drawn: its link, its file name and why.
struct MissingMesh {
    link: String,
    filename: String,
    why: String,
    /// Whether it was a visual's mesh or a collision's.
    which: Elements,
}

/// One warning per missing mesh, except that the meshes of one package that is not found at
/// all (a description without its meshes, dozens of files) are said in one warning naming the
/// links.
fn missing_mesh_warnings(missing: Vec<MissingMesh>) -> Vec<String> {
    let package_of = |m: &MissingMesh| {
        m.why
            .strip_prefix("package \"")
            .and_then(|r| r.split_once('"'))
            .map(|(p, _)| p.to_string())
    };
    let mut out = Vec::new();
    let mut grouped: Vec<(String, Vec<MissingMesh>)> = Vec::new();
    for m in missing {
        match package_of(&m) {
            Some(p) => match grouped.iter_mut().find(|g| g.0 == p) {
                Some(g) => g.1.push(m),
                None => grouped.push((p, vec![m])),
            },
            None => out.push(one_missing(&m)),
        }
    }
    for (pkg, ms) in grouped {
        if ms.len() == 1 {
            out.push(one_missing(&ms[0]));
            continue;
        }
        let mut links: Vec<&str> = ms.iter().map(|m| m.link.as_str()).collect();
        links.dedup();
        let shown: Vec<String> = links.iter().take(6).map(|l| format!("\"{l}\"")).collect();
        let more = links.len().saturating_sub(6);
        let more = if more > 0 {
            format!(" and {more} more")
        } else {
            String::new()
        };
        let (what, instead) = match ms[0].which {
            Elements::Visual => ("meshes not drawn", "drawn with their joints' bodies"),
            Elements::Collision => (
                "collision meshes not read",
                "checked with their joints' bodies",
            ),
        };
        out.push(format!(
            "package \"{pkg}\" not found: {} {what}, on links {}{more} ({instead}); add the \
             package's parent folder with --package-path or ROS_PACKAGE_PATH",
            ms.len(),
            shown.join(", ")
        ));
    }
    out
}

/// The warning for one mesh not drawn.
fn one_missing(m: &MissingMesh) -> String {
    match m.which {
        Elements::Visual => format!(
            "link \"{}\": mesh \"{}\" not drawn ({}); the link is drawn with its joint's body",
            m.link, m.filename, m.why
        ),
        Elements::Collision => format!(
            "link \"{}\": collision mesh \"{}\" not read ({}); the link is checked with its \
             joint's body",
            m.link, m.filename, m.why
        ),
    }
}

/// The mesh with the URDF's `scale` applied (shared unchanged when the scale is 1).
fn scaled(mesh: &Arc<TriMesh>, s: [f64; 3]) -> Arc<TriMesh> {
    if s == [1.0; 3] || !s.iter().all(|v| v.is_finite()) {
        return mesh.clone();
    }
    Arc::new(TriMesh {
        positions: mesh
            .positions
            .iter()
            .map(|p| std::array::from_fn(|k| (f64::from(p[k]) * s[k]) as f32))
            .collect(),
        triangles: mesh.triangles.clone(),
    })
}
