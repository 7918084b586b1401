//! The GPU side of the 3D view: the wgpu pipelines, the vertex buffers (grown only when too
//! small) and the offscreen colour + depth target, and the render of one frame.

use eframe::egui::{self, Color32};
use eframe::egui_wgpu;
use eframe::wgpu;

use super::camera::Camera;
use super::vertex_data::{LINE_STRIDE, MeshData, SURFACE_STRIDE, push_vec3};
use super::{BACK_COLOUR, FRONT_COLOUR, NORMAL_COLOUR, View3dSettings, WIRE_COLOUR};

/// Width of the wireframe lines in pixels.
const WIRE_WIDTH_PX: f32 = 1.0;

const COLOUR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
const UNIFORM_SIZE: u64 = 64 + 7 * 16;

/// Pushes the linear RGB of `c` and then `w`.
fn push_colour(out: &mut Vec<u8>, c: Color32, w: f32) {
    let rgba = egui::Rgba::from(c);
    for x in [rgba.r(), rgba.g(), rgba.b(), w] {
        out.extend_from_slice(&x.to_le_bytes());
    }
}

/// The GPU side: pipelines, buffers and the render target.
pub(super) struct Gpu {
    pub(super) state: egui_wgpu::RenderState,
    shader: wgpu::ShaderModule,
    layout: wgpu::PipelineLayout,
    uniforms: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    pipelines: Option<Pipelines>,
    surface: Option<wgpu::Buffer>,
    lines: Option<wgpu::Buffer>,
    uploaded: Option<u64>,
    pub(super) target: Option<Target>,
    /// Sample count used with `msaa` (1 if the adapter cannot do 4).
    msaa_samples: u32,
}

struct Pipelines {
    samples: u32,
    surface: wgpu::RenderPipeline,
    lines: wgpu::RenderPipeline,
}

pub(super) struct Target {
    size: [u32; 2],
    samples: u32,
    /// Single-sampled, shown by egui.
    colour: wgpu::TextureView,
    /// Multisampled, resolved into `colour`.
    msaa: Option<wgpu::TextureView>,
    depth: wgpu::TextureView,
    pub(super) texture_id: egui::TextureId,
}

impl Gpu {
    pub(super) fn new(state: &egui_wgpu::RenderState) -> Self {
        let device = &state.device;
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("view3d shader"),
            source: wgpu::ShaderSource::Wgsl(include_str!("view3d.wgsl").into()),
        });
        let bind_group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("view3d uniforms"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(UNIFORM_SIZE),
                },
                count: None,
            }],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("view3d"),
            bind_group_layouts: &[Some(&bind_group_layout)],
            immediate_size: 0,
        });
        let uniforms = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("view3d uniforms"),
            size: UNIFORM_SIZE,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("view3d uniforms"),
            layout: &bind_group_layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: uniforms.as_entire_binding() }],
        });
        let can_msaa = |format| state.adapter.get_texture_format_features(format).flags.sample_count_supported(4);
        let msaa_samples = if can_msaa(COLOUR_FORMAT) && can_msaa(DEPTH_FORMAT) { 4 } else { 1 };
        Self {
            state: state.clone(),
            shader,
            layout,
            uniforms,
            bind_group,
            pipelines: None,
            surface: None,
            lines: None,
            uploaded: None,
            target: None,
            msaa_samples,
        }
    }

    fn pipelines(&mut self, samples: u32) -> &Pipelines {
        if self.pipelines.as_ref().is_none_or(|p| p.samples != samples) {
            self.pipelines = Some(Pipelines {
                samples,
                surface: self.pipeline(samples, true),
                lines: self.pipeline(samples, false),
            });
        }
        self.pipelines.as_ref().unwrap()
    }

    fn pipeline(&self, samples: u32, surface: bool) -> wgpu::RenderPipeline {
        let surface_attributes = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Unorm8x4];
        let line_attributes = wgpu::vertex_attr_array![0 => Float32x3];
        let (stride, attributes, topology, vs, fs) = if surface {
            (SURFACE_STRIDE, &surface_attributes[..], wgpu::PrimitiveTopology::TriangleList, "vs_surface", "fs_surface")
        } else {
            (LINE_STRIDE, &line_attributes[..], wgpu::PrimitiveTopology::LineList, "vs_line", "fs_line")
        };
        self.state.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(if surface { "view3d surface" } else { "view3d normals" }),
            layout: Some(&self.layout),
            vertex: wgpu::VertexState {
                module: &self.shader,
                entry_point: Some(vs),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: stride,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes,
                })],
            },
            primitive: wgpu::PrimitiveState { topology, cull_mode: None, ..Default::default() },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(if surface {
                    wgpu::CompareFunction::Less
                } else {
                    wgpu::CompareFunction::LessEqual
                }),
                stencil: wgpu::StencilState::default(),
                bias: wgpu::DepthBiasState::default(),
            }),
            multisample: wgpu::MultisampleState { count: samples, mask: !0, alpha_to_coverage_enabled: false },
            fragment: Some(wgpu::FragmentState {
                module: &self.shader,
                entry_point: Some(fs),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: COLOUR_FORMAT,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        })
    }

    /// (Re)creates the render target when the size or sample count changed.
    fn target(&mut self, size: [u32; 2], samples: u32) {
        if self.target.as_ref().is_some_and(|t| t.size == size && t.samples == samples) {
            return;
        }
        let device = &self.state.device;
        let texture = |label, format, samples, usage| {
            device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 },
                    mip_level_count: 1,
                    sample_count: samples,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage,
                    view_formats: &[],
                })
                .create_view(&wgpu::TextureViewDescriptor::default())
        };
        let colour = texture(
            "view3d colour",
            COLOUR_FORMAT,
            1,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
        );
        let msaa = (samples > 1)
            .then(|| texture("view3d colour (msaa)", COLOUR_FORMAT, samples, wgpu::TextureUsages::RENDER_ATTACHMENT));
        let depth = texture("view3d depth", DEPTH_FORMAT, samples, wgpu::TextureUsages::RENDER_ATTACHMENT);
        let mut renderer = self.state.renderer.write();
        let texture_id = match &self.target {
            Some(old) => {
                renderer.update_egui_texture_from_wgpu_texture(
                    device,
                    &colour,
                    wgpu::FilterMode::Linear,
                    old.texture_id,
                );
                old.texture_id
            }
            None => renderer.register_native_texture(device, &colour, wgpu::FilterMode::Linear),
        };
        self.target = Some(Target { size, samples, colour, msaa, depth, texture_id });
    }

    pub(super) fn render(&mut self, data: &MeshData, camera: &Camera, settings: &View3dSettings, size: [u32; 2]) {
        let samples = if settings.msaa { self.msaa_samples } else { 1 };
        self.target(size, samples);
        self.pipelines(samples);

        // Upload the mesh, into the existing buffers when they are large enough. A mesh too
        // large for one buffer is cut short rather than failing.
        let max_buffer = self.state.device.limits().max_buffer_size;
        let surface_len = clamp_len(data.surface.len(), 3 * SURFACE_STRIDE, max_buffer);
        let lines_len = clamp_len(data.lines.len(), 2 * LINE_STRIDE, max_buffer);
        if self.uploaded != Some(data.generation) {
            upload(&self.state, &mut self.surface, &data.surface[..surface_len], "view3d surface");
            upload(&self.state, &mut self.lines, &data.lines[..lines_len], "view3d normals");
            self.uploaded = Some(data.generation);
        }

        // Uniforms.
        let (centre, radius) = data.centre_radius();
        let eye = camera.eye();
        let reach = 1.2 * radius;
        let to_centre = (eye - centre).length();
        let far = (to_centre + reach).max(1e-9);
        let near = (to_centre - reach).max(far * 1e-4);
        let aspect = f64::from(size[0]) / f64::from(size[1]);
        let view_proj = camera.view_proj(data.origin, aspect, near, far).as_mat4();
        let (right, up) = camera.right_up();
        let light = (-0.45 * right + 0.65 * up + camera.back()).normalize();
        let mut u = Vec::with_capacity(UNIFORM_SIZE as usize);
        for x in view_proj.to_cols_array() {
            u.extend_from_slice(&x.to_le_bytes());
        }
        push_vec3(&mut u, (eye - data.origin).as_vec3());
        u.extend_from_slice(&1f32.to_le_bytes());
        push_vec3(&mut u, light.as_vec3());
        u.extend_from_slice(&0f32.to_le_bytes());
        push_colour(&mut u, FRONT_COLOUR, 1.0);
        push_colour(&mut u, BACK_COLOUR, 1.0);
        push_colour(&mut u, WIRE_COLOUR, 0.5 * WIRE_WIDTH_PX);
        push_colour(&mut u, NORMAL_COLOUR, 1.0);
        let flag = |b: bool| if b { 1f32 } else { 0f32 };
        for x in [
            flag(settings.wireframe),
            flag(settings.smooth),
            flag(settings.show_backfaces_colour),
            match (data.has_colours, settings.checker, settings.vertex_colours) {
                (true, true, _) => 2.0,
                (true, false, true) => 1.0,
                _ => 0.0,
            },
        ] {
            u.extend_from_slice(&x.to_le_bytes());
        }
        debug_assert_eq!(u.len() as u64, UNIFORM_SIZE);
        self.state.queue.write_buffer(&self.uniforms, 0, &u);

        let (Some(target), Some(pipelines)) = (&self.target, &self.pipelines) else { return };
        // Transparent (premultiplied) where nothing is drawn: egui paints the background,
        // the grid and the axes under the image.
        let clear = wgpu::Color::TRANSPARENT;
        let mut encoder =
            self.state.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("view3d") });
        {
            let (view, resolve_target, store) = match &target.msaa {
                Some(msaa) => (msaa, Some(&target.colour), wgpu::StoreOp::Discard),
                None => (&target.colour, None, wgpu::StoreOp::Store),
            };
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("view3d"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target,
                    ops: wgpu::Operations { load: wgpu::LoadOp::Clear(clear), store },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &target.depth,
                    depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Discard }),
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            pass.set_bind_group(0, &self.bind_group, &[]);
            if let Some(buffer) = &self.surface
                && surface_len > 0
                && settings.surface
            {
                pass.set_pipeline(&pipelines.surface);
                pass.set_vertex_buffer(0, buffer.slice(..surface_len as u64));
                pass.draw(0..(surface_len as u64 / SURFACE_STRIDE) as u32, 0..1);
            }
            if settings.normals
                && let Some(buffer) = &self.lines
                && lines_len > 0
            {
                pass.set_pipeline(&pipelines.lines);
                pass.set_vertex_buffer(0, buffer.slice(..lines_len as u64));
                pass.draw(0..(lines_len as u64 / LINE_STRIDE) as u32, 0..1);
            }
        }
        self.state.queue.submit(Some(encoder.finish()));
    }
}

/// `len` cut down to a multiple of `unit` bytes that fits in `max` bytes.
fn clamp_len(len: usize, unit: u64, max: u64) -> usize {
    let len = (len as u64).min(max);
    (len - len % unit) as usize
}

/// Writes `bytes` to the buffer in `slot`, replacing it with a larger one if needed.
fn upload(state: &egui_wgpu::RenderState, slot: &mut Option<wgpu::Buffer>, bytes: &[u8], label: &str) {
    if bytes.is_empty() {
        return;
    }
    let needed = bytes.len() as u64;
    if slot.as_ref().is_none_or(|b| b.size() < needed) {
        let max = state.device.limits().max_buffer_size;
        let size = (needed + needed / 2).next_multiple_of(256).min(max).max(needed);
        *slot = Some(state.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        }));
    }
    if let Some(buffer) = slot {
        state.queue.write_buffer(buffer, 0, bytes);
    }
}
