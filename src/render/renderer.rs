//! [`Renderer`]: draws a [`Scene`] into a [`RenderTarget`].

use super::buffer::GrowBuffer;
use super::gamma::GammaEncode;
use super::geometry::{LOD_SEGMENTS, UnitMeshes};
use super::gpu_types::{FrameUniforms, MeshVertex};
use super::instances::{DrawLists, Projection};
use super::pipelines::Pipelines;
use super::settings::frame_uniforms;
use super::{Gpu, RenderError, RenderSettings, RenderTarget, SAMPLE_COUNTS, ViewUniforms};
use crate::mesh::{TriMesh, Winding};
use crate::scene::Scene;
use std::collections::HashMap;
use std::ops::Range;
use std::sync::Arc;
use wgpu::util::DeviceExt;

/// Draws scenes: lit instanced meshes, screen-space lines and round dots.
///
/// Create once per device and sample count; [`Self::render`] as often as needed. Instance
/// buffers grow to fit and are reused, so a scene of unchanged size allocates nothing.
#[derive(Debug)]
pub struct Renderer {
    sample_count: u32,
    pipelines: Pipelines,
    frame_buffer: wgpu::Buffer,
    frame_bind_group: wgpu::BindGroup,
    shape_vertices: wgpu::Buffer,
    shape_indices: wgpu::Buffer,
    shape_ranges: [[Range<u32>; 4]; LOD_SEGMENTS.len()],
    mesh_instances: GrowBuffer,
    line_instances: GrowBuffer,
    dot_instances: GrowBuffer,
    lists: DrawLists,
    /// Custom meshes uploaded so far, by the address of their `Arc` (kept alive here, so the
    /// address is not reused while cached); dropped once nothing else holds the mesh.
    custom: HashMap<usize, CustomGpu>,
    /// The sRGB re-encoding copy, made for the first target that needs it (WebGL2).
    gamma: Option<GammaEncode>,
}

/// A custom mesh on the GPU: one vertex per triangle corner with the face normal (flat
/// shading, as CAD meshes are meant to be seen). A closed surface wound inward is flipped; an
/// open or inconsistently wound one gets every triangle twice, once each way round, so every
/// face shows (back faces are culled, so each is drawn once, lit from the side it is seen).
#[derive(Debug)]
struct CustomGpu {
    mesh: Arc<TriMesh>,
    vertices: wgpu::Buffer,
    count: u32,
}

impl CustomGpu {
    fn new(device: &wgpu::Device, mesh: &Arc<TriMesh>) -> Self {
        let p = &mesh.positions;
        let winding = mesh.winding();
        let mut verts = Vec::with_capacity(mesh.triangles.len() * 6);
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| p[i as usize]);
            let [b, c] = if winding == Winding::Inward {
                [c, b]
            } else {
                [b, c]
            };
            let (u, v) = (
                [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
                [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
            );
            let n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            let normal = if len > 0.0 {
                n.map(|x| x / len)
            } else {
                [0.0, 0.0, 1.0]
            };
            for position in [a, b, c] {
                verts.push(MeshVertex { position, normal });
            }
            if winding != Winding::Mixed {
                continue;
            }
            let back = normal.map(|x| -x);
            for position in [a, c, b] {
                verts.push(MeshVertex {
                    position,
                    normal: back,
                });
            }
        }
        let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("armlab custom mesh"),
            contents: bytemuck::cast_slice(&verts),
            usage: wgpu::BufferUsages::VERTEX,
        });
        Self {
            mesh: mesh.clone(),
            vertices,
            count: verts.len() as u32,
        }
    }
}

impl Renderer {
    /// Builds the pipelines for `sample_count` (1, or 4 for MSAA) and uploads the unit shapes.
    pub fn new(gpu: &Gpu, sample_count: u32) -> Result<Self, RenderError> {
        if !SAMPLE_COUNTS.contains(&sample_count) {
            return Err(RenderError::UnsupportedSampleCount {
                count: sample_count,
            });
        }
        let device = &gpu.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let pipelines = Pipelines::new(device, sample_count);
        let frame_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("armlab frame"),
            size: size_of::<FrameUniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let frame_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("armlab frame"),
            layout: &pipelines.frame_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: frame_buffer.as_entire_binding(),
            }],
        });
        let shapes = UnitMeshes::new();
        let shape_vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("armlab shape vertices"),
            contents: bytemuck::cast_slice(&shapes.vertices),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let shape_indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("armlab shape indices"),
            contents: bytemuck::cast_slice(&shapes.indices),
            usage: wgpu::BufferUsages::INDEX,
        });
        if let Some(e) = super::error::scope_error(scope.pop()) {
            return Err(e.into());
        }
        Ok(Self {
            sample_count,
            pipelines,
            frame_buffer,
            frame_bind_group,
            shape_vertices,
            shape_indices,
            shape_ranges: shapes.ranges,
            mesh_instances: GrowBuffer::new(
                "armlab mesh instances",
                "meshes",
                wgpu::BufferUsages::VERTEX,
            ),
            line_instances: GrowBuffer::new(
                "armlab line instances",
                "lines",
                wgpu::BufferUsages::VERTEX,
            ),
            dot_instances: GrowBuffer::new(
                "armlab dot instances",
                "dots",
                wgpu::BufferUsages::VERTEX,
            ),
            lists: DrawLists::default(),
            custom: HashMap::new(),
            gamma: None,
        })
    }

    /// Samples per pixel the pipelines were built for; targets must match.
    pub fn sample_count(&self) -> u32 {
        self.sample_count
    }

    /// How many times an instance buffer was (re)allocated since creation (a diagnostic: it
    /// stays put while the scene's size does not grow).
    pub fn buffer_allocations(&self) -> u32 {
        self.mesh_instances.allocations()
            + self.line_instances.allocations()
            + self.dot_instances.allocations()
    }

    /// Draws `scene` into `target` and submits the work (does not wait for it).
    ///
    /// Order: the underlay's dots (no depth test or write, so everything covers them); opaque
    /// meshes; opaque lines and dots (depth written); translucent meshes
    /// (alpha < 1) sorted back to front by the distance from the eye to their origin, blended
    /// with depth test on and depth write off; then translucent lines and dots. Items with
    /// alpha <= 0 are skipped.
    pub fn render(
        &mut self,
        gpu: &Gpu,
        target: &RenderTarget,
        scene: &Scene,
        view: &ViewUniforms,
        settings: &RenderSettings,
    ) -> Result<(), RenderError> {
        let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("armlab frame"),
            });
        let encoded = self.encode(gpu, &mut encoder, target, scene, view, settings);
        if encoded.is_ok() {
            gpu.queue.submit([encoder.finish()]);
        }
        let gpu_error = super::error::scope_error(scope.pop());
        encoded?;
        match gpu_error {
            Some(e) => Err(e.into()),
            None => Ok(()),
        }
    }

    /// Like [`Self::render`] but records into the caller's encoder (uploads go through the
    /// queue and land before the caller's next submit).
    pub fn encode(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        target: &RenderTarget,
        scene: &Scene,
        view: &ViewUniforms,
        settings: &RenderSettings,
    ) -> Result<(), RenderError> {
        if target.sample_count() != self.sample_count {
            return Err(RenderError::SampleCountMismatch {
                renderer: self.sample_count,
                target: target.sample_count(),
            });
        }
        let frame = frame_uniforms(target.size(), view, settings);
        gpu.queue
            .write_buffer(&self.frame_buffer, 0, bytemuck::bytes_of(&frame));
        let proj = Projection {
            clip_from_world: view.clip_from_world,
            height_px: frame.viewport[1],
        };
        self.lists.build(scene, view.eye, &proj);
        self.custom.retain(|_, g| Arc::strong_count(&g.mesh) > 1);
        for d in &self.lists.custom_draws {
            let mesh = &scene.custom_meshes[d.scene_index].mesh;
            self.custom
                .entry(d.key)
                .or_insert_with(|| CustomGpu::new(&gpu.device, mesh));
        }
        self.mesh_instances.write(gpu, &self.lists.meshes)?;
        self.line_instances.write(gpu, &self.lists.lines)?;
        self.dot_instances.write(gpu, &self.lists.dots)?;

        let c = settings.clear.map(f64::from);
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("armlab scene"),
            color_attachments: &[Some(target.color_attachment(wgpu::Color {
                r: c[0],
                g: c[1],
                b: c[2],
                a: c[3],
            }))],
            depth_stencil_attachment: Some(target.depth_attachment()),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &self.frame_bind_group, &[]);
        let under = self.lists.underlay_range();
        if let (Some(buffer), false) = (self.dot_instances.buffer(), under.is_empty()) {
            pass.set_pipeline(&self.pipelines.dot_underlay);
            pass.set_vertex_buffer(0, buffer.slice(..));
            pass.draw(0..3, under);
        }
        for translucent in [false, true] {
            self.draw_meshes(&mut pass, translucent);
            self.draw_overlays(&mut pass, translucent);
        }
        drop(pass);
        if let Some(to) = target.encoded_view() {
            let device = &gpu.device;
            let gamma = self.gamma.get_or_insert_with(|| GammaEncode::new(device));
            gamma.encode(device, encoder, target.color_view(), &to);
        }
        Ok(())
    }

    fn draw_meshes(&self, pass: &mut wgpu::RenderPass<'_>, translucent: bool) {
        let Some(instances) = self.mesh_instances.buffer() else {
            return;
        };
        let mut bound = false;
        for d in self
            .lists
            .mesh_draws
            .iter()
            .filter(|d| d.translucent == translucent)
        {
            if !bound {
                pass.set_vertex_buffer(0, self.shape_vertices.slice(..));
                pass.set_vertex_buffer(1, instances.slice(..));
                pass.set_index_buffer(self.shape_indices.slice(..), wgpu::IndexFormat::Uint32);
                bound = true;
            }
            pass.set_pipeline(&self.pipelines.mesh[translucent as usize][d.mirrored as usize]);
            pass.draw_indexed(
                self.shape_ranges[d.lod][d.shape].clone(),
                0,
                d.instances.clone(),
            );
        }
        for d in self
            .lists
            .custom_draws
            .iter()
            .filter(|d| d.translucent == translucent)
        {
            let Some(g) = self.custom.get(&d.key) else {
                continue;
            };
            pass.set_pipeline(&self.pipelines.mesh[translucent as usize][d.mirrored as usize]);
            pass.set_vertex_buffer(0, g.vertices.slice(..));
            pass.set_vertex_buffer(1, instances.slice(..));
            pass.draw(0..g.count, d.instances.clone());
        }
    }

    fn draw_overlays(&self, pass: &mut wgpu::RenderPass<'_>, translucent: bool) {
        // Lines: a 4-vertex strip (quad) each; dots: one triangle each.
        for (pipelines, buffer, range, vertices) in [
            (
                &self.pipelines.line,
                &self.line_instances,
                self.lists.line_range(translucent),
                4,
            ),
            (
                &self.pipelines.dot,
                &self.dot_instances,
                self.lists.dot_range(translucent),
                3,
            ),
        ] {
            if let (Some(buffer), false) = (buffer.buffer(), range.is_empty()) {
                pass.set_pipeline(&pipelines[translucent as usize]);
                pass.set_vertex_buffer(0, buffer.slice(..));
                pass.draw(0..vertices, range);
            }
        }
    }
}
