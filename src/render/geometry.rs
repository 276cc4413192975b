//! The four unit shapes as indexed triangle meshes with smooth normals, built once.
//! Every triangle winds counter-clockwise seen from outside (wgpu's default front face).

use super::gpu_types::MeshVertex;
use crate::scene::Shape;
use std::f32::consts::TAU;
use std::ops::Range;

/// Segments around the circle of cylinders, cones and spheres (round at 2400 px).
pub(crate) const SEGMENTS: u32 = 48;

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

/// All four shapes in one vertex and one index list.
#[derive(Debug, Clone)]
pub(crate) struct UnitMeshes {
    /// Vertices of every shape.
    pub vertices: Vec<MeshVertex>,
    /// Indices into `vertices` (absolute).
    pub indices: Vec<u32>,
    /// The index range of each shape, in [`SHAPES`] order.
    pub ranges: [Range<u32>; 4],
}

#[derive(Default)]
struct Builder {
    vertices: Vec<MeshVertex>,
    indices: Vec<u32>,
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
        for i in 0..=SEGMENTS {
            let (s, c) = (TAU * i as f32 / SEGMENTS as f32).sin_cos();
            self.vertex([c, s, z], n);
        }
        for i in 0..SEGMENTS {
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
        for i in 0..=SEGMENTS {
            let (s, c) = (TAU * i as f32 / SEGMENTS as f32).sin_cos();
            self.vertex([c, s, -0.5], [c, s, 0.0]);
            self.vertex([c, s, 0.5], [c, s, 0.0]);
        }
        for i in 0..SEGMENTS {
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
        let rings = SEGMENTS / 2;
        let first = self.vertices.len() as u32;
        let stride = SEGMENTS + 1;
        for j in 0..=rings {
            let (sp, cp) = (std::f32::consts::PI * j as f32 / rings as f32).sin_cos();
            for i in 0..=SEGMENTS {
                let (s, c) = (TAU * i as f32 / SEGMENTS as f32).sin_cos();
                let p = [sp * c, sp * s, cp];
                self.vertex(p, p);
            }
        }
        for j in 0..rings {
            for i in 0..SEGMENTS {
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
        for i in 0..=SEGMENTS {
            let (s, c) = (TAU * i as f32 / SEGMENTS as f32).sin_cos();
            self.vertex([c, s, 0.0], [c * k, s * k, k]);
        }
        for i in 0..SEGMENTS {
            let (s, c) = (TAU * (i as f32 + 0.5) / SEGMENTS as f32).sin_cos();
            let apex = self.vertex([0.0, 0.0, 1.0], [c * k, s * k, k]);
            self.tri(first + i, first + i + 1, apex);
        }
        self.disc(0.0, false);
    }
}

impl UnitMeshes {
    /// Builds the four shapes.
    pub(crate) fn new() -> Self {
        let mut b = Builder::default();
        let ranges = SHAPES.map(|shape| {
            let start = b.indices.len() as u32;
            match shape {
                Shape::Cylinder => b.cylinder(),
                Shape::Cube => b.cube(),
                Shape::Sphere => b.sphere(),
                Shape::Cone => b.cone(),
            }
            start..b.indices.len() as u32
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
        for (shape, range) in SHAPES.iter().zip(&m.ranges) {
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
}
