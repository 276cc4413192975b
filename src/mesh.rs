//! Triangle meshes as plain data (f32, as mesh files store them): what a URDF's mesh files are
//! read into, what the scene draws and the renderer uploads. A leaf module: [`crate::urdf`],
//! [`crate::kinematics`] and the renderer all name these types, and it names none of them.

/// A triangle mesh in its own frame (m, the URDF's `scale` applied), f32 as mesh files store it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TriMesh {
    /// Vertex positions (m).
    pub positions: Vec<[f32; 3]>,
    /// Triangles as indices into `positions`, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

/// Triangles of a mesh's coarse copy, drawn in a live view's moving frames on a software
/// rasterizer (the still frame after them draws the full mesh).
pub const COARSE_TRIANGLES: usize = 500;

/// How a mesh's triangles are wound, which decides how it can be drawn with back faces culled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Winding {
    /// A closed surface wound counter-clockwise seen from outside (positive volume).
    Outward,
    /// A closed surface wound the other way (negative volume): flip every triangle.
    Inward,
    /// Open, or wound inconsistently (an edge used twice in one direction): draw both sides.
    Mixed,
}

impl TriMesh {
    /// The winding of the triangles: each edge of a closed, consistently wound surface is used
    /// once in each direction, and the sign of the enclosed volume says which side is out.
    /// Vertices at the same position count as one (mesh files often repeat a vertex per face to
    /// give it that face's normal).
    pub fn winding(&self) -> Winding {
        use std::collections::HashMap;
        let mut welded: HashMap<[u32; 3], u32> = HashMap::with_capacity(self.positions.len());
        let canon: Vec<u32> = self
            .positions
            .iter()
            .enumerate()
            .map(|(i, p)| {
                *welded
                    .entry(p.map(|v| (v + 0.0).to_bits()))
                    .or_insert(i as u32)
            })
            .collect();
        let mut edges: HashMap<(u32, u32), u32> = HashMap::with_capacity(self.triangles.len() * 3);
        for t in &self.triangles {
            let t = t.map(|i| canon[i as usize]);
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                let n = edges.entry((a, b)).or_insert(0);
                *n += 1;
                if *n > 1 {
                    return Winding::Mixed;
                }
            }
        }
        if edges.keys().any(|&(a, b)| !edges.contains_key(&(b, a))) {
            return Winding::Mixed;
        }
        let volume: f64 = self
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.positions[i as usize].map(f64::from));
                a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0])
            })
            .sum();
        if volume >= 0.0 {
            Winding::Outward
        } else {
            Winding::Inward
        }
    }

    /// The mesh reduced to at most about `max_triangles` by vertex clustering: vertices are
    /// merged on a grid over the bounding box (the cell shrinks until the budget holds), and
    /// triangles that collapse are dropped. The shape keeps its outline to about one cell.
    pub fn decimated(&self, max_triangles: usize) -> TriMesh {
        if self.triangles.len() <= max_triangles || self.positions.is_empty() {
            return self.clone();
        }
        let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        for p in &self.positions {
            for ((l, h), v) in lo.iter_mut().zip(hi.iter_mut()).zip(p) {
                *l = l.min(*v);
                *h = h.max(*v);
            }
        }
        let mut cells = ((max_triangles as f64 / 2.0).sqrt() as u32).max(2);
        loop {
            let out = self.clustered(lo, hi, cells);
            if out.triangles.len() <= max_triangles || cells <= 2 {
                return out;
            }
            cells = (cells * 3 / 4).max(2);
        }
    }

    /// Vertex clustering on a grid of `cells` per side over the box [lo, hi].
    fn clustered(&self, lo: [f32; 3], hi: [f32; 3], cells: u32) -> TriMesh {
        use std::collections::HashMap;
        let size: [f32; 3] = std::array::from_fn(|k| (hi[k] - lo[k]).max(f32::MIN_POSITIVE));
        let cell_of = |p: &[f32; 3]| -> [u32; 3] {
            std::array::from_fn(|k| {
                (((p[k] - lo[k]) / size[k] * cells as f32) as u32).min(cells - 1)
            })
        };
        let mut index: HashMap<[u32; 3], u32> = HashMap::new();
        let mut sums: Vec<([f64; 3], u32)> = Vec::new();
        let remap: Vec<u32> = self
            .positions
            .iter()
            .map(|p| {
                let k = *index.entry(cell_of(p)).or_insert_with(|| {
                    sums.push(([0.0; 3], 0));
                    sums.len() as u32 - 1
                });
                let s = &mut sums[k as usize];
                for (sum, v) in s.0.iter_mut().zip(p) {
                    *sum += f64::from(*v);
                }
                s.1 += 1;
                k
            })
            .collect();
        let positions = sums
            .iter()
            .map(|(s, n)| std::array::from_fn(|i| (s[i] / f64::from(*n)) as f32))
            .collect();
        let mut seen = std::collections::HashSet::new();
        let triangles = self
            .triangles
            .iter()
            .map(|t| t.map(|v| remap[v as usize]))
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .filter(|t| {
                let mut key = *t;
                key.sort_unstable();
                seen.insert(key)
            })
            .collect();
        TriMesh {
            positions,
            triangles,
        }
    }
}
