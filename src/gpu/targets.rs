//! The render targets' formats and textures, described once: a leaf that the offscreen
//! target, the window's presenters and the host-memory targets all build on (it uses only
//! wgpu).

/// Colour format of every render target (offscreen and, as Bgra8Unorm, windows).
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// Depth format of every render target.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// A depth texture matching a colour target's size.
pub fn depth_texture(device: &wgpu::Device, width: u32, height: u32) -> wgpu::TextureView {
    let desc = target_descriptor(
        "shaderlab.depth",
        width.max(1),
        height.max(1),
        DEPTH_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT,
    );
    device
        .create_texture(&desc)
        .create_view(&wgpu::TextureViewDescriptor::default())
}

/// A render target's texture: one `width` x `height` 2D image (one level, one sample) in
/// `format`, used as `usage` says.
pub fn target_descriptor(
    label: &str,
    width: u32,
    height: u32,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::TextureDescriptor<'_> {
    wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    }
}

/// A colour texture in `format` that can be drawn into and copied out of, and its view.
pub fn copyable_color(
    device: &wgpu::Device,
    label: &str,
    width: u32,
    height: u32,
    format: wgpu::TextureFormat,
) -> (wgpu::Texture, wgpu::TextureView) {
    let texture = device.create_texture(&target_descriptor(
        label,
        width,
        height,
        format,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
    ));
    let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
    (texture, view)
}

/// A texture as [`target_descriptor`] describes it, labelled `label`, and its view labelled
/// `label_view`.
pub fn texture_and_view(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> (wgpu::Texture, wgpu::TextureView) {
    let texture = device.create_texture(&target_descriptor(label, width, height, format, usage));
    let view = texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some(&format!("{label}_view")),
        ..Default::default()
    });
    (texture, view)
}

/// A vertex shader entry point `full_screen` (WGSL) drawing one triangle that covers the
/// target: three vertices, no buffers.
pub const FULL_SCREEN_WGSL: &str = r"
@vertex
fn full_screen(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let p = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
}
";

/// A pipeline that runs `module`'s fragment entry point `entry` over the whole target (the
/// module holds [`FULL_SCREEN_WGSL`]), into `targets`, with no depth or blending of its own.
pub fn full_screen_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::PipelineLayout,
    module: &wgpu::ShaderModule,
    entry: &str,
    targets: &[Option<wgpu::ColorTargetState>],
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("full_screen"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// Records copying `texture`'s first `width` × `height` texels into `buffer`, rows `stride`
/// bytes apart ([`padded_row`]), for the CPU to map.
pub fn copy_to_buffer(
    encoder: &mut wgpu::CommandEncoder,
    texture: &wgpu::Texture,
    buffer: &wgpu::Buffer,
    stride: u32,
    (width, height): (u32, u32),
) {
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(stride),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
}

/// Bytes in one row of a buffer that a `width`-pixel row is copied into: `bytes_per_pixel *
/// width` padded to the 256 bytes wgpu's texture-to-buffer copies need.
pub fn padded_row(bytes_per_pixel: u32, width: u32) -> u32 {
    (bytes_per_pixel * width).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT
}

/// A buffer the GPU copies `height` rows of `stride` bytes into and the CPU maps to read.
pub fn readback_buffer(device: &wgpu::Device, label: &str, stride: u32, height: u32) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: stride as u64 * height as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    })
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    /// The depth buffer is made in one place and named by one path: no module defines a second
    /// `depth_texture` or passes this one on under its own name.
    #[test]
    fn one_depth_texture_by_one_path() {
        let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
        let mut defined = Vec::new();
        let mut passed_on = Vec::new();
        let mut dirs = vec![src.clone()];
        while let Some(dir) = dirs.pop() {
            for entry in std::fs::read_dir(&dir).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    dirs.push(path);
                    continue;
                }
                if path.extension().is_none_or(|e| e != "rs") {
                    continue;
                }
                let text = std::fs::read_to_string(&path).unwrap();
                let file = path.strip_prefix(&src).unwrap().display().to_string();
                if text.contains("fn depth_texture(") {
                    defined.push(file.clone());
                }
                // A `pub use` that names it, on one line or over a list.
                for (at, _) in text.match_indices("pub use ") {
                    let statement = text[at..].split(';').next().unwrap_or("");
                    if statement.contains("depth_texture") {
                        passed_on.push(file.clone());
                    }
                }
            }
        }
        assert_eq!(defined, ["gpu/targets.rs"], "depth_texture defined in {defined:?}");
        assert!(passed_on.is_empty(), "depth_texture passed on by {passed_on:?}");
    }
}
