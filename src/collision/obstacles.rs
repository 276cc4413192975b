//! A cell's obstacles: the TOML scene file, read with errors naming the file, the line and the
//! obstacle, and written back.
//!
//! ```toml
//! [[obstacle]]
//! name = "table"
//! shape = "box"            # box | cylinder | sphere | plane | mesh
//! size = [1.2, 0.8, 0.05]  # box: full extents; cylinder: [radius, length]; sphere: [radius]
//! xyz = [0.6, 0.0, 0.375]  # metres, in `frame` (default: the world)
//! rpy_deg = [0, 0, 0]      # fixed-axis roll, pitch, yaw as in URDF
//! # mesh = "fixture.stl"   # shape = "mesh": relative to the scene file; scale = [1, 1, 1]
//! # frame = "world"        # or a link of the robot: the obstacle moves with it
//! # decompose = false      # a mesh as a convex decomposition instead of its hull
//! ```

use super::CollisionError;
use super::geometry::{GeometryOptions, mesh_parts, to_parry};
use crate::kinematics::Pose;
use crate::kinematics::pose::{rot_x, rot_y, rot_z};
use crate::mesh::{TriMesh, Winding};
use parry3d_f64::math::{Pose as PPose, Vec3};
use parry3d_f64::shape::SharedShape;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Most bytes of a scene file: 1 MiB.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;

/// An obstacle's shape, in its own frame (m).
#[derive(Debug, Clone, PartialEq)]
pub enum ObstacleShape {
    /// A box centred on the origin with these full extents.
    Box {
        /// Edge lengths along x, y, z (m).
        size: [f64; 3],
    },
    /// A cylinder along z centred on the origin.
    Cylinder {
        /// Radius (m).
        radius: f64,
        /// Length along z (m).
        length: f64,
    },
    /// A sphere about the origin.
    Sphere {
        /// Radius (m).
        radius: f64,
    },
    /// A solid half-space: everything below the frame's x-y plane (its z is the outward
    /// normal).
    Plane,
    /// A triangle mesh read from a file (checked as its convex hull, or a decomposition).
    Mesh {
        /// The file name as the scene file gives it (relative to the scene file).
        file: String,
        /// The scale applied to the file's vertices.
        scale: [f64; 3],
        /// The mesh, scaled (m).
        mesh: Arc<TriMesh>,
        /// Whether to split it into convex pieces instead of taking its hull.
        decompose: bool,
    },
}

/// The frame an obstacle's pose is given in.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ObstacleFrame {
    /// The world frame (fixed obstacles).
    World,
    /// A link of the robot, by name: the obstacle moves with it (a tool, a payload).
    Link(String),
}

/// One obstacle of a cell.
#[derive(Debug, Clone, PartialEq)]
pub struct Obstacle {
    /// Its name in reports ("forearm hits table").
    pub name: String,
    /// Its shape.
    pub shape: ObstacleShape,
    /// Position of its frame in `frame` (m).
    pub xyz: [f64; 3],
    /// Fixed-axis roll, pitch, yaw of its frame in `frame` (rad), as in URDF.
    pub rpy: [f64; 3],
    /// The frame the pose is given in.
    pub frame: ObstacleFrame,
    /// 1-based line of its table in the scene file (0 when made in the app).
    pub line: usize,
}

/// The obstacles of a cell, as a scene file gives them.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CellScene {
    /// The obstacles in file order.
    pub obstacles: Vec<Obstacle>,
    /// What reading the file let pass with a remark (an unknown key, a mesh that is not
    /// closed), naming the obstacle.
    pub warnings: Vec<String>,
    /// The file it was read from (messages; meshes are relative to it).
    pub path: Option<PathBuf>,
}

impl Obstacle {
    /// `frame_from_obstacle`: the pose its `xyz` and `rpy` give (URDF's fixed-axis RPY).
    pub fn frame_from_obstacle(&self) -> Pose {
        let [x, y, z] = self.xyz;
        let [r, p, w] = self.rpy;
        Pose::translation(x, y, z) * rot_z(w) * rot_y(p) * rot_x(r)
    }

    /// A box obstacle in the world frame.
    pub fn cuboid(name: &str, size: [f64; 3], xyz: [f64; 3]) -> Obstacle {
        Obstacle {
            name: name.into(),
            shape: ObstacleShape::Box { size },
            xyz,
            rpy: [0.0; 3],
            frame: ObstacleFrame::World,
            line: 0,
        }
    }

    /// A floor: the half-space below z = `height` (m), world frame.
    pub fn floor(name: &str, height: f64) -> Obstacle {
        Obstacle {
            name: name.into(),
            shape: ObstacleShape::Plane,
            xyz: [0.0, 0.0, height],
            rpy: [0.0; 3],
            frame: ObstacleFrame::World,
            line: 0,
        }
    }

    /// The obstacle as convex parts in its own frame.
    pub(super) fn parts(
        &self,
        options: GeometryOptions,
    ) -> Result<Vec<(PPose, SharedShape)>, String> {
        let at = PPose::IDENTITY;
        Ok(match &self.shape {
            ObstacleShape::Box { size } => vec![(
                at,
                SharedShape::cuboid(size[0] / 2.0, size[1] / 2.0, size[2] / 2.0),
            )],
            ObstacleShape::Cylinder { radius, length } => {
                let y_to_z = PPose::from_rotation(parry3d_f64::math::Rot3::from_rotation_x(
                    std::f64::consts::FRAC_PI_2,
                ));
                vec![(y_to_z, SharedShape::cylinder(length / 2.0, *radius))]
            }
            ObstacleShape::Sphere { radius } => vec![(at, SharedShape::ball(*radius))],
            ObstacleShape::Plane => vec![(at, SharedShape::halfspace(Vec3::Z))],
            ObstacleShape::Mesh {
                mesh, decompose, ..
            } => mesh_parts(mesh, *decompose || options.decompose_meshes)?,
        })
    }

    /// The pose as a parry pose (`frame_from_obstacle`).
    pub(super) fn parry_pose(&self) -> PPose {
        to_parry(&self.frame_from_obstacle())
    }

    /// The shape's word in the scene file.
    pub fn shape_word(&self) -> &'static str {
        match self.shape {
            ObstacleShape::Box { .. } => "box",
            ObstacleShape::Cylinder { .. } => "cylinder",
            ObstacleShape::Sphere { .. } => "sphere",
            ObstacleShape::Plane => "plane",
            ObstacleShape::Mesh { .. } => "mesh",
        }
    }

    /// The obstacle as a `[[obstacle]]` table of the scene file.
    fn to_toml(&self) -> String {
        let list = |v: &[f64]| {
            let items: Vec<String> = v.iter().map(|x| format_number(*x)).collect();
            format!("[{}]", items.join(", "))
        };
        let mut out = format!(
            "[[obstacle]]\nname = {}\nshape = \"{}\"\n",
            toml_string(&self.name),
            self.shape_word()
        );
        match &self.shape {
            ObstacleShape::Box { size } => out += &format!("size = {}\n", list(size)),
            ObstacleShape::Cylinder { radius, length } => {
                out += &format!("size = {}\n", list(&[*radius, *length]))
            }
            ObstacleShape::Sphere { radius } => out += &format!("size = {}\n", list(&[*radius])),
            ObstacleShape::Plane => {}
            ObstacleShape::Mesh {
                file,
                scale,
                decompose,
                ..
            } => {
                out += &format!("mesh = {}\n", toml_string(file));
                if *scale != [1.0; 3] {
                    out += &format!("scale = {}\n", list(scale));
                }
                if *decompose {
                    out += "decompose = true\n";
                }
            }
        }
        out += &format!("xyz = {}\n", list(&self.xyz));
        let rpy_deg = self.rpy.map(f64::to_degrees);
        out += &format!("rpy_deg = {}\n", list(&rpy_deg));
        if let ObstacleFrame::Link(link) = &self.frame {
            out += &format!("frame = {}\n", toml_string(link));
        }
        out
    }
}

/// A number as the scene file writes it: at most 9 decimals, no trailing zeros.
fn format_number(x: f64) -> String {
    let s = format!("{:.9}", x);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    let s = if s == "-0" { "0" } else { s };
    s.to_string()
}

/// A TOML basic string.
fn toml_string(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

impl CellScene {
    /// Reads a scene file (at most 1 MiB); meshes are read relative to it.
    pub fn read(path: &Path) -> Result<CellScene, CollisionError> {
        let text =
            crate::input::read_text(path, MAX_SCENE_BYTES, "a scene file").map_err(|source| {
                CollisionError::Read {
                    path: path.to_path_buf(),
                    source,
                }
            })?;
        CellScene::parse(&text, path)
    }

    /// Parses scene-file text; `path` names it in messages and is where meshes are looked up
    /// from.
    pub fn parse(text: &str, path: &Path) -> Result<CellScene, CollisionError> {
        let toml_error = |offset: usize, message: String| {
            let (line, column) = super::line_column(text, offset);
            CollisionError::Toml {
                path: path.to_path_buf(),
                line,
                column,
                message,
            }
        };
        let doc: toml::Spanned<toml::Table> =
            toml::from_str(text).map_err(|e: toml::de::Error| {
                toml_error(
                    e.span().map_or(0, |s| s.start),
                    e.message().trim().to_string(),
                )
            })?;
        let mut scene = CellScene {
            path: Some(path.to_path_buf()),
            ..CellScene::default()
        };
        for key in doc.get_ref().keys().filter(|k| *k != "obstacle") {
            scene
                .warnings
                .push(format!("{}: unknown key \"{key}\" ignored", path.display()));
        }
        // The tables again, with their spans, for the lines in messages.
        #[derive(serde::Deserialize)]
        struct Doc {
            #[serde(default)]
            obstacle: Vec<toml::Spanned<toml::Table>>,
        }
        let spanned: Doc = toml::from_str(text).map_err(|e: toml::de::Error| {
            toml_error(
                e.span().map_or(0, |s| s.start),
                format!(
                    "`obstacle` must be a list of tables ([[obstacle]]): {}",
                    e.message().trim()
                ),
            )
        })?;
        for (i, table) in spanned.obstacle.iter().enumerate() {
            let (line, _) = super::line_column(text, table.span().start);
            let obstacle = read_obstacle(table.get_ref(), i, line, path, &mut scene.warnings)?;
            if scene.obstacles.iter().any(|o| o.name == obstacle.name) {
                return Err(CollisionError::Obstacle {
                    path: path.to_path_buf(),
                    line,
                    obstacle: obstacle.name,
                    problem: "the name is used by an earlier obstacle: names must be unique".into(),
                });
            }
            scene.obstacles.push(obstacle);
        }
        Ok(scene)
    }

    /// The scene as a scene file's text ([`CellScene::parse`] reads it back).
    pub fn to_toml(&self) -> String {
        let tables: Vec<String> = self.obstacles.iter().map(Obstacle::to_toml).collect();
        format!(
            "# armlab scene: obstacles of a cell (m, degrees)\n\n{}",
            tables.join("\n")
        )
    }
}

/// A key's numbers, each finite.
fn numbers(table: &toml::Table, key: &str) -> Result<Option<Vec<f64>>, String> {
    let Some(v) = table.get(key) else {
        return Ok(None);
    };
    let items = v
        .as_array()
        .ok_or_else(|| format!("`{key}` must be a list of numbers"))?;
    let mut out = Vec::with_capacity(items.len());
    for item in items {
        let x = match item {
            toml::Value::Float(x) => *x,
            toml::Value::Integer(i) => *i as f64,
            _ => return Err(format!("`{key}` must be a list of numbers (found {item})")),
        };
        if !x.is_finite() {
            return Err(format!("`{key}` has a value that is not finite ({x})"));
        }
        out.push(x);
    }
    Ok(Some(out))
}

/// A key's exactly `n` finite numbers, or `default`.
fn fixed<const N: usize>(
    table: &toml::Table,
    key: &str,
    default: [f64; N],
) -> Result<[f64; N], String> {
    match numbers(table, key)? {
        None => Ok(default),
        Some(v) => v
            .try_into()
            .map_err(|v: Vec<f64>| format!("`{key}` must have {N} numbers (found {})", v.len())),
    }
}

/// The keys an obstacle table may have.
const KEYS: [&str; 9] = [
    "name",
    "shape",
    "size",
    "xyz",
    "rpy_deg",
    "mesh",
    "scale",
    "frame",
    "decompose",
];

/// One `[[obstacle]]` table.
fn read_obstacle(
    table: &toml::Table,
    index: usize,
    line: usize,
    path: &Path,
    warnings: &mut Vec<String>,
) -> Result<Obstacle, CollisionError> {
    let name = table
        .get("name")
        .and_then(|v| v.as_str())
        .map_or_else(|| format!("#{}", index + 1), str::to_string);
    let err = |problem: String| CollisionError::Obstacle {
        path: path.to_path_buf(),
        line,
        obstacle: name.clone(),
        problem,
    };
    if !table.get("name").is_some_and(|v| v.is_str()) {
        return Err(err("`name` (a string) is missing".into()));
    }
    for key in table.keys().filter(|k| !KEYS.contains(&k.as_str())) {
        warnings.push(format!(
            "{}:{line}: obstacle \"{name}\": unknown key \"{key}\" ignored",
            path.display()
        ));
    }
    let shape_word = table
        .get("shape")
        .and_then(|v| v.as_str())
        .ok_or_else(|| err("`shape` is missing: box, cylinder, sphere, plane or mesh".into()))?;
    let size = numbers(table, "size").map_err(&err)?;
    let shape = match shape_word {
        "box" | "cylinder" | "sphere" => primitive(shape_word, size).map_err(&err)?,
        "plane" => {
            if size.is_some() {
                warnings.push(format!(
                    "{}:{line}: obstacle \"{name}\": a plane has no size; `size` ignored",
                    path.display()
                ));
            }
            ObstacleShape::Plane
        }
        "mesh" => read_mesh_shape(table, path, line, &name, warnings).map_err(&err)?,
        other => {
            return Err(err(format!(
                "unknown shape \"{other}\": box, cylinder, sphere, plane or mesh"
            )));
        }
    };
    let xyz = fixed(table, "xyz", [0.0; 3]).map_err(&err)?;
    let rpy = fixed(table, "rpy_deg", [0.0; 3])
        .map_err(&err)?
        .map(f64::to_radians);
    let frame = match table.get("frame").map(|v| v.as_str()) {
        None | Some(Some("world")) => ObstacleFrame::World,
        Some(Some(link)) => ObstacleFrame::Link(link.to_string()),
        Some(None) => {
            return Err(err(
                "`frame` must be a string: \"world\" or a link's name".into()
            ));
        }
    };
    Ok(Obstacle {
        name: name.clone(),
        shape,
        xyz,
        rpy,
        frame,
        line,
    })
}

/// A box, cylinder or sphere from its `size`, every size positive.
fn primitive(word: &str, size: Option<Vec<f64>>) -> Result<ObstacleShape, String> {
    let (want, what) = match word {
        "box" => (3, "[x, y, z] (full extents, m)"),
        "cylinder" => (2, "[radius, length] (m)"),
        _ => (1, "[radius] (m)"),
    };
    let size = size.ok_or_else(|| format!("a {word} needs `size` = {what}"))?;
    if size.len() != want {
        return Err(format!(
            "a {word}'s `size` is {what}: {want} numbers (found {})",
            size.len()
        ));
    }
    if size.iter().any(|s| *s <= 0.0) {
        return Err(format!(
            "a {word}'s `size` {size:?} has a size that is not positive: the {word} is degenerate"
        ));
    }
    Ok(match word {
        "box" => ObstacleShape::Box {
            size: [size[0], size[1], size[2]],
        },
        "cylinder" => ObstacleShape::Cylinder {
            radius: size[0],
            length: size[1],
        },
        _ => ObstacleShape::Sphere { radius: size[0] },
    })
}

/// A mesh obstacle: the file read relative to the scene file, scaled; a mesh that is not closed
/// is a warning (its convex hull is checked).
fn read_mesh_shape(
    table: &toml::Table,
    path: &Path,
    line: usize,
    name: &str,
    warnings: &mut Vec<String>,
) -> Result<ObstacleShape, String> {
    let file = table
        .get("mesh")
        .and_then(|v| v.as_str())
        .ok_or("a mesh needs `mesh` = \"file.stl\" (relative to the scene file)")?;
    let scale = fixed(table, "scale", [1.0; 3])?;
    if scale.contains(&0.0) {
        return Err(format!(
            "`scale` {scale:?} has a zero: the mesh would be flat"
        ));
    }
    let decompose = table
        .get("decompose")
        .and_then(|v| v.as_bool())
        .unwrap_or(false);
    let full = path.parent().unwrap_or(Path::new(".")).join(file);
    let bytes = crate::input::read_bytes(&full, crate::urdf::MAX_MESH_BYTES, "a mesh")
        .map_err(|e| format!("mesh \"{file}\" cannot be read: {e} ({})", full.display()))?;
    let raw = crate::urdf::parse_mesh(&bytes, &full).map_err(|e| {
        let shown = full.display().to_string();
        if e.contains(&shown) {
            format!("mesh \"{file}\": {e}")
        } else {
            format!("mesh \"{file}\": {e} ({shown})")
        }
    })?;
    let mesh = TriMesh {
        positions: raw
            .positions
            .iter()
            .map(|p| std::array::from_fn(|k| (f64::from(p[k]) * scale[k]) as f32))
            .collect(),
        triangles: raw.triangles,
    };
    if mesh.winding() == Winding::Mixed {
        warnings.push(format!(
            "{}:{line}: obstacle \"{name}\": mesh \"{file}\" is not closed: its convex hull is \
             checked",
            path.display()
        ));
    }
    Ok(ObstacleShape::Mesh {
        file: file.to_string(),
        scale,
        mesh: Arc::new(mesh),
        decompose,
    })
}
