//! The four unit shapes as indexed triangle meshes with smooth normals, built once.
//! Every triangle winds counter-clockwise seen from outside (wgpu's default front face).

use super::gpu_types::MeshVertex;
use crate::scene::Shape;
use std::f32::consts::TAU;
use std::ops::Range;

/// Segments around the circle of cylinders, cones and spheres, one mesh per level of detail.
/// A software rasterizer pays for every thin triangle a round body is cut into, so each
/// instance uses the coarsest level whose silhouette stays within [`MAX_SILHOUETTE_ERROR_PX`]
/// of the true circle (see [`lod_for_radius_px`]); the finest is round at 2400 px.
pub(crate) const LOD_SEGMENTS: [u32; 4] = [12, 24, 48, 96];

/// Largest distance (px) between a polygonal silhouette and the circle it stands for.
pub(crate) const MAX_SILHOUETTE_ERROR_PX: f32 = 0.3;

/// The level of detail for a round body whose radius projects to `radius_px` pixels: the
/// fewest segments `n` with `radius_px * (1 - cos(pi / n)) <= MAX_SILHOUETTE_ERROR_PX`
/// (the finest level when none is enough, or when the radius is not finite).
pub(crate) fn lod_for_radius_px(radius_px: f32) -> usize {
    if !radius_px.is_finite() {
        return LOD_SEGMENTS.len() - 1;
    }
    LOD_SEGMENTS
        .iter()
        .position(|&n| {
            radius_px * (1.0 - (std::f32::consts::PI / n as f32).cos()) <= MAX_SILHOUETTE_ERROR_PX
        })
        .unwrap_or(LOD_SEGMENTS.len() - 1)
}

/// Shapes in the order of their index ranges.
pub(crate) const SHAPES: [Shape; 4] = [Shape::Cylinder, Shape::Cube, Shape::Sphere, Shape::Cone];

/// Index of a shape in [`SHAPES`].
pub(crate) fn shape_index(shape: Shape) -> usize {
    match shape {
        Shape::Cylinder => 0,
        Shape::Cube => 1,
        Shape::Sphere => 2,
        Shape::Cone => 3,
    }
}

/// All four shapes at every level of detail in one vertex and one index list.
#[derive(Debug, Clone)]
pub(crate) struct UnitMeshes {
    /// Vertices of every shape.
    pub vertices: Vec<MeshVertex>,
    /// Indices into `vertices` (absolute).
    pub indices: Vec<u32>,
    /// The index range of each shape, by level of detail and then in [`SHAPES`] order.
    pub ranges: [[Range<u32>; 4]; LOD_SEGMENTS.len()],
}

#[derive(Default)]
struct Builder {
    vertices: Vec<MeshVertex>,
    indices: Vec<u32>,
    /// Segments around the circle of the shapes being built.
    segments: u32,
}

impl Builder {
    fn vertex(&mut self, position: [f32; 3], normal: [f32; 3]) -> u32 {
        self.vertices.push(MeshVertex { position, normal });
        self.vertices.len() as u32 - 1
    }

    fn tri(&mut self, a: u32, b: u32, c: u32) {
        self.indices.extend([a, b, c]);
    }

    /// A disc of radius 1 at height `z` facing +z (`up`) or -z.
    fn disc(&mut self, z: f32, up: bool) {
        let n = if up {
            [0.0, 0.0, 1.0]
        } else {
            [0.0, 0.0, -1.0]
        };
        let centre = self.vertex([0.0, 0.0, z], n);
        let first = self.vertices.len() as u32;
        for i in 0..=self.segments {
            let (s, c) = (TAU * i as f32 / self.segments as f32).sin_cos();
            self.vertex([c, s, z], n);
        }
        for i in 0..self.segments {
            let (r0, r1) = (first + i, first + i + 1);
            if up {
                self.tri(centre, r0, r1)
            } else {
                self.tri(centre, r1, r0)
            }
        }
    }

    fn cylinder(&mut self) {
        let first = self.vertices.len() as u32;
        for i in 0..=self.segments {
            let (s, c) = (TAU * i as f32 / self.segments as f32).sin_cos();
            self.vertex([c, s, -0.5], [c, s, 0.0]);
            self.vertex([c, s, 0.5], [c, s, 0.0]);
        }
        for i in 0..self.segments {
            let (b0, t0, b1, t1) = (
                first + 2 * i,
                first + 2 * i + 1,
                first + 2 * i + 2,
                first + 2 * i + 3,
            );
            self.tri(b0, b1, t1);
            self.tri(b0, t1, t0);
        }
        self.disc(0.5, true);
        self.disc(-0.5, false);
    }

    fn cube(&mut self) {
        // (normal, u, v) with u x v = normal.
        let faces: [([f32; 3], [f32; 3], [f32; 3]); 6] = [
            ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
            ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            ([0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
        ];
        for (n, u, v) in faces {
            let first = self.vertices.len() as u32;
            for (su, sv) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)] {
                let p = std::array::from_fn(|k| n[k] * 0.5 + u[k] * su + v[k] * sv);
                self.vertex(p, n);
            }
            self.tri(first, first + 1, first + 2);
            self.tri(first, first + 2, first + 3);
        }
    }

    fn sphere(&mut self) {
        let rings = self.segments / 2;
        let first = self.vertices.len() as u32;
        let stride = self.segments + 1;
        for j in 0..=rings {
            let (sp, cp) = (std::f32::consts::PI * j as f32 / rings as f32).sin_cos();
            for i in 0..=self.segments {
                let (s, c) = (TAU * i as f32 / self.segments as f32).sin_cos();
                let p = [sp * c, sp * s, cp];
                self.vertex(p, p);
            }
        }
        for j in 0..rings {
            for i in 0..self.segments {
                let a = first + j * stride + i;
                let (b, c, d) = (a + stride, a + stride + 1, a + 1);
                if j + 1 < rings {
                    self.tri(a, b, c);
                }
                if j > 0 {
                    self.tri(a, c, d);
                }
            }
        }
    }

    fn cone(&mut self) {
        let k = std::f32::consts::FRAC_1_SQRT_2;
        let first = self.vertices.len() as u32;
        for i in 0..=self.segments {
            let (s, c) = (TAU * i as f32 / self.segments as f32).sin_cos();
            self.vertex([c, s, 0.0], [c * k, s * k, k]);
        }
        for i in 0..self.segments {
            let (s, c) = (TAU * (i as f32 + 0.5) / self.segments as f32).sin_cos();
            let apex = self.vertex([0.0, 0.0, 1.0], [c * k, s * k, k]);
            self.tri(first + i, first + i + 1, apex);
        }
        self.disc(0.0, false);
    }
}

impl UnitMeshes {
    /// Builds the four shapes at every level of detail.
    pub(crate) fn new() -> Self {
        let mut b = Builder::default();
        let ranges = LOD_SEGMENTS.map(|segments| {
            b.segments = segments;
            SHAPES.map(|shape| {
                let start = b.indices.len() as u32;
                match shape {
                    Shape::Cylinder => b.cylinder(),
                    Shape::Cube => b.cube(),
                    Shape::Sphere => b.sphere(),
                    Shape::Cone => b.cone(),
                }
                start..b.indices.len() as u32
            })
        });
        Self {
            vertices: b.vertices,
            indices: b.indices,
            ranges,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }
    fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }
    fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    #[test]
    fn triangles_wind_outward_and_normals_are_unit_and_inside_the_unit_shape() {
        let m = UnitMeshes::new();
        for (shape, range) in m.ranges.iter().flat_map(|r| SHAPES.iter().zip(r)) {
            assert!(range.len() % 3 == 0 && !range.is_empty(), "{shape:?}");
            for t in m.indices[range.start as usize..range.end as usize].chunks_exact(3) {
                let [a, b, c] = [0, 1, 2].map(|k| m.vertices[t[k] as usize]);
                let face = cross(sub(b.position, a.position), sub(c.position, a.position));
                let n = [0, 1, 2].map(|k| a.normal[k] + b.normal[k] + c.normal[k]);
                assert!(dot(face, n) > 0.0, "{shape:?}: triangle {t:?} winds inward");
            }
        }
        for v in &m.vertices {
            assert!((dot(v.normal, v.normal) - 1.0).abs() < 1e-5);
            assert!(v.position.iter().all(|x| x.abs() <= 1.0 + 1e-6));
        }
    }

    #[test]
    fn level_of_detail_keeps_the_silhouette_within_the_bound() {
        assert_eq!(lod_for_radius_px(0.0), 0);
        assert_eq!(lod_for_radius_px(f32::NAN), LOD_SEGMENTS.len() - 1);
        assert_eq!(lod_for_radius_px(1e9), LOD_SEGMENTS.len() - 1);
        let mut last = 0;
        for r in (0..2000).map(|k| k as f32 * 0.25) {
            let lod = lod_for_radius_px(r);
            assert!(lod >= last, "coarser at a larger radius {r}");
            last = lod;
            let n = LOD_SEGMENTS[lod] as f32;
            let err = r * (1.0 - (std::f32::consts::PI / n).cos());
            assert!(
                err <= MAX_SILHOUETTE_ERROR_PX || lod == LOD_SEGMENTS.len() - 1,
                "r {r}"
            );
            if lod > 0 {
                let coarser = LOD_SEGMENTS[lod - 1] as f32;
                assert!(
                    r * (1.0 - (std::f32::consts::PI / coarser).cos()) > MAX_SILHOUETTE_ERROR_PX
                );
            }
        }
    }
}
