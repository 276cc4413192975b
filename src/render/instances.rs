//! The CPU side of a frame: the scene's draw lists as GPU instances, in draw order.

use super::geometry::{LOD_SEGMENTS, lod_for_radius_px, shape_index};
use super::gpu_types::{DotGpu, LineGpu, MeshInstanceGpu};
use crate::scene::{Dot, Line, MeshInstance, Scene, Shape};
use std::ops::Range;

/// One instanced mesh draw.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MeshDraw {
    /// Drawn blended, after the opaque pass.
    pub translucent: bool,
    /// The transform mirrors (negative determinant): triangles wind clockwise.
    pub mirrored: bool,
    /// Index of the unit shape.
    pub shape: usize,
    /// Level of detail (index into [`LOD_SEGMENTS`]).
    pub lod: usize,
    /// Range in [`DrawLists::meshes`].
    pub instances: Range<u32>,
}

/// One draw of a custom mesh's instances.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct CustomDraw {
    /// The mesh's identity (its `Arc` address; the renderer's cache key).
    pub key: usize,
    /// Index in the scene's `custom_meshes` of one instance (to reach the mesh itself).
    pub scene_index: usize,
    /// Drawn blended, in the translucent pass.
    pub translucent: bool,
    /// The transform mirrors.
    pub mirrored: bool,
    /// Range in [`DrawLists::meshes`].
    pub instances: Range<u32>,
}

/// A frame's instances in draw order; kept between frames to reuse the allocations.
#[derive(Debug, Default)]
pub(crate) struct DrawLists {
    /// Opaque instances by [`DrawKey::index`].
    opaque: [Vec<MeshInstanceGpu>; DrawKey::COUNT],
    /// Translucent instances with their squared distance to the eye and [`DrawKey::index`].
    translucent: Vec<(f32, usize, MeshInstanceGpu)>,
    /// Opaque meshes grouped by shape and winding, then translucent ones back to front.
    pub meshes: Vec<MeshInstanceGpu>,
    /// The draws over `meshes`, in order.
    pub mesh_draws: Vec<MeshDraw>,
    /// The draws of custom meshes (their instances follow the shapes' in `meshes`), grouped by
    /// pass, mesh and winding.
    pub custom_draws: Vec<CustomDraw>,
    /// Opaque lines, then translucent ones.
    pub lines: Vec<LineGpu>,
    /// Number of opaque lines.
    pub lines_opaque: u32,
    /// The underlay's dots, then the opaque dots, then the translucent ones.
    pub dots: Vec<DotGpu>,
    /// Number of underlay dots (first in `dots`).
    pub dots_underlay: u32,
    /// Number of opaque dots (after the underlay's).
    pub dots_opaque: u32,
}

/// What one instanced draw shares: the unit shape, its level of detail and the winding.
#[derive(Debug, Clone, Copy, PartialEq)]
struct DrawKey {
    shape: usize,
    lod: usize,
    mirrored: bool,
}

impl DrawKey {
    const COUNT: usize = LOD_SEGMENTS.len() * 4 * 2;

    fn index(self) -> usize {
        (self.lod * 4 + self.shape) * 2 + self.mirrored as usize
    }

    fn from_index(i: usize) -> Self {
        Self {
            mirrored: i % 2 == 1,
            shape: (i / 2) % 4,
            lod: i / 8,
        }
    }

    fn draw(self, translucent: bool, instances: Range<u32>) -> MeshDraw {
        MeshDraw {
            translucent,
            mirrored: self.mirrored,
            shape: self.shape,
            lod: self.lod,
            instances,
        }
    }
}

/// How a frame projects sizes: enough to find how many pixels a body's radius covers.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Projection {
    /// `clip_from_world`, column-major.
    pub clip_from_world: [[f32; 4]; 4],
    /// Viewport height (px).
    pub height_px: f32,
}

impl Projection {
    /// Radius (px) that a sphere of `radius` (m) around `centre` (world) covers on screen, from
    /// the vertical scale of the projection; infinite when the centre is at or behind the eye.
    fn radius_px(&self, centre: [f32; 3], radius: f32) -> f32 {
        let m = &self.clip_from_world;
        let row = |r: usize| [m[0][r], m[1][r], m[2][r], m[3][r]];
        let (y, w) = (row(1), row(3));
        let w = w[0] * centre[0] + w[1] * centre[1] + w[2] * centre[2] + w[3];
        if w.partial_cmp(&1e-6) != Some(std::cmp::Ordering::Greater) {
            return f32::INFINITY;
        }
        let scale = (y[0] * y[0] + y[1] * y[1] + y[2] * y[2]).sqrt();
        radius * scale / w * self.height_px * 0.5
    }
}

/// The level of detail of a mesh instance seen through `proj`: round bodies by the radius
/// their circle projects to, cubes always the first level (they have no circle).
fn mesh_lod(m: &MeshInstance, proj: &Projection) -> usize {
    let len = |k: usize| {
        let c = m.world_from_unit[k];
        (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
    };
    let radius = match m.shape {
        Shape::Cube => return 0,
        Shape::Sphere => len(0).max(len(1)).max(len(2)),
        Shape::Cylinder | Shape::Cone => len(0).max(len(1)),
    };
    let t = m.world_from_unit[3];
    lod_for_radius_px(proj.radius_px([t[0], t[1], t[2]], radius))
}

fn sub3(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross3(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot3(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The GPU form of a mesh instance and whether its transform mirrors (negative determinant).
///
/// The normal matrix is the inverse-transpose of the 3x3 part up to a positive factor: the
/// cofactor matrix (columns b x c, c x a, a x b = det * M^-T) times sign(det), divided by its
/// largest entry. It stays defined when a scale is zero and is exact under non-uniform scale.
pub(crate) fn mesh_instance_gpu(m: &MeshInstance) -> (MeshInstanceGpu, bool) {
    let col = |k: usize| {
        [
            m.world_from_unit[k][0],
            m.world_from_unit[k][1],
            m.world_from_unit[k][2],
        ]
    };
    let (a, b, c) = (col(0), col(1), col(2));
    let cof = [cross3(b, c), cross3(c, a), cross3(a, b)];
    let det = dot3(a, cof[0]);
    let largest = cof.iter().flatten().fold(0.0f32, |acc, v| acc.max(v.abs()));
    let k = if largest > 0.0 && largest.is_finite() {
        det.signum() / largest
    } else {
        0.0
    };
    let normal_from_unit = cof.map(|n| [n[0] * k, n[1] * k, n[2] * k, 0.0]);
    (
        MeshInstanceGpu {
            world_from_unit: m.world_from_unit,
            normal_from_unit,
            color: m.color,
        },
        det < 0.0,
    )
}

fn line_gpu(l: &Line) -> LineGpu {
    LineGpu {
        a: l.a,
        width_px: l.width_px,
        b: l.b,
        pad: 0.0,
        color: l.color,
    }
}

fn dot_gpu(d: &Dot) -> DotGpu {
    DotGpu {
        p: d.p,
        size_px: d.size_px,
        color: d.color,
    }
}

/// Clears `out`, appends the items with alpha >= 1 and then those with 0 < alpha < 1; returns (opaque, all).
fn partition<T, G>(
    out: &mut Vec<G>,
    items: &[T],
    alpha: impl Fn(&T) -> f32,
    convert: impl Fn(&T) -> G,
) -> (u32, u32) {
    out.clear();
    out.extend(items.iter().filter(|i| alpha(i) >= 1.0).map(&convert));
    let opaque = out.len() as u32;
    out.extend(
        items
            .iter()
            .filter(|i| alpha(i) > 0.0 && alpha(i) < 1.0)
            .map(&convert),
    );
    (opaque, out.len() as u32)
}

impl DrawLists {
    /// Appends the custom meshes' instances to `meshes` and fills `custom_draws`.
    fn build_custom(&mut self, scene: &Scene) {
        self.custom_draws.clear();
        let mut order: Vec<(bool, usize, bool, usize)> = scene
            .custom_meshes
            .iter()
            .enumerate()
            .filter(|(_, m)| m.color[3].partial_cmp(&0.0) == Some(std::cmp::Ordering::Greater))
            .map(|(i, m)| {
                let unit = MeshInstance {
                    shape: Shape::Cube,
                    world_from_unit: m.world_from_mesh,
                    color: m.color,
                };
                let mirrored = mesh_instance_gpu(&unit).1;
                (
                    m.color[3] < 1.0,
                    std::sync::Arc::as_ptr(&m.mesh) as usize,
                    mirrored,
                    i,
                )
            })
            .collect();
        order.sort_unstable();
        for (translucent, key, mirrored, i) in order {
            let m = &scene.custom_meshes[i];
            let (gpu, _) = mesh_instance_gpu(&MeshInstance {
                shape: Shape::Cube,
                world_from_unit: m.world_from_mesh,
                color: m.color,
            });
            let at = self.meshes.len() as u32;
            self.meshes.push(gpu);
            match self.custom_draws.last_mut() {
                Some(last)
                    if (last.translucent, last.key, last.mirrored)
                        == (translucent, key, mirrored) =>
                {
                    last.instances.end = at + 1
                }
                _ => self.custom_draws.push(CustomDraw {
                    key,
                    scene_index: i,
                    translucent,
                    mirrored,
                    instances: at..at + 1,
                }),
            }
        }
    }

    /// Rebuilds every list for `scene` seen from `eye`. Items with alpha <= 0 (or a
    /// non-positive width or size) are left out.
    pub(crate) fn build(&mut self, scene: &Scene, eye: [f32; 3], proj: &Projection) {
        self.build_meshes(scene, eye, proj);
        self.build_custom(scene);
        let line_alpha = |l: &Line| if l.width_px > 0.0 { l.color[3] } else { 0.0 };
        let dot_alpha = |d: &Dot| if d.size_px > 0.0 { d.color[3] } else { 0.0 };
        (self.lines_opaque, _) = partition(&mut self.lines, &scene.lines, line_alpha, line_gpu);
        (self.dots_opaque, _) = partition(&mut self.dots, &scene.dots, dot_alpha, dot_gpu);
        // The underlay goes first: drawn before anything else, it is covered by all of it.
        let under: Vec<DotGpu> = scene
            .underlay
            .iter()
            .filter(|d| dot_alpha(d) > 0.0)
            .map(dot_gpu)
            .collect();
        self.dots_underlay = under.len() as u32;
        self.dots.splice(0..0, under);
    }

    /// The underlay's dots (an instance range).
    pub(crate) fn underlay_range(&self) -> Range<u32> {
        0..self.dots_underlay
    }

    /// The lines of one pass (an instance range).
    pub(crate) fn line_range(&self, translucent: bool) -> Range<u32> {
        if translucent {
            self.lines_opaque..self.lines.len() as u32
        } else {
            0..self.lines_opaque
        }
    }

    /// The dots of one pass (an instance range).
    pub(crate) fn dot_range(&self, translucent: bool) -> Range<u32> {
        let opaque_end = self.dots_underlay + self.dots_opaque;
        if translucent {
            opaque_end..self.dots.len() as u32
        } else {
            self.dots_underlay..opaque_end
        }
    }

    /// Fills `meshes` (opaque grouped by shape, level of detail and winding, then translucent
    /// back to front) and `mesh_draws`.
    fn build_meshes(&mut self, scene: &Scene, eye: [f32; 3], proj: &Projection) {
        self.opaque.iter_mut().for_each(Vec::clear);
        self.translucent.clear();
        self.meshes.clear();
        self.mesh_draws.clear();
        for m in &scene.meshes {
            let alpha = m.color[3];
            // Invisible (or NaN) alpha: nothing to draw.
            if alpha.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                continue;
            }
            let (gpu, mirrored) = mesh_instance_gpu(m);
            let key = DrawKey {
                shape: shape_index(m.shape),
                lod: mesh_lod(m, proj),
                mirrored,
            }
            .index();
            if alpha >= 1.0 {
                self.opaque[key].push(gpu);
            } else {
                let o = [
                    m.world_from_unit[3][0],
                    m.world_from_unit[3][1],
                    m.world_from_unit[3][2],
                ];
                let d = sub3(o, eye);
                self.translucent.push((dot3(d, d), key, gpu));
            }
        }
        for (key, group) in self.opaque.iter().enumerate() {
            if !group.is_empty() {
                let start = self.meshes.len() as u32;
                self.meshes.extend_from_slice(group);
                let instances = start..self.meshes.len() as u32;
                self.mesh_draws
                    .push(DrawKey::from_index(key).draw(false, instances));
            }
        }
        // Farthest first; the sort is stable, so equal distances keep scene order.
        self.translucent.sort_by(|a, b| b.0.total_cmp(&a.0));
        for &(_, key, gpu) in &self.translucent {
            let i = self.meshes.len() as u32;
            self.meshes.push(gpu);
            let key = DrawKey::from_index(key);
            match self.mesh_draws.last_mut() {
                Some(last)
                    if last.translucent
                        && (last.shape, last.lod, last.mirrored)
                            == (key.shape, key.lod, key.mirrored) =>
                {
                    last.instances.end = i + 1
                }
                _ => self.mesh_draws.push(key.draw(true, i..i + 1)),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Shape;

    #[test]
    fn normal_matrix_is_the_inverse_transpose_up_to_a_positive_factor() {
        // world_from_unit = diag(2, 0.5, 3) then a translation; mirrored copy with x negated.
        let mut m = MeshInstance {
            shape: Shape::Cube,
            world_from_unit: [
                [2.0, 0.0, 0.0, 0.0],
                [0.0, 0.5, 0.0, 0.0],
                [0.0, 0.0, 3.0, 0.0],
                [1.0, 2.0, 3.0, 1.0],
            ],
            color: [1.0; 4],
        };
        let (g, mirrored) = mesh_instance_gpu(&m);
        assert!(!mirrored);
        // M^-T = diag(0.5, 2, 1/3); the largest entry is scaled to 1.
        let expect = [0.25, 1.0, 1.0 / 6.0];
        for (k, e) in expect.iter().enumerate() {
            assert!(
                (g.normal_from_unit[k][k] - e).abs() < 1e-6,
                "{:?}",
                g.normal_from_unit
            );
        }
        m.world_from_unit[0][0] = -2.0;
        let (g, mirrored) = mesh_instance_gpu(&m);
        assert!(mirrored);
        assert!(
            g.normal_from_unit[0][0] < 0.0 && g.normal_from_unit[1][1] > 0.0,
            "outward normals stay outward"
        );
        m.world_from_unit[2][2] = 0.0;
        let (g, _) = mesh_instance_gpu(&m);
        assert!(g.normal_from_unit.iter().flatten().all(|v| v.is_finite()));
    }

    #[test]
    fn partition_puts_opaque_first_and_drops_invisible() {
        let mut out = Vec::new();
        let alphas = [0.5f32, 1.0, 0.0, 1.0, 0.2];
        let (opaque, all) = partition(&mut out, &alphas, |a| *a, |a| *a);
        assert_eq!((opaque, all), (2, 4));
        assert_eq!(out, vec![1.0, 1.0, 0.5, 0.2]);
    }

    #[test]
    fn round_bodies_get_more_segments_the_larger_they_look() {
        // Looking down -z from 2 m away with a 90 degree vertical field on a 1000 px view.
        let proj = Projection {
            clip_from_world: [
                [1.0, 0.0, 0.0, 0.0],
                [0.0, 1.0, 0.0, 0.0],
                [0.0, 0.0, 0.0, -1.0],
                [0.0, 0.0, 1.0, 2.0],
            ],
            height_px: 1000.0,
        };
        let cylinder = |radius: f32, z: f32| MeshInstance {
            shape: Shape::Cylinder,
            world_from_unit: [
                [radius, 0.0, 0.0, 0.0],
                [0.0, radius, 0.0, 0.0],
                [0.0, 0.0, 0.5, 0.0],
                [0.0, 0.0, z, 1.0],
            ],
            color: [1.0; 4],
        };
        // 1 cm at 2 m: 2.5 px; 20 cm: 50 px; 1 m at 1 m: 500 px; behind the eye: finest.
        assert_eq!(proj.radius_px([0.0, 0.0, 0.0], 0.01), 2.5);
        let lods = [(0.01, 0.0), (0.2, 0.0), (1.0, 1.0), (0.1, 3.0)]
            .map(|(r, z)| mesh_lod(&cylinder(r, z), &proj));
        assert_eq!(lods, [0, 2, 3, 3]);
        let cube = MeshInstance {
            shape: Shape::Cube,
            ..cylinder(1.0, 1.0)
        };
        assert_eq!(mesh_lod(&cube, &proj), 0);
    }
}
